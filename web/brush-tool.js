// Sculpting brushes in the browser: the pointer strokes the surface and the core's BrushStroker
// stamps along the path with dynamic topology (cpp/sculpt/brush.h). Press on the surface to
// stroke (Ctrl or Alt held at the press: inverted), anywhere else to orbit. Pen pressure scales
// the strength. [ ] change the radius, - and = the strength, Shift+wheel the radius.
//
// One wasm call per animation frame while stroking: pointer events (and their coalesced samples)
// only queue screen positions; frame() finds the surface under each of them in JS
// (surface-raycast.js) and sends them all in one brushStamp call as x, y, z, pressure.
// The snake hook drags the surface under the press along: its samples are the pointer on the view
// plane through the press point, as the core expects. Everything is in the sculpted mesh's own
// coordinates (view.ray converts the pointer).
import * as THREE from 'three';
import { BrushCursor } from './brush-cursor.js';
import { raycastSurface } from './surface-raycast.js';
import { CanvasTool, isTextInput } from './tool-events.js';
import { checkSymmetry } from './settings.js';
import { LazyPointer } from './lazy-pointer.js';
import { TouchGate } from './touch-gate.js';
// lastSamples keeps a long stroke's first samples only (it is for scripts and tests, not the stroke).
const MAX_SAMPLES_KEPT = 10000;

// The tool palette: the paper's handle grab (web/grab-tool.js), the core's seven brushes and the
// mask brush (web/mask-api.js).
// `name` is what setTool takes and, for brushes, the core's tool name. ('grab' is not a tool name:
// the handle grab is 'pull' and app.grab; the snake-hook brush was called 'grab' before, and the core
// still reads that in old session files.)
export const TOOLS = [
  { name: 'pull', label: 'Pull', key: '1', title: 'handle grab: drag the surface, R rotate, S scale' },
  { name: 'draw', label: 'Draw', key: '2', title: 'raise the surface along the stroke' },
  { name: 'inflate', label: 'Inflate', key: '3', title: 'push the surface out along its normals' },
  { name: 'smooth', label: 'Smooth', key: '4', title: 'relax bumps and creases' },
  { name: 'flatten', label: 'Flatten', key: '5', title: 'move the surface towards its mean plane' },
  { name: 'pinch', label: 'Pinch', key: '6', title: 'pull the surface towards the stroke' },
  { name: 'crease', label: 'Crease', key: '7', title: 'cut a sharp groove (inverted: a ridge)' },
  { name: 'snakeHook', label: 'Snake hook', key: '8', title: 'drag the surface under the press along' },
  { name: 'mask', label: 'Mask', key: 'm', title: 'paint a mask (Ctrl/Alt: erase); masked parts never move' },
];

export function checkTool(name) {
  if (!TOOLS.some((t) => t.name === name)) {
    const hint = name === 'grab' ? ' (the snake-hook brush is \'snakeHook\'; the handle grab is \'pull\')' : '';
    throw new Error(`setTool: unknown tool '${name}'${hint}; one of ${TOOLS.map((t) => t.name).join(', ')}`);
  }
  return name;
}

const STRENGTH_STEP = 0.05;
const RADIUS_FACTOR = 1.15;

