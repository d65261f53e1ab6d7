// The stroke stabiliser ("lazy mouse", as in SculptGL, Krita and Blender): the brush hangs on a string
// of `length` screen pixels behind the pointer. While the pointer moves within the string's reach the
// brush stays put; beyond it the brush is pulled along the line towards the pointer until the string
// is taut again. A jittery or zig-zag hand then gives a calm path whose corners are cut by up to the
// string's length. Screen space, so the feel does not depend on the zoom.
export class LazyPointer {
  constructor(x, y) {
    this.x = x;
    this.y = y;
  }

  // The pointer moved to (px, py): true when the brush moved (to this.x, this.y), false when the
  // pointer is still within the string's reach.
  follow(px, py, length) {
    const dx = px - this.x, dy = py - this.y;
    const d = Math.hypot(dx, dy);
    if (d <= length) return false;
    const t = (d - length) / d;
    this.x += dx * t;
    this.y += dy * t;
    return true;
  }
}
