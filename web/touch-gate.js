// Touch for the canvas tools (BrushTool, GrabTool): one finger on the model uses the tool, one finger
// off it orbits, two fingers orbit and pinch-zoom (OrbitControls). OrbitControls must see every
// finger's pointerdown to track a two-finger gesture, so a finger's press is never swallowed: a finger
// on the model waits (OrbitControls' one-finger orbit held off meanwhile) and becomes the tool's press
// once it moves TOUCH_SLOP_PX, or on lifting (a tap); a second finger before that cancels it, and a
// second finger during the tool's drag tells the tool to end it.

// How far (CSS pixels) a finger moves before its press is the tool's: the two fingers of a pinch or
// an orbit land a few milliseconds apart, long before either moved this far.
export const TOUCH_SLOP_PX = 6;

export class TouchGate {
  // holdOrbit(true|false): hold off / restore OrbitControls' one-finger action (view.holdTouchOrbit).
  constructor(holdOrbit) {
    this.holdOrbit = holdOrbit;
    this.fingers = new Set(); // touch pointers down on the canvas
    this.pending = null;      // the finger on the model that has not moved yet: {pointerId, x, y, hit}
  }

  // A finger went down; true when it is a further finger (the gesture is the view's: the caller ends
  // its drag, if any).
  down(e) {
    // The first finger of a new touch: fingers lifted outside the canvas (no pointerup here) are gone.
    if (e.isPrimary) this.fingers.clear();
    this.fingers.add(e.pointerId);
    if (this.fingers.size === 1) return false;
    this.pending = null;
    return true;
  }

  // The first finger landed on the model at `hit`: the tool's press if it moves or taps.
  wait(e, hit) {
    this.holdOrbit(true);
    this.pending = { pointerId: e.pointerId, x: e.clientX, y: e.clientY, hit };
  }

  // A pointer moved: {down, hit} (the press at the landing point) once the waiting finger moved far
  // enough, else null.
  moved(e) {
    const p = this.pending;
    if (!p || e.pointerId !== p.pointerId || Math.hypot(e.clientX - p.x, e.clientY - p.y) < TOUCH_SLOP_PX) return null;
    this.pending = null;
    const down = { clientX: p.x, clientY: p.y, pointerId: p.pointerId, pointerType: 'touch', pressure: 1, button: 0,
      ctrlKey: false, altKey: false, target: e.target };
    return { down, hit: p.hit };
  }

  // A finger went up (or was cancelled): {down, hit} when the waiting finger tapped, else null.
  up(e) {
    this.fingers.delete(e.pointerId);
    const p = this.pending;
    let tap = null;
    if (p && p.pointerId === e.pointerId) {
      this.pending = null;
      if (e.type === 'pointerup') tap = { down: e, hit: p.hit }; // a cancel is not a tap
    }
    if (this.fingers.size === 0) this.holdOrbit(false);
    return tap;
  }
}
