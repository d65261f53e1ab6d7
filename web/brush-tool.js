// Sculpting brushes in the browser: the pointer strokes the surface and the core's BrushStroker
// stamps along the path with dynamic topology (cpp/sculpt/brush.h). Press on the surface to
// stroke (Ctrl or Alt held at the press: inverted), anywhere else to orbit. Pen pressure scales
// the strength. [ ] change the radius, - and = the strength, Shift+wheel the radius.
//
// One wasm call per animation frame while stroking: pointer events (and their coalesced samples)
// only queue screen positions; frame() finds the surface under each of them in JS
// (surface-raycast.js) and sends them all in one brushStamp call as x, y, z, pressure.
// The grab brush ("snake hook") drags the surface under the press along: its samples are the
// pointer on the view plane through the press point, as the core expects.
import * as THREE from 'three';
import { BrushCursor } from './brush-cursor.js';
import { raycastSurface } from './surface-raycast.js';
import { bindToolEvents, isTextInput } from './tool-events.js';

// The tool palette: the paper's handle grab (web/grab-tool.js) and the core's seven brushes.
// `name` is what app.setTool takes and, for brushes, the core's tool name.
export const TOOLS = [
  { name: 'pull', label: 'Pull', key: '1', title: 'handle grab: drag the surface, R rotate, S scale' },
  { name: 'draw', label: 'Draw', key: '2', title: 'raise the surface along the stroke' },
  { name: 'inflate', label: 'Inflate', key: '3', title: 'push the surface out along its normals' },
  { name: 'smooth', label: 'Smooth', key: '4', title: 'relax bumps and creases' },
  { name: 'flatten', label: 'Flatten', key: '5', title: 'move the surface towards its mean plane' },
  { name: 'pinch', label: 'Pinch', key: '6', title: 'pull the surface towards the stroke' },
  { name: 'crease', label: 'Crease', key: '7', title: 'cut a sharp groove (inverted: a ridge)' },
  { name: 'grab', label: 'Snake hook', key: '8', title: 'grab brush: drag the surface under the press along' },
];
export const SYMMETRY = ['x', 'y', 'z', 'off'];
// The brush part of the app state (radius in percent of the diagonal, like the panel's lengths).
// detailPixels > 0: strokes remesh to edges of that many screen pixels at the brush (the detail
// follows the view, Blender's relative detail) instead of the remesh settings (epsilon, lengths).
export const BRUSH_STATE = { tool: 'pull', brushRadius: 5, brushStrength: 0.5, symmetry: 'x', detailPixels: 0 };

// setParams keys of the brushes besides brushRadius (a length, handled with the grab radii): checked values.
export const BRUSH_PARAMS = {
  brushStrength(v) {
    if (typeof v !== 'number' || !(v >= 0 && v <= 1)) throw new Error('setParams: brushStrength must be a number between 0 and 1');
    return v;
  },
  detailPixels(v) {
    if (typeof v !== 'number' || !(v >= 0 && v <= 100)) throw new Error('setParams: detailPixels must be a number between 0 (off) and 100');
    return v;
  },
  symmetry(v) {
    const s = v === 'none' ? 'off' : v;
    if (!SYMMETRY.includes(s)) throw new Error(`setParams: symmetry must be one of ${SYMMETRY.join(', ')}`);
    return s;
  },
};

const STRENGTH_STEP = 0.05;
const RADIUS_FACTOR = 1.15;

