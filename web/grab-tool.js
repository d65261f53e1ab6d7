// The grab tool: press on the surface to take a handle there, drag to move it in the view plane.
// While dragging: R rotates (about the view axis, by horizontal mouse motion), S scales, G goes
// back to moving; the wheel scales. Not on the surface (or other buttons): the orbit controls act.
// Radii: [ and ] resize the region of interest, { and } (with Shift) the handle; Shift+wheel too.
//
// Pointer events only record the wanted transform; frame() (called once per animation frame by
// AdaptiveSculptor) sends it to the core: at most one wasm call per frame however many events arrive.
// Everything here is in the sculpted mesh's own coordinates (view.ray and view.viewPlane convert).
import * as THREE from 'three';
import { CanvasTool, isTextInput } from './tool-events.js';
import { TouchGate } from './touch-gate.js';

export class GrabTool extends CanvasTool {
  // view: { ray(clientX, clientY), viewDirection(), viewPlane(point), setOrbit(on), holdTouchOrbit(hold),
  //         showGrab({center, handleRadius, roiRadius, visible}), schedule() (a frame() is due) }
  // core: { pick(ray) -> THREE.Vector3|null, begin(center), drag(transform) -> {timings}|undefined, end(), notify(message), radii(),
  //         scaleRadii(handleFactor, roiFactor), busy() }
  constructor(view, core) {
    super();
    this.view = view;
    this.core = core;
    this.grab = null;   // {center, plane, start, mode, translate, degrees, scale, modeX, ...}
    this.enabled = true; // false while a brush is the current tool (tool-palette.js)
    this.dirty = false;
    this.hover = null;  // last pointer position for the hover preview
    this.hoverPending = false;
    this.hoverPoint = null;
    this.touch = new TouchGate((hold) => view.holdTouchOrbit(hold)); // one finger pulls, two are the view's
  }

  onDisconnect() {
    this.hover = null;
  }

  get active() { return this.grab !== null; }

  setEnabled(on) {
    this.enabled = on;
    this.hoverPending = on;
    this.updateBrush();
  }

  onPointerDown(e) {
    if (e.pointerType === 'touch') {
      this.onTouchDown(e);
      return;
    }
    if (!this.enabled || e.button !== 0 || this.grab || this.core.busy()) return;
    const hit = this.core.pick(this.view.ray(e.clientX, e.clientY));
    if (!hit) return; // empty space: let OrbitControls rotate the view
    e.stopImmediatePropagation();
    e.preventDefault();
    this.beginGrab(e, hit);
  }

  // Touch (web/touch-gate.js): a finger on the model takes the handle once it moves; a second finger
  // ends the grab and the two orbit and zoom.
  onTouchDown(e) {
    if (this.touch.down(e)) {
      if (this.grab) this.endGrab(e);
      return;
    }
    if (!this.enabled || this.grab || this.core.busy()) return;
    const hit = this.core.pick(this.view.ray(e.clientX, e.clientY));
    if (hit) this.touch.wait(e, hit); // off the model: one finger orbits
  }

  // A press on the surface at `hit` (the mouse's, or a finger's once it moved).
  beginGrab(e, hit) {
    this.view.setOrbit(false);
    try {
      e.target.setPointerCapture(e.pointerId); // the drag continues outside the canvas
    } catch {
      // not a live pointer (a synthetic event): the drag still works inside the canvas
    }
    this.grab = {
      pointerId: e.pointerId,
      center: hit.clone(),
      plane: this.view.viewPlane(hit),
      mode: 'translate',
      translate: new THREE.Vector3(),
      offset: new THREE.Vector3(), // translation frozen while rotating/scaling
      degrees: 0, scale: 1, cappedShown: false,
      modeX: e.clientX, modeStartValue: 0,
      x: e.clientX, y: e.clientY,
    };
    this.core.begin(hit);
    this.dirty = false;
    this.updateBrush();
  }

  onPointerLeave() {
    this.hover = null;
    this.updateBrush();
  }

  onPointerMove(e) {
    const press = this.touch.pending && this.touch.moved(e);
    if (press) this.beginGrab(press.down, press.hit);
    if (!this.grab) {
      this.hover = { x: e.clientX, y: e.clientY };
      this.hoverPending = true;
      if (this.enabled) this.view.schedule();
      return;
    }
    if (e.pointerId !== this.grab.pointerId) return;
    this.grab.x = e.clientX;
    this.grab.y = e.clientY;
    this.updateTransform();
  }

