// AdaptiveSculptor: sculpt the host's own THREE.Mesh in the host's own scene, with the core's adaptive
// remeshing (Dunyach et al. 2013) under every stroke. A three.js addon in the style of the
// examples' controls: it listens to pointer events on a canvas, changes the mesh's BufferGeometry
// in place and dispatches events; the host keeps its renderer, camera, lights and render loop.
//
//   const sculptor = await AdaptiveSculptor.create(mesh, camera, { tool: 'draw', radius: '5%' });
//   sculptor.connect(renderer.domElement);
//   sculptor.addEventListener('change', render);   // or render every frame anyway
//   sculptor.addEventListener('end', (e) => console.log(e.timings));
//
// The whole API is declared (and documented) in web/adasculpt.d.ts.
//
// Coordinates: the core works in the mesh's own (local) coordinates; pointer rays are carried
// there through mesh.matrixWorld, so lengths (radius, epsilon, ...) are in the geometry's units and
// "x%" means percent of the geometry's bounding-box diagonal.
//
// Frames: pointer events only queue samples; update() sends a frame's samples to the core in one
// wasm call. The sculptor calls update() itself on the next animation frame whenever something is
// pending; a host (like createSculptApp) may call it first in its own frame, before rendering.
import * as THREE from 'three';
import { mergeVertices } from 'three/addons/utils/BufferGeometryUtils.js';
import { instantiateCore } from './wasm-module.js';
import { MeshBuffers } from './mesh-buffers.js';
import { GrabTool } from './grab-tool.js';
import { BrushTool, checkTool, createBrushApi } from './brush-tool.js';
import { BrushCursor } from './brush-cursor.js';
import { createMaskApi } from './mask-api.js';
import { raycastSurface } from './surface-raycast.js';
import {
  TOOL_DEFAULTS, RADIUS_RANGE_PCT, ROI_RANGE_PCT, lengthToPercent, checkStrength, checkSymmetry,
} from './settings.js';
import { FEEL_DEFAULTS, FEEL_KEYS, checkFeel, detailLength } from './brush-feel.js';

const CORE_KEYS = ['epsilon', 'minLength', 'maxLength', 'features', 'guardCrossings'];
const TOOL_KEYS = ['tool', 'radius', 'strength', 'symmetry', 'handleRadius', 'roiRadius'];
const STROKE_LOG_MAX = 100000;

export class AdaptiveSculptor extends THREE.EventDispatcher {
  // mesh: a THREE.Mesh with its own (indexed or not) BufferGeometry; camera: the camera the pointer
  // looks through. Options: wasmUrl, epsilon, minLength, maxLength, features, guardCrossings, tool, radius,
  // strength, symmetry, handleRadius, roiRadius, keyTarget (keyboard shortcuts), controls (disabled
  // during a stroke), wireframe (keep a wireframe geometry too), grabPreview, module.
  static async create(mesh, camera, options = {}) {
    if (!mesh || !mesh.isMesh || !mesh.geometry) throw new Error('AdaptiveSculptor.create: expected a THREE.Mesh');
    if (!camera || !camera.isCamera) throw new Error('AdaptiveSculptor.create: expected a THREE.Camera');
    const Module = options.module || await instantiateCore(options.wasmUrl);
    const sculptor = new AdaptiveSculptor(mesh, camera, Module, options);
    try {
      if (mesh.geometry.attributes.position) sculptor.loadGeometry(mesh.geometry);
      sculptor.setParams(pick(options, [...CORE_KEYS, ...TOOL_KEYS, ...FEEL_KEYS]));
    } catch (e) {
      sculptor.dispose();
      throw e;
    }
    return sculptor;
  }