// The page API's `brush` (app.brush). session: the embind Session; applyChanges(changes): copies a
// frame's changes into three.js; afterStroke(): the stroke ended; defaults():
// {tool, radius (absolute), strength, symmetry} from the panel.
export function createBrushApi({ session, applyChanges, afterStroke, defaults }) {
  const api = {
    // Settings: {tool, radius, strength, symmetry: 'x'|'y'|'z'|'off', invert, spacing, detail (an edge length for
    // this stroke), pixelSize (the world size of a screen pixel at the brush: with the panel's detailPixels, the
    // stroke's detail)}; missing ones from the panel.
    begin(settings = {}) {
      session.brushBegin(coreSettings(settings, defaults()));
    },
    // samples: [x, y, z, pressure, ...] (array or typed array); the whole frame in one wasm call.
    stamp(samples) {
      const ch = session.brushStamp(samples instanceof Float64Array ? samples : Float64Array.from(samples));
      applyChanges(ch);
      return { vertices: ch.vertices, faces: ch.faces, timings: ch.timings };
    },
    end() {
      session.brushEnd();
      afterStroke();
    },
    // A whole stroke (one undo step): path [[x, y, z], ...] of surface points (the grab brush: the
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
  const symmetry = s.symmetry ?? d.symmetry;
  return {
    tool: s.tool ?? d.tool,
    radius: s.radius ?? d.radius,
    strength: s.strength ?? d.strength,
    symmetry: symmetry === 'off' || symmetry === false || symmetry === null ? 'none' : symmetry,
    ...(s.invert !== undefined ? { invert: s.invert } : {}),
    ...(s.spacing !== undefined ? { spacing: s.spacing } : {}),
    ...(detailLength(s, d) > 0 ? { detail: detailLength(s, d) } : {}),
  };
}

// The stroke's own edge length: given, or the panel's detail in pixels times a pixel's size at the brush.
function detailLength(s, d) {
  if (s.detail !== undefined) return s.detail;
  return d.detailPixels > 0 && s.pixelSize > 0 ? d.detailPixels * s.pixelSize : 0;
}

export class BrushTool {
  // core: { begin({invert}) -> bool (false: did not start), stamp(Float64Array), end(), busy(),
  //         radius() (absolute), geometry() (the drawn BufferGeometry), changed() (state edited by keys) }
  // state: the app state (tool, brushRadius, brushStrength, symmetry).
  constructor(viewer, core, keyTarget, state) {
    this.viewer = viewer;
    this.core = core;
    this.state = state;
    this.enabled = false;
    this.stroke = null;      // {pointerId, pending: [{x, y, pressure}], snake, plane, inverted, hit}
    this.hover = null;       // last pointer position while not stroking
    this.hoverPending = false;
    this.hoverHit = null;
    this.pointerInside = false;
    this.modifier = false;   // Ctrl/Alt held: the cursor previews the inverted brush
    this.cursor = new BrushCursor(viewer);
    this.unbind = bindToolEvents(this, viewer.renderer.domElement, keyTarget);
  }

  dispose() {
    this.unbind();
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
    if (!this.enabled || e.button !== 0 || this.stroke || this.core.busy()) return;
    const hit = raycastSurface(this.core.geometry(), this.viewer.ray(e.clientX, e.clientY));
    if (!hit) return; // empty space: let OrbitControls rotate the view
    e.stopImmediatePropagation();
    e.preventDefault();
    const inverted = e.ctrlKey || e.altKey;
    if (!this.core.begin({ invert: inverted, pixelSize: pixelSizeAt(this.viewer, hit.point) })) return;
    this.viewer.controls.enabled = false;
    try {
      e.target.setPointerCapture(e.pointerId); // strokes continue outside the canvas
    } catch {
      // not a live pointer (a synthetic event): the stroke still works inside the canvas
    }
    const viewDir = this.viewer.camera.getWorldDirection(new THREE.Vector3());
    this.stroke = {
      pointerId: e.pointerId,
      pending: [sample(e)],
      snake: this.state.tool === 'grab',
      plane: new THREE.Plane().setFromNormalAndCoplanarPoint(viewDir, hit.point),
      facing: viewDir.clone().negate(),
      inverted,
      hit,
    };
    this.updateCursor();
  }

  onPointerLeave() {
    this.hoverHit = null;
    this.updateCursor();
  }

  onPointerMove(e) {
    this.modifier = e.ctrlKey || e.altKey;
    if (!this.enabled) return;
    if (!this.stroke) {
      this.hover = { x: e.clientX, y: e.clientY };
      this.hoverPending = true;
      return;
    }
    if (e.pointerId !== this.stroke.pointerId) return;
    const events = typeof e.getCoalescedEvents === 'function' ? e.getCoalescedEvents() : [];
    for (const ev of events.length ? events : [e]) this.stroke.pending.push(sample(ev));
  }

  onPointerUp(e) {
    if (!this.stroke || e.pointerId !== this.stroke.pointerId) return;
    if (this.stroke.pending.length) this.flush(); // the last motion still reaches the core
    this.stroke = null;
    this.core.end();
    this.viewer.controls.enabled = true;
    this.hover = { x: e.clientX, y: e.clientY };
    this.hoverPending = true;
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
    this.state.brushRadius = round(clamp(this.state.brushRadius * f, 0.5, 30), 3);
    this.core.changed();
    this.updateCursor();
  }

  addStrength(d) {
    this.state.brushStrength = round(clamp(this.state.brushStrength + d, 0.05, 1), 3);
    this.core.changed();
    this.updateCursor();
  }

  // Once per animation frame: at most one wasm call (the stroke's samples), hover costs none.
  frame() {
    if (this.stroke) {
      if (this.stroke.pending.length) this.flush();
    } else if (this.enabled && this.hoverPending && this.hover && this.pointerInside) {
      this.hoverPending = false;
      this.hoverHit = this.core.busy() ? null : raycastSurface(this.core.geometry(), this.viewer.ray(this.hover.x, this.hover.y));
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
      const ray = this.viewer.ray(q.x, q.y);
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
    this.cursor.show(hit.point, hit.normal, this.core.radius(), this.state.brushStrength, inverted);
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
function round(x, digits) { return Number(x.toFixed(digits)); }

// The world size of one screen pixel at `point` (perspective: grows with the distance; orthographic:
// the same everywhere).
function pixelSizeAt(viewer, point) {
  const camera = viewer.camera;
  const height = viewer.renderer.domElement.clientHeight || 1;
  if (camera.isOrthographicCamera) return (camera.top - camera.bottom) / camera.zoom / height;
  const distance = camera.position.distanceTo(point);
  return (2 * distance * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2)) / camera.zoom / height;
}