// The programmatic strokes (sculptor.brush, app.brush). session: the embind Session; stroke: the
// sculptor's stroke life cycle {begin(kind, fn), frame(changes), end(fn)}; defaults(): {tool,
// radius (absolute), strength, symmetry} from the current settings.
export function createBrushApi({ session, stroke, defaults }) {
  const api = {
    // Settings: {tool, radius, strength, symmetry: 'x'|'y'|'z'|'off', invert, spacing, falloff, detail (an
    // absolute edge length; 0: the remesh settings)}; missing ones from the current ones.
    begin(settings = {}) {
      const s = coreSettings(settings, defaults());
      stroke.begin(s.tool, () => session.brushBegin(s));
    },
    // samples: [x, y, z, pressure, ...] (array or typed array); the whole frame in one wasm call.
    stamp(samples) {
      const ch = session.brushStamp(samples instanceof Float64Array ? samples : Float64Array.from(samples));
      stroke.frame(ch);
      return { vertices: ch.vertices, faces: ch.faces, timings: ch.timings };
    },
    end() {
      stroke.end(() => session.brushEnd());
    },
    // A whole stroke (one undo step): path [[x, y, z], ...] of surface points (the snake hook: the
    // pointer positions), pressure optional (one per point, 0..1).
    stroke({ path, pressure, ...settings } = {}) {
      if (!Array.isArray(path) || path.length === 0) throw new Error('brush.stroke: path must be a non-empty array of [x, y, z]');
      if (pressure !== undefined && (!Array.isArray(pressure) || pressure.length !== path.length)) {
        throw new Error('brush.stroke: pressure must have one value per path point');
      }
      const samples = new Float64Array(4 * path.length);
      path.forEach((p, i) => {
        const q = Array.isArray(p) ? p : [p?.x, p?.y, p?.z];
        if (q.length !== 3 || !q.every(Number.isFinite)) throw new Error(`brush.stroke: path[${i}] must be [x, y, z]`);
        samples.set([q[0], q[1], q[2], pressure ? pressure[i] : 1], 4 * i);
      });
      api.begin(settings);
      try {
        return api.stamp(samples);
      } finally {
        api.end();
      }
    },
  };
  return api;
}

// The core's brush settings from the API's (symmetry 'off' is the core's 'none').
function coreSettings(s, d) {
  const symmetry = checkSymmetry(s.symmetry ?? d.symmetry);
  const tool = s.tool ?? d.tool;
  if (tool === 'pull') throw new Error("brush: 'pull' is the handle grab (grab.begin/drag/end), not a brush");
  if (tool === 'mask') throw new Error("brush: 'mask' is the mask brush (mask.stroke/begin/stamp/end), not a brush");
  return {
    tool: checkTool(tool),
    radius: s.radius ?? d.radius,
    strength: s.strength ?? d.strength,
    symmetry: symmetry === 'off' ? 'none' : symmetry,
    ...(s.invert !== undefined ? { invert: s.invert } : {}),
    spacing: s.spacing ?? d.spacing,
    falloff: s.falloff ?? d.falloff,
    detail: s.detail ?? d.detail,
  };
}

export class BrushTool extends CanvasTool {
  // view: as GrabTool's, plus cursorParent (the sculpted mesh) and changed() (redraw).
  // core: { begin({invert, point}) -> bool (false: did not start; point: the surface under the press, for
  //         the detail in screen pixels), stamp(Float64Array), end(), busy(), stabilizer() (pixels, 0: off),
  //         radius() (absolute), scaleRadius(factor), strength(), addStrength(delta), tool(),
  //         geometry() (the drawn BufferGeometry) }
  constructor(view, core) {
    super();
    this.view = view;
    this.core = core;
    this.enabled = false;
    this.stroke = null;      // {pointerId, pending: [{x, y, pressure}], snake, plane, inverted, hit}
    this.hover = null;       // last pointer position while not stroking
    this.hoverPending = false;
    this.hoverHit = null;
    this.modifier = false;   // Ctrl/Alt held: the cursor previews the inverted brush
    this.touch = new TouchGate((hold) => view.holdTouchOrbit(hold)); // one finger strokes, two are the view's
    this.lastSamples = [];    // the last stroke's samples as sent (screen x, y), for scripts and tests
    this.cursor = new BrushCursor(view.cursorParent, view.changed);
  }

  onDisconnect() {
    this.hoverHit = null;
    this.updateCursor();
  }

  dispose() {
    this.disconnect();
    this.cursor.dispose();
  }

  get active() { return this.stroke !== null; }

  setEnabled(on) {
    this.enabled = on;
    this.hoverPending = on;
    if (!on) this.hoverHit = null;
    this.updateCursor();
  }