  constructor(mesh, camera, Module, options = {}) {
    super();
    this.mesh = mesh;
    this.camera = camera;
    this.module = Module;
    this.session = new Module.Session();
    this.controls = options.controls || null;
    this.keyTarget = options.keyTarget || null;
    this.domElement = null;
    this.enabled = true;
    this.buffers = new MeshBuffers(Module, mesh.geometry, { lines: !!options.wireframe });
    this._tool = checkTool(options.tool ?? TOOL_DEFAULTS.tool);
    this._pct = {}; // tool lengths in percent of the diagonal (they follow the mesh's size)
    this._strength = TOOL_DEFAULTS.strength;
    this._symmetry = TOOL_DEFAULTS.symmetry;
    this._diagonal = 1;
    this._busy = null;        // {done, total} while a whole-mesh remesh runs
    this._stroke = null;      // the stroke (grab or brush) in progress: kind, timings
    this._scheduled = 0;
    this._disposed = false;
    this._inverse = new THREE.Matrix4();
    this._raycaster = new THREE.Raycaster();
    this._ndc = new THREE.Vector2();
    for (const k of ['radius', 'handleRadius', 'roiRadius']) this._pct[k] = lengthToPercent(TOOL_DEFAULTS[k], 1, k);
    // Falloff, spacing, stabiliser, detail mode and sizes (web/brush-feel.js); constantDetail in percent.
    this._feel = { ...FEEL_DEFAULTS, constantDetail: lengthToPercent(FEEL_DEFAULTS.constantDetail, 1, 'constantDetail') };
    this._touchOrbit = null;  // OrbitControls' one-finger action while a finger rests on the model

    const sculptor = this;
    const view = {
      ray: (x, y) => this._ray(x, y),
      viewDirection: () => this._viewDirection(),
      viewPlane: (p) => this._viewPlane(p),
      setOrbit: (on) => { if (this.controls) this.controls.enabled = on; },
      holdTouchOrbit: (hold) => this._holdTouchOrbit(hold),
      schedule: () => this._schedule(),
      changed: () => this.dispatchEvent({ type: 'change' }),
      cursorParent: mesh,
      showGrab: options.grabPreview || ((g) => this._showGrab(g)),
    };
    this._view = view;
    const guard = (fn) => (...args) => this._guard(() => fn(...args));
    this.grabTool = new GrabTool(view, {
      pick: (ray) => this._pick(ray),
      begin: guard((center) => this.grab.begin({ center })),
      drag: guard((t) => this.grab.drag(t)),
      notify: (message) => this.dispatchEvent({ type: 'notice', message }),
      end: guard(() => this.grab.end()),
      radii: () => ({ handle: this.handleRadius, roi: this.roiRadius }),
      scaleRadii: (fh, fr) => {
        const p = this._pct;
        p.roiRadius = round(clamp(p.roiRadius * fr, ...ROI_RANGE_PCT));
        p.handleRadius = round(clamp(p.handleRadius * fh, RADIUS_RANGE_PCT[0], Math.min(RADIUS_RANGE_PCT[1], p.roiRadius * 0.9)));
        this.dispatchEvent({ type: 'params' });
      },
      busy: () => this.busy || !this.session.hasMesh(),
    });
    // The mask brush is the same pointer tool: Ctrl/Alt erase instead of invert, points without pressure.
    const masking = () => this._tool === 'mask';
    this.brushTool = new BrushTool(view, {
      begin: ({ invert, point }) => this._guard(() => {
        if (masking()) this.mask.begin({ erase: invert });
        else this.brush.begin({ invert, detail: this.detailLength(point) });
        return true;
      }) === true,
      stabilizer: () => this._feel.stabilizer,
      stamp: guard((samples) => (masking() ? this.mask.stamp(withoutPressure(samples)) : this.brush.stamp(samples))),
      end: guard(() => (masking() ? this.mask.end() : this.brush.end())),
      busy: () => this.busy, // no wasm call: without a mesh there is no geometry to hit
      radius: () => this.radius,
      scaleRadius: (f) => {
        this._pct.radius = round(clamp(this._pct.radius * f, ...RADIUS_RANGE_PCT));
        this.dispatchEvent({ type: 'params' });
      },
      strength: () => this._strength,
      addStrength: (d) => {
        this._strength = round(clamp(this._strength + d, 0.05, 1));
        this.dispatchEvent({ type: 'params' });
      },
      tool: () => this._tool,
      geometry: () => (this.buffers.allocated ? this.buffers.geometry : null),
    });
    this.grabTool.setEnabled(this._tool === 'pull');
    this.brushTool.setEnabled(this._tool !== 'pull');

    // The stroke life cycle shared by the pointer and the programmatic API: start, change per
    // frame, end (with the stroke's timings); a throwing begin leaves no stroke behind.
    const stroke = {
      begin(kind, call) {
        call();
        sculptor._stroke = { kind, t0: performance.now(), frames: [], stamps: 0 };
        sculptor._sync();
        sculptor.dispatchEvent({ type: 'start', tool: kind });
      },
      frame(ch) {
        const s = sculptor._stroke;
        if (s && s.frames.length < STROKE_LOG_MAX) {
          s.frames.push(ch.timings.total + ch.timings.buffers);
          s.stamps += ch.timings.stamps;
        }
        sculptor._sync(ch);
      },
      end(call) {
        const s = sculptor._stroke;
        sculptor._stroke = null;
        call();
        sculptor._sync();
        sculptor.buffers.updateBounds();
        if (s) sculptor.dispatchEvent({ type: 'end', tool: s.kind, timings: strokeTimings(s), ...sculptor._counts() });
      },
    };

    // Programmatic strokes, the same path as the pointer's (one undo step each).
    this.grab = {
      // center: snapped to the closest surface point; radii absolute, default the current ones.
      begin({ center, handleRadius, roiRadius } = {}) {
        const c = toVec3(center, 'center');
        stroke.begin('pull', () => sculptor.session.grabBegin(c.x, c.y, c.z,
          handleRadius ?? sculptor.handleRadius, roiRadius ?? sculptor.roiRadius));
      },
      // The total transform since begin; one frame of deformation and local remeshing.
      drag({ translate = [0, 0, 0], rotate = { axis: [0, 0, 1], degrees: 0 }, scale = 1 } = {}) {
        const t = toVec3(translate, 'translate');
        const a = toVec3(rotate.axis || [0, 0, 1], 'rotate.axis');
        const ch = sculptor.session.grabDrag(t.x, t.y, t.z, a.x, a.y, a.z, rotate.degrees || 0, scale);
        stroke.frame(ch);
        return { vertices: ch.vertices, faces: ch.faces, timings: ch.timings };
      },
      end() { stroke.end(() => sculptor.session.grabEnd()); },
    };
    this.brush = createBrushApi({
      session: this.session,
      stroke,
      defaults: () => ({
        tool: this._tool === 'pull' || this._tool === 'mask' ? 'draw' : this._tool, radius: this.radius,
        strength: this._strength, symmetry: this._symmetry, spacing: this._feel.spacing, falloff: this._feel.falloff,
        detail: this.detailLength(),
      }),
    });
    this.mask = createMaskApi({
      session: this.session,
      stroke,
      defaults: () => ({ radius: this.radius, strength: this._strength }),
    });
  }