  updateTransform() {
    const g = this.grab;
    const dx = g.x - g.modeX;
    if (g.mode === 'translate') {
      const p = this.view.ray(g.x, g.y).intersectPlane(g.plane, new THREE.Vector3());
      if (p) g.translate.copy(p).sub(g.center).sub(g.offset);
    } else if (g.mode === 'rotate') {
      g.degrees = g.modeStartValue + dx * 0.5;
    } else if (g.mode === 'scale') {
      g.scale = g.modeStartValue * Math.exp(dx / 200);
    }
    this.dirty = true;
    this.view.schedule();
  }

  setMode(mode) {
    const g = this.grab;
    if (!g || g.mode === mode) return;
    if (g.mode === 'translate') g.offset.set(0, 0, 0);
    // The new mode starts from the current pointer position and the current value.
    g.mode = mode;
    g.modeX = g.x;
    g.modeStartValue = mode === 'rotate' ? g.degrees : mode === 'scale' ? g.scale : 0;
    if (mode === 'translate') {
      // Continue moving from where the handle is: the ray now hits the plane elsewhere.
      const p = this.view.ray(g.x, g.y).intersectPlane(g.plane, new THREE.Vector3());
      if (p) g.offset.copy(p).sub(g.center).sub(g.translate);
    }
  }

  onPointerUp(e) {
    if (e.pointerType === 'touch') this.touch.up(e); // a tap takes no handle: a pull needs a drag
    if (!this.grab || e.pointerId !== this.grab.pointerId) return;
    this.endGrab(e);
  }

  endGrab(e) {
    if (this.dirty) this.frame(); // the last motion still reaches the core
    this.grab = null;
    this.core.end();
    this.view.setOrbit(true);
    this.hover = { x: e.clientX, y: e.clientY };
    this.hoverPending = true;
    this.view.schedule();
  }

  onWheel(e) {
    if (!this.enabled) return;
    if (this.grab) {
      e.preventDefault();
      e.stopImmediatePropagation();
      if (this.grab.mode !== 'scale') this.grab.scale *= Math.exp(-e.deltaY * 0.001);
      else this.grab.modeStartValue *= Math.exp(-e.deltaY * 0.001);
      this.updateTransform();
    } else if (e.shiftKey) {
      e.preventDefault();
      e.stopImmediatePropagation();
      const f = Math.exp(-Math.sign(e.deltaY || e.deltaX) * 0.1);
      this.core.scaleRadii(f, f);
      this.updateBrush();
    }
  }

  onKey(e) {
    if (!this.enabled || e.ctrlKey || e.metaKey || e.altKey || isTextInput(e.target)) return;
    const k = e.key;
    if (this.grab && (k === 'r' || k === 'R')) this.setMode('rotate');
    else if (this.grab && (k === 's' || k === 'S')) this.setMode('scale');
    else if (this.grab && (k === 'g' || k === 'G' || k === 't' || k === 'T')) this.setMode('translate');
    else if (k === '[' || k === ']') this.core.scaleRadii(1, k === ']' ? 1.15 : 1 / 1.15);
    else if (k === '{' || k === '}') this.core.scaleRadii(k === '}' ? 1.15 : 1 / 1.15, 1);
    else return;
    e.preventDefault();
    this.updateBrush();
  }

  // The transform since grab begin, in the page API's terms.
  transform() {
    const g = this.grab;
    const axis = this.view.viewDirection().negate();
    return { translate: g.translate.toArray(), rotate: { axis: axis.toArray(), degrees: g.degrees }, scale: g.scale };
  }

  // Once per animation frame.
  frame() {
    if (this.grab) {
      if (this.dirty) {
        this.dirty = false;
        const t = this.core.drag(this.transform())?.timings;
        // The core cut the region of interest to its vertex budget: say so once per grab.
        if (t?.roiCapped && !this.grab.cappedShown) {
          this.grab.cappedShown = true;
          this.core.notify?.(`Region of interest limited to ${t.roiVertices} vertices (smaller than asked) to keep dragging fluid`);
        }
        this.updateBrush();
      }
    } else if (this.enabled && this.hoverPending && this.hover && this.pointerInside && !this.core.busy()) {
      this.hoverPending = false;
      this.hoverPoint = this.core.pick(this.view.ray(this.hover.x, this.hover.y));
      this.updateBrush();
    }
  }

  updateBrush() {
    const { handle, roi } = this.core.radii();
    if (this.grab) {
      const c = this.grab.center.clone().add(this.grab.translate);
      this.view.showGrab({ center: c, handleRadius: handle, roiRadius: roi, visible: true });
    } else {
      const visible = !!(this.enabled && this.hover && this.hoverPoint);
      this.view.showGrab({ center: this.hoverPoint || undefined, handleRadius: handle, roiRadius: roi, visible });
    }
  }
}