  onPointerDown(e) {
    if (e.pointerType === 'touch') {
      this.onTouchDown(e);
      return;
    }
    if (!this.enabled || e.button !== 0 || this.stroke || this.core.busy()) return;
    const hit = raycastSurface(this.core.geometry(), this.view.ray(e.clientX, e.clientY));
    if (!hit) return; // empty space: let OrbitControls rotate the view
    e.stopImmediatePropagation();
    e.preventDefault();
    this.beginStroke(e, hit);
  }

  // A mouse or pen press on the surface, or a finger once it moved or tapped (web/touch-gate.js).
  beginStroke(e, hit) {
    const inverted = e.ctrlKey || e.altKey;
    if (!this.core.begin({ invert: inverted, point: hit.point })) return;
    this.view.setOrbit(false);
    try {
      e.target.setPointerCapture(e.pointerId); // strokes continue outside the canvas
    } catch {
      // not a live pointer (a synthetic event): the stroke still works inside the canvas
    }
    const stabilizer = this.core.stabilizer();
    this.stroke = {
      pointerId: e.pointerId,
      pending: [sample(e)],
      snake: this.core.tool() === 'snakeHook',
      plane: this.view.viewPlane(hit.point),
      facing: this.view.viewDirection().negate(),
      inverted,
      hit,
      lazy: stabilizer > 0 ? new LazyPointer(e.clientX, e.clientY) : null,
      stabilizer,
    };
    this.lastSamples = [[e.clientX, e.clientY]];
    this.updateCursor();
  }

  // Touch (web/touch-gate.js): a finger on the model strokes once it moves (a tap: one dab); a second
  // finger ends the stroke and the two orbit and zoom.
  onTouchDown(e) {
    if (this.touch.down(e)) {
      if (this.stroke) this.finishStroke(e);
      return;
    }
    if (!this.enabled || this.stroke || this.core.busy()) return;
    const hit = raycastSurface(this.core.geometry(), this.view.ray(e.clientX, e.clientY));
    if (hit) this.touch.wait(e, hit); // off the model: one finger orbits
  }

  onPointerLeave() {
    this.hoverHit = null;
    this.updateCursor();
  }

  onPointerMove(e) {
    this.modifier = e.ctrlKey || e.altKey;
    if (!this.enabled) return;
    const press = this.touch.pending && this.touch.moved(e);
    if (press) this.beginStroke(press.down, press.hit);
    if (!this.stroke) {
      this.hover = { x: e.clientX, y: e.clientY };
      this.hoverPending = true;
      this.view.schedule();
      return;
    }
    if (e.pointerId !== this.stroke.pointerId) return;
    const events = typeof e.getCoalescedEvents === 'function' ? e.getCoalescedEvents() : [];
    const s = this.stroke;
    for (const ev of events.length ? events : [e]) {
      const q = sample(ev);
      if (s.lazy) { // the stabiliser: the brush trails the pointer on its string
        if (!s.lazy.follow(q.x, q.y, s.stabilizer)) continue;
        q.x = s.lazy.x;
        q.y = s.lazy.y;
      }
      s.pending.push(q);
      if (this.lastSamples.length < MAX_SAMPLES_KEPT) this.lastSamples.push([q.x, q.y]);
    }
    this.view.schedule();
  }

  onPointerUp(e) {
    const tap = e.pointerType === 'touch' && this.touch.up(e);
    if (tap) this.beginStroke(tap.down, tap.hit);
    if (!this.stroke || e.pointerId !== this.stroke.pointerId) return;
    this.finishStroke(e);
  }

  finishStroke(e) {
    if (this.stroke.pending.length) this.flush(); // the last motion still reaches the core
    this.stroke = null;
    this.core.end();
    this.view.setOrbit(true);
    this.hover = { x: e.clientX, y: e.clientY };
    this.hoverPending = true;
    this.view.schedule();
  }