  // ---- settings

  get tool() { return this._tool; }
  // 'pull' (the handle grab), a brush or 'mask'; false (nothing changes) while a stroke is under way.
  setTool(name) {
    checkTool(name);
    if (this.grabTool.active || this.brushTool.active) return false;
    this._tool = name;
    this.grabTool.setEnabled(name === 'pull');
    this.brushTool.setEnabled(name !== 'pull');
    this.dispatchEvent({ type: 'tool', tool: name });
    return true;
  }

  get diagonal() { return this._diagonal; }
  get radius() { return (this._pct.radius / 100) * this._diagonal; }
  get handleRadius() { return (this._pct.handleRadius / 100) * this._diagonal; }
  get roiRadius() { return (this._pct.roiRadius / 100) * this._diagonal; }
  get strength() { return this._strength; }
  get symmetry() { return this._symmetry; }
  get busy() { return !!this._busy; }

  // Everything adjustable, lengths absolute (plus diagonal and the tool lengths in percent).
  get params() {
    const s = this.session.hasMesh() ? this.session.settings() : null;
    return {
      epsilon: s ? s.epsilon : null, minLength: s ? s.minLength : null, maxLength: s ? s.maxLength : null,
      features: s ? s.features : null, guardCrossings: s ? s.guardCrossings : null, diagonal: this._diagonal,
      tool: this._tool, radius: this.radius, strength: this._strength, symmetry: this._symmetry,
      handleRadius: this.handleRadius, roiRadius: this.roiRadius,
      ...this._feel, constantDetail: (this._feel.constantDetail / 100) * this._diagonal,
      percent: { ...this._pct, constantDetail: this._feel.constantDetail },
    };
  }

  // Lengths: a number (absolute) or "x%" of the diagonal. Checks everything before changing
  // anything; throws on an unknown key or a bad value. Returns this.params.
  setParams(p = {}) {
    const core = {};
    const pct = {};
    const feel = {};
    let strength, symmetry;
    for (const [k, v] of Object.entries(p)) {
      if (v === undefined) continue;
      if (CORE_KEYS.includes(k)) core[k] = v;
      else if (k === 'radius' || k === 'handleRadius' || k === 'roiRadius') pct[k] = lengthToPercent(v, this._diagonal, k);
      else if (k === 'strength') strength = checkStrength(v);
      else if (k === 'symmetry') symmetry = checkSymmetry(v);
      else if (k === 'tool') checkTool(v);
      else if (FEEL_KEYS.includes(k)) feel[k] = checkFeel(k, v, this._diagonal, lengthToPercent);
      else throw new Error(`setParams: unknown parameter '${k}'`);
    }
    if (Object.keys(core).length) {
      if (!this.session.hasMesh()) throw new Error('setParams: epsilon, minLength, maxLength, features and guardCrossings need a mesh');
      this.session.setSettings(core);
    }
    Object.assign(this._pct, pct);
    Object.assign(this._feel, feel);
    if (strength !== undefined) this._strength = strength;
    if (symmetry !== undefined) this._symmetry = symmetry;
    if (p.tool !== undefined) this.setTool(p.tool);
    this.grabTool.updateBrush();
    this.brushTool.updateCursor();
    this.dispatchEvent({ type: 'params' });
    return this.params;
  }

