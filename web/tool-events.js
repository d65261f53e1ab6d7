// The DOM events a canvas tool (GrabTool, BrushTool) listens to, in one place: pointer down (capture
// phase, so a press on the model can keep OrbitControls from seeing it), move, up/cancel, enter and
// leave on the canvas, the wheel (capture, not passive: the tool may take it from the zoom), and keys
// on the key target (none when it is null). The tool provides onPointerDown, onPointerMove, onPointerUp,
// onPointerLeave, onWheel, onKey and optionally onKeyUp; enter sets tool.pointerInside.
// Returns a function that removes them all.
export function bindToolEvents(tool, canvas, keyTarget) {
  const listeners = [
    [canvas, 'pointerdown', (e) => tool.onPointerDown(e), { capture: true }],
    [canvas, 'pointermove', (e) => tool.onPointerMove(e)],
    [canvas, 'pointerup', (e) => tool.onPointerUp(e)],
    [canvas, 'pointercancel', (e) => tool.onPointerUp(e)],
    [canvas, 'pointerenter', () => { tool.pointerInside = true; }],
    [canvas, 'pointerleave', () => { tool.pointerInside = false; tool.onPointerLeave(); }],
    [canvas, 'wheel', (e) => tool.onWheel(e), { capture: true, passive: false }],
  ];
  if (keyTarget) listeners.push([keyTarget, 'keydown', (e) => tool.onKey(e)]);
  if (keyTarget && tool.onKeyUp) listeners.push([keyTarget, 'keyup', (e) => tool.onKeyUp(e)]);
  for (const [t, type, fn, opt] of listeners) t.addEventListener(type, fn, opt);
  return () => {
    for (const [t, type, fn, opt] of listeners) t.removeEventListener(type, fn, opt);
  };
}

// The base of GrabTool and BrushTool: connect(canvas, keyTarget) listens until disconnect();
// onDisconnect() lets a tool forget its hover state.
export class CanvasTool {
  constructor() {
    this.unbind = null;
    this.pointerInside = false;
  }

  connect(canvas, keyTarget) {
    this.disconnect();
    this.unbind = bindToolEvents(this, canvas, keyTarget);
  }

  disconnect() {
    if (this.unbind) this.unbind();
    this.unbind = null;
    this.pointerInside = false;
    this.onDisconnect();
  }

  onDisconnect() {}
}

// Keys typed into a form field (the panel's number inputs) are not shortcuts.
export function isTextInput(t) {
  return t && (t.tagName === 'INPUT' || t.tagName === 'TEXTAREA' || t.tagName === 'SELECT' || t.isContentEditable);
}