  onWheel(e) {
    if (!this.enabled || !e.shiftKey) return;
    e.preventDefault();
    e.stopImmediatePropagation();
    this.scaleRadius(Math.sign(e.deltaY || e.deltaX) < 0 ? RADIUS_FACTOR : 1 / RADIUS_FACTOR);
  }

  onKey(e) {
    this.onModifier(e);
    if (!this.enabled || e.ctrlKey || e.metaKey || e.altKey || isTextInput(e.target)) return;
    const k = e.key;
    if (k === '[' || k === ']') this.scaleRadius(k === ']' ? RADIUS_FACTOR : 1 / RADIUS_FACTOR);
    else if (k === '-' || k === '_') this.addStrength(-STRENGTH_STEP);
    else if (k === '=' || k === '+') this.addStrength(STRENGTH_STEP);
    else return;
    e.preventDefault();
  }

  onKeyUp(e) { this.onModifier(e); }

  onModifier(e) {
    const held = e.ctrlKey || e.altKey;
    if (held !== this.modifier) {
      this.modifier = held;
      this.updateCursor();
    }
  }

  scaleRadius(f) {
    this.core.scaleRadius(f);
    this.updateCursor();
  }

  addStrength(d) {
    this.core.addStrength(d);
    this.updateCursor();
  }

  // Once per animation frame: at most one wasm call (the stroke's samples), hover costs none.
  frame() {
    if (this.stroke) {
      if (this.stroke.pending.length) this.flush();
    } else if (this.enabled && this.hoverPending && this.hover && this.pointerInside) {
      this.hoverPending = false;
      this.hoverHit = this.core.busy() ? null : raycastSurface(this.core.geometry(), this.view.ray(this.hover.x, this.hover.y));
      this.updateCursor();
    }
  }

  // The queued samples as surface points (the snake hook: points on its view plane), in one call.
  // The full raycast walks every triangle (about 3 ms on 120k), so it runs once per frame, for the
  // last sample; the coalesced ones before it, a few pixels apart, go on the tangent plane of the
  // previous hit (the core projects every sample onto the surface near the previous stamp anyway).
  flush() {
    const s = this.stroke;
    const out = [];
    const last = s.pending.length - 1;
    s.pending.forEach((q, i) => {
      const ray = this.view.ray(q.x, q.y);
      const hit = s.snake ? planeHit(ray, s.plane, s.facing)
        : (i < last && this.nearHit(ray, s.hit)) || raycastSurface(this.core.geometry(), ray);
      if (!hit) return; // off the surface: the stroke resumes where the pointer comes back
      out.push(hit.point.x, hit.point.y, hit.point.z, q.pressure);
      s.hit = hit;
    });
    s.pending.length = 0;
    if (out.length) this.core.stamp(new Float64Array(out));
    this.updateCursor();
  }

  // The ray on the tangent plane of `prev`, if that is within half a brush radius of it.
  nearHit(ray, prev) {
    const hit = planeHit(ray, new THREE.Plane().setFromNormalAndCoplanarPoint(prev.normal, prev.point), prev.normal);
    return hit && hit.point.distanceTo(prev.point) < 0.5 * this.core.radius() ? hit : null;
  }

  updateCursor() {
    const hit = this.stroke ? this.stroke.hit : this.pointerInside ? this.hoverHit : null;
    if (!this.enabled || !hit) {
      this.cursor.show(null);
      return;
    }
    const inverted = this.stroke ? this.stroke.inverted : this.modifier;
    this.cursor.show(hit.point, hit.normal, this.core.radius(), this.core.strength(), inverted);
  }
}

// A pointer sample; a mouse reports pressure 0.5 while pressed, so only a pen's counts.
function sample(e) {
  const pressure = e.pointerType === 'pen' ? clamp(e.pressure, 0, 1) : 1;
  return { x: e.clientX, y: e.clientY, pressure };
}

function planeHit(ray, plane, facing) {
  const point = ray.intersectPlane(plane, new THREE.Vector3());
  return point ? { point, normal: facing } : null;
}


function clamp(x, lo, hi) { return Math.min(hi, Math.max(lo, x)); }