  // ---- the mesh

  // Replaces the sculpted surface by this geometry's triangles (welded by position: three.js
  // primitives split vertices along UV seams). History and remeshing settings start afresh.
  loadGeometry(geometry) {
    const { positions, indices } = weldedTriangles(geometry);
    this.session.loadArrays(positions, indices);
    this.resync();
  }

  // Replaces the surface by a mesh file's bytes (OBJ, STL, PLY, OFF; `name` gives the format).
  // Throws the reader's message; the current mesh stays.
  loadBytes(bytes, name) {
    this.session.loadBytes(bytes, name);
    this.resync();
  }

  // Re-reads the whole surface and its size from the session (after a load, or after calling
  // methods of `session` directly, such as restoreState).
  resync() {
    this._diagonal = this.session.settings().diagonal || 1;
    this._sync();
    this.buffers.updateBounds();
    this.grabTool.updateBrush();
    this.brushTool.updateCursor();
  }

  undo() { return this._historyStep(() => this.session.undo()); }
  redo() { return this._historyStep(() => this.session.redo()); }
  _historyStep(fn) {
    if (this._stroke || this.busy) return false;
    const ok = fn();
    this._sync();
    this.buffers.updateBounds();
    return ok;
  }

  // Whole-mesh adaptive remeshing: one core call of `iterations` (one undo step, the CLI's
  // `remesh --iterations` result exactly: the remesher keeps its reference surface across the
  // iterations). With onProgress, {done: 0, total} is reported and one animation frame passes (the
  // page can show it) before the call, {done: total, total} after it. Resolves with the mesh's counts.
  // detail > 0: every edge towards that absolute length (Session.remeshDetail) instead of the settings.
  async remesh({ iterations = 5, detail = 0, onProgress } = {}) {
    if (this.busy) throw new Error('a remesh is already running');
    if (this._stroke) throw new Error('remesh: a stroke is under way');
    if (!(Number.isInteger(iterations) && iterations >= 1)) throw new Error('remesh: iterations must be a positive integer');
    if (!(typeof detail === 'number' && detail >= 0 && Number.isFinite(detail))) throw new Error('remesh: detail must be a length >= 0');
    this._busy = { done: 0, total: iterations };
    try {
      if (onProgress) {
        onProgress({ ...this._busy });
        await new Promise((resolve) => requestAnimationFrame(resolve));
      }
      if (!this._disposed) {
        if (detail > 0) this.session.remeshDetail(iterations, detail);
        else this.session.remesh(iterations);
        this._sync();
        this._busy.done = iterations;
        if (onProgress) onProgress({ ...this._busy });
      }
    } finally {
      this._busy = null;
    }
    if (this._disposed) return { vertices: 0, faces: 0 };
    this.buffers.updateBounds();
    return this._counts();
  }

  // The detail flood fill: the whole mesh remeshed at the detail strokes get now (detailLength();
  // 'relative' mode: the remesh settings), in one call and one undo step, with remesh()'s progress.
  floodFill({ iterations = 5, onProgress } = {}) {
    return this.remesh({ iterations, detail: this.detailLength(), onProgress });
  }

  // The edge length a stroke at `point` (the mesh's coordinates; default: the middle of its bounds)
  // remeshes to under the current detail mode; 0 in 'relative' mode (the remesh settings).
  detailLength(point) {
    return detailLength(this._feel, {
      diagonal: this._diagonal, radius: this.radius,
      pixelSize: () => this._pixelSize(point || this.buffers.boundingBox().getCenter(new THREE.Vector3())),
    });
  }

  // Runs a session file (text or object, as `adasculpt replay` reads it); returns its report.
  replay(file) {
    if (this._stroke || this.busy) throw new Error('replay: a stroke or remesh is under way');
    const report = this.session.replay(file);
    this._sync();
    this.buffers.updateBounds();
    return report;
  }

  // ---- pointer input

  // Listens to pointer events on the element (the canvas the camera draws into) until disconnect().
  connect(domElement) {
    this.disconnect();
    this.domElement = domElement;
    this.grabTool.connect(domElement, this.keyTarget);
    this.brushTool.connect(domElement, this.keyTarget);
    domElement.style.touchAction = 'none'; // pointer events, not scrolling, on touch screens
  }

  disconnect() {
    if (!this.domElement) return;
    this.grabTool.disconnect();
    this.brushTool.disconnect();
    this.domElement = null;
  }

  // Sends the pointer samples queued since the last frame to the core (one wasm call at most).
  update() {
    if (this._disposed || !this.enabled) return;
    this.grabTool.frame();
    this.brushTool.frame();
  }

  // Frees the wasm instance, the cursor's GPU resources and every listener. The mesh keeps the
  // sculpted geometry. Idempotent.
  dispose() {
    if (this._disposed) return;
    this._disposed = true;
    cancelAnimationFrame(this._scheduled);
    this.disconnect();
    this.brushTool.dispose();
    if (this._grabCursor) this._grabCursor.dispose();
    this.buffers.dispose();
    this.session.delete();
    this.module = null;
    this.dispatchEvent({ type: 'dispose' });
  }

  // ---- internals

  _schedule() {
    if (this._scheduled || this._disposed) return;
    this._scheduled = requestAnimationFrame(() => {
      this._scheduled = 0;
      this.update();
    });
  }

  // Copies what the core changed into the geometry; `change` with the frame's counts and timings.
  _sync(changes) {
    const ch = changes || this.session.changes();
    const t0 = performance.now();
    if (this.buffers.apply(ch)) {
      this.dispatchEvent({ type: 'change', vertices: ch.vertices, faces: ch.faces, timings: ch.timings,
        copyMs: performance.now() - t0 });
    }
  }

  _counts() {
    const ch = this.session.changes(); // empty after a sync: only the counts are read
    return { vertices: ch.vertices, faces: ch.faces };
  }

  _guard(fn) {
    try {
      return fn();
    } catch (error) {
      if (this._hasListener('error')) this.dispatchEvent({ type: 'error', error });
      else console.error(error);
      return undefined;
    }
  }

  _hasListener(type) {
    return !!(this._listeners && this._listeners[type] && this._listeners[type].length);
  }

  _updateInverse() {
    this.mesh.updateWorldMatrix(true, false);
    this._inverse.copy(this.mesh.matrixWorld).invert();
  }

  // The pointer's ray in the mesh's own coordinates.
  _ray(clientX, clientY) {
    const r = this.domElement.getBoundingClientRect();
    this._ndc.set(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
    this._raycaster.setFromCamera(this._ndc, this.camera);
    this._updateInverse();
    return this._raycaster.ray.clone().applyMatrix4(this._inverse);
  }

  _viewDirection() {
    this._updateInverse();
    return this.camera.getWorldDirection(new THREE.Vector3()).transformDirection(this._inverse);
  }

  // The plane through a (local) point facing the camera, in local coordinates.
  _viewPlane(point) {
    this._updateInverse();
    const world = point.clone().applyMatrix4(this.mesh.matrixWorld);
    const plane = new THREE.Plane().setFromNormalAndCoplanarPoint(this.camera.getWorldDirection(new THREE.Vector3()), world);
    return plane.applyMatrix4(this._inverse);
  }

  // The surface point under a pointer position (client pixels) in world coordinates, or null (the
  // JS raycast the brushes use; no wasm call). Needs connect().
  surfacePoint(clientX, clientY) {
    if (!this.domElement || !this.buffers.allocated) return null;
    const hit = raycastSurface(this.buffers.geometry, this._ray(clientX, clientY));
    return hit ? hit.point.clone().applyMatrix4(this.mesh.matrixWorld) : null;
  }

  // The size of one screen pixel at a point of the mesh (its own coordinates and units): perspective,
  // it grows with the distance from the camera; orthographic, the same everywhere.
  _pixelSize(point) {
    const height = (this.domElement && this.domElement.clientHeight) || 1;
    this._updateInverse();
    const world = point.clone().applyMatrix4(this.mesh.matrixWorld);
    const c = this.camera;
    const span = c.isOrthographicCamera ? (c.top - c.bottom) / c.zoom
      : (2 * Math.tan(THREE.MathUtils.degToRad(c.fov) / 2) * c.position.distanceTo(world)) / c.zoom;
    return span / height / this.mesh.matrixWorld.getMaxScaleOnAxis();
  }

  // Touch: OrbitControls' one-finger orbit is held off while a finger rests on the model (it sculpts).
  _holdTouchOrbit(hold) {
    const t = this.controls && this.controls.touches;
    if (!t) return;
    if (hold && this._touchOrbit === null) {
      this._touchOrbit = t.ONE;
      t.ONE = null; // OrbitControls: no one-finger action; two fingers still orbit and zoom
    } else if (!hold && this._touchOrbit !== null) {
      t.ONE = this._touchOrbit;
      this._touchOrbit = null;
    }
  }

  // The Pull tool's press and hover: the same JS raycast of the drawn geometry as the brushes'
  // (slot-ray-tree.js: no wasm call per hover); grabBegin snaps the point to the surface itself.
  _pick(ray) {
    if (!this.session.hasMesh()) return null;
    const hit = raycastSurface(this.buffers.geometry, ray);
    return hit ? hit.point : null;
  }

  // The Pull tool's preview without a host shader: rings at the region and handle radii, facing
  // the camera, at the handle.
  _showGrab({ center, handleRadius, roiRadius, visible }) {
    if (!visible || !center) {
      if (this._grabCursor) this._grabCursor.show(null);
      return;
    }
    if (!this._grabCursor) this._grabCursor = new BrushCursor(this.mesh, this._view.changed);
    const facing = this._viewDirection().negate();
    this._grabCursor.show(center, facing, roiRadius, handleRadius / roiRadius, false);
  }
}

// ---- helpers

function strokeTimings(s) {
  const f = s.frames.slice().sort((a, b) => a - b);
  const q = (p) => (f.length ? f[Math.min(f.length - 1, Math.floor(p * f.length))] : 0);
  return {
    frames: f.length, stamps: s.stamps, durationMs: performance.now() - s.t0,
    coreMs: f.reduce((a, b) => a + b, 0), medianFrameMs: q(0.5), p95FrameMs: q(0.95), maxFrameMs: f.length ? f[f.length - 1] : 0,
  };
}

// Positions (Float64Array) and triangles (Uint32Array) of a BufferGeometry, vertices welded by
// position within a millionth of its diagonal, triangles that collapse in the welding left out.
function weldedTriangles(geometry) {
  const src = geometry.attributes.position;
  if (!src || src.count === 0) throw new Error('loadGeometry: the geometry has no positions');
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', src);
  if (geometry.index) g.setIndex(geometry.index);
  g.computeBoundingBox();
  const diagonal = g.boundingBox.getSize(new THREE.Vector3()).length() || 1;
  const welded = mergeVertices(g, diagonal * 1e-6);
  const p = welded.attributes.position;
  const positions = new Float64Array(3 * p.count);
  for (let i = 0; i < p.count; i++) {
    positions[3 * i] = p.getX(i);
    positions[3 * i + 1] = p.getY(i);
    positions[3 * i + 2] = p.getZ(i);
  }
  const idx = welded.index.array;
  const tris = [];
  for (let f = 0; f + 2 < idx.length; f += 3) {
    const a = idx[f], b = idx[f + 1], c = idx[f + 2];
    if (a !== b && b !== c && c !== a) tris.push(a, b, c);
  }
  welded.dispose();
  return { positions, indices: Uint32Array.from(tris) };
}

// [x, y, z, pressure, ...] -> [x, y, z, ...]: the mask brush has no pressure.
function withoutPressure(samples) {
  const out = new Float64Array((samples.length / 4) * 3);
  for (let i = 0, j = 0; i < samples.length; i += 4, j += 3) out.set(samples.subarray(i, i + 3), j);
  return out;
}

function toVec3(v, what) {
  if (v && v.isVector3) return v;
  if (Array.isArray(v) && v.length === 3 && v.every(Number.isFinite)) return new THREE.Vector3(v[0], v[1], v[2]);
  if (v && [v.x, v.y, v.z].every(Number.isFinite)) return new THREE.Vector3(v.x, v.y, v.z);
  throw new Error(`${what}: expected [x, y, z]`);
}

function pick(o, keys) {
  const out = {};
  for (const k of keys) if (o[k] !== undefined) out[k] = o[k];
  return out;
}

function clamp(x, lo, hi) { return Math.min(hi, Math.max(lo, x)); }
function round(x) { return Number(x.toFixed(3)); }
