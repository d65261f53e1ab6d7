// Shared pieces of the brush comparison with three.js's Sculptor addon (issue #7):
// tests/bench/sculptor-compare.mjs (the benchmark) and tests/js/brush-quality.test.mjs (our quality
// targets) both use them.
//
// - the same mesh goes into both: it is loaded by adasculpt's wasm Session and its positions and
//   indices are handed to Sculptor as a BufferGeometry (Sculptor welds; the mesh is already welded);
// - a stroke is a line of parallel rays (an orthographic view): Sculptor gets the rays
//   (strokeFromRay, one stamp per call), adasculpt gets the points where those rays hit the
//   initial surface as the stroke path, spaced so that each path point is exactly one stamp;
// - quality is measured by ONE function on both final meshes (brushedRegionMetrics).
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';

export const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');

// ---------------------------------------------------------------------------------------------
// adasculpt (the wasm module in public/wasm, or ADASCULPT_WASM_DIR)

export async function loadAdasculpt(dir = process.env.ADASCULPT_WASM_DIR || path.join(ROOT, 'public', 'wasm')) {
  const wasmDir = path.resolve(dir);  // require() takes a relative path as a package name
  const js = path.join(wasmDir, 'adasculpt.js');
  const wasm = path.join(wasmDir, 'adasculpt.wasm');
  if (!fs.existsSync(js) || !fs.existsSync(wasm)) return null;
  const create = createRequire(import.meta.url)(js);
  return create({ wasmBinary: fs.readFileSync(wasm) });
}

// {positions: Float64Array, indices: Uint32Array} of a mesh file, read by adasculpt's own loader.
export function readMesh(M, file) {
  const s = new M.Session();
  try {
    s.loadBytes(new Uint8Array(fs.readFileSync(file)), path.basename(file));
    return { positions: Float64Array.from(s.positions()), indices: Uint32Array.from(s.indices()) };
  } finally {
    s.delete();
  }
}

// ---------------------------------------------------------------------------------------------
// geometry helpers (plain arrays; no three.js needed)

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);
const normalize = (a) => scale(a, 1 / norm(a));
const vert = (P, i) => [P[3 * i], P[3 * i + 1], P[3 * i + 2]];

export function boundingBox(P) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < P.length; i += 3)
    for (let k = 0; k < 3; ++k) {
      lo[k] = Math.min(lo[k], P[i + k]);
      hi[k] = Math.max(hi[k], P[i + k]);
    }
  return { lo, hi, diagonal: norm(sub(hi, lo)), centre: scale(add(lo, hi), 0.5) };
}

// Nearest hit (distance t > 0) of the ray o + t d on the mesh (Möller–Trumbore, both sides); null
// when it misses. The faces are bucketed once per mesh and ray direction in a grid over the plane
// perpendicular to d (a stroke's rays are parallel), so a ray tests only the faces of its cell.
const grids = new WeakMap();
function gridFor(mesh, d) {
  let byDir = grids.get(mesh);
  if (!byDir) grids.set(mesh, (byDir = new Map()));
  const k = d.join(',');
  let g = byDir.get(k);
  if (g) return g;
  const P = mesh.positions, F = mesh.indices, nf = F.length / 3;
  const a = Math.abs(d[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
  const u = normalize(cross(d, a)), w = cross(d, u);
  const nv = P.length / 3, pu = new Float64Array(nv), pw = new Float64Array(nv);
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  for (let i = 0; i < nv; ++i) {
    const p = vert(P, i);
    pu[i] = dot(p, u);
    pw[i] = dot(p, w);
    lo = [Math.min(lo[0], pu[i]), Math.min(lo[1], pw[i])];
    hi = [Math.max(hi[0], pu[i]), Math.max(hi[1], pw[i])];
  }
  const n = Math.max(1, Math.min(1024, Math.ceil(Math.sqrt(nf / 2))));
  const cu = (hi[0] - lo[0]) / n || 1, cw = (hi[1] - lo[1]) / n || 1;
  const cells = Array.from({ length: n * n }, () => []);
  const clampCell = (x) => Math.max(0, Math.min(n - 1, Math.floor(x)));
  for (let f = 0; f < nf; ++f) {
    const ids = [F[3 * f], F[3 * f + 1], F[3 * f + 2]];
    const us = ids.map((i) => pu[i]), ws = ids.map((i) => pw[i]);
    const i0 = clampCell((Math.min(...us) - lo[0]) / cu), i1 = clampCell((Math.max(...us) - lo[0]) / cu);
    const j0 = clampCell((Math.min(...ws) - lo[1]) / cw), j1 = clampCell((Math.max(...ws) - lo[1]) / cw);
    for (let i = i0; i <= i1; ++i) for (let j = j0; j <= j1; ++j) cells[i * n + j].push(f);
  }
  g = { u, w, lo, cu, cw, n, cells };
  byDir.set(k, g);
  return g;
}

export function raycast(mesh, o, d) {
  const P = mesh.positions, F = mesh.indices;
  const g = gridFor(mesh, d);
  const iu = Math.floor((dot(o, g.u) - g.lo[0]) / g.cu), iw = Math.floor((dot(o, g.w) - g.lo[1]) / g.cw);
  if (iu < 0 || iw < 0 || iu >= g.n || iw >= g.n) return null;
  let best = Infinity;
  for (const f3 of g.cells[iu * g.n + iw]) {
    const f = 3 * f3;
    const a = vert(P, F[f]), b = vert(P, F[f + 1]), c = vert(P, F[f + 2]);
    const e1 = sub(b, a), e2 = sub(c, a), p = cross(d, e2), det = dot(e1, p);
    if (Math.abs(det) < 1e-300) continue;
    const inv = 1 / det, s = sub(o, a), u = dot(s, p) * inv;
    if (u < 0 || u > 1) continue;
    const q = cross(s, e1), v = dot(d, q) * inv;
    if (v < 0 || u + v > 1) continue;
    const t = dot(e2, q) * inv;
    if (t > 0 && t < best) best = t;
  }
  return best === Infinity ? null : add(o, scale(d, best));
}

function distanceToSegment2(p, a, b) {
  const ab = sub(b, a), ap = sub(p, a), l2 = dot(ab, ab);
  const t = l2 > 0 ? Math.max(0, Math.min(1, dot(ap, ab) / l2)) : 0;
  const d = sub(ap, scale(ab, t));
  return dot(d, d);
}
function distanceToPolyline(p, line) {
  if (line.length === 1) return norm(sub(p, line[0]));
  let best = Infinity;
  for (let i = 1; i < line.length; ++i) best = Math.min(best, distanceToSegment2(p, line[i - 1], line[i]));
  return Math.sqrt(best);
}

// ---------------------------------------------------------------------------------------------
// strokes

// A stroke seen from direction `view` (unit, pointing from the eye into the scene): a line across
// the mesh's bounding box through its centre, perpendicular to the view, `across` being the
// in-screen direction, from -span/2 to +span/2 times the diagonal, with a sine wiggle of
// `wiggle` times the diagonal so that it is not a straight cut. Returns the rays whose hits on
// the initial surface are spacing * radius apart (3D chord), i.e. one stamp each, and those hits.
export function makeStroke(mesh, { view, across, span = 0.5, wiggle = 0.05, offset = 0, radius, spacing = 0.25 }) {
  const bb = boundingBox(mesh.positions);
  const d = normalize(view);
  const u = normalize(sub(across, scale(d, dot(across, d))));
  const w = cross(d, u);
  const far = 2 * bb.diagonal;
  const rayAt = (s) => {
    // s in [-1/2, 1/2]: position along the stroke, in units of span * diagonal
    const x = s * span * bb.diagonal;
    const y = offset * bb.diagonal + wiggle * bb.diagonal * Math.sin(2 * Math.PI * s);
    const o = add(add(add(bb.centre, scale(u, x)), scale(w, y)), scale(d, -far));
    return { origin: o, direction: d };
  };
  // Dense hits, then points at chord distance `step` along them. The step is a hair longer than
  // spacing * radius so that adasculpt's stroker (a stamp each time the travelled length reaches
  // spacing * radius) stamps exactly once per path point despite rounding.
  const step = spacing * radius * (1 + 1e-6);
  const dense = [];
  const n = 2000;
  for (let i = 0; i <= n; ++i) {
    const r = rayAt(i / n - 0.5);
    const hit = raycast(mesh, r.origin, r.direction);
    if (hit) dense.push({ s: i / n - 0.5, hit });
  }
  if (dense.length < 2) throw new Error('stroke misses the mesh');
  const rays = [], path = [];
  const push = (s, hit) => {
    rays.push(rayAt(s));
    path.push(hit);
  };
  push(dense[0].s, dense[0].hit);
  for (let i = 1; i < dense.length; ++i) {
    const last = path[path.length - 1];
    if (norm(sub(dense[i].hit, last)) < step) continue;
    // bisect between dense[i-1] and dense[i] for the point at chord distance `step`
    let lo = dense[i - 1].s, hi = dense[i].s, hitHi = dense[i].hit;
    for (let k = 0; k < 40; ++k) {
      const mid = 0.5 * (lo + hi), r = rayAt(mid), h = raycast(mesh, r.origin, r.direction);
      if (h && norm(sub(h, last)) >= step) {
        hi = mid;
        hitHi = h;
      } else {
        lo = mid;
      }
    }
    push(hi, hitHi);
    --i;  // the next point may lie before dense[i] still
  }
  return { rays, path, radius, spacing, view: d };
}

// A snake-hook grab: pick the surface where the ray at `start` (fraction of the diagonal along
// `across` from the bounding-box centre) hits, then pull that point `pull` * radius further along
// `across`, in the view plane (the depth stays: what an orthographic pointer drag does). The path
// is the dragged point every spacing * radius (one stamp each after the pick-up); `regionLine`
// (the path itself: the hook follows it) replaces the rays in brushedRegionMetrics.
export function makeGrab(mesh, { view, across, start = 0.25, pull = 3, radius, spacing = 0.15 }) {
  const bb = boundingBox(mesh.positions);
  const d = normalize(view);
  const u = normalize(sub(across, scale(d, dot(across, d))));
  let hit = null;
  for (let s = start; !hit && s > 0; s -= 0.01)
    hit = raycast(mesh, add(add(bb.centre, scale(u, s * bb.diagonal)), scale(d, -2 * bb.diagonal)), d);
  if (!hit) throw new Error('grab misses the mesh');
  const step = spacing * radius * (1 + 1e-6);
  const path = [];
  for (let k = 0; k * step <= pull * radius; ++k) path.push(add(hit, scale(u, k * step)));
  return { kind: 'drag', path, regionLine: path, rays: [], radius, spacing, view: d, across: u, centre: bb.centre, diagonal: bb.diagonal };
}

// How far the hook got: the farthest vertex along the pull from the picked point, as a share of
// the pointer's travel (1 = the surface followed the pointer all the way).
export function grabReach(mesh, grab) {
  const P = mesh.positions, o = dot(grab.path[0], grab.across);
  let far = -Infinity;
  for (let i = 0; i < P.length; i += 3) far = Math.max(far, dot(vert(P, i / 3), grab.across) - o);
  return far / (dot(grab.path[grab.path.length - 1], grab.across) - o);
}

// ---------------------------------------------------------------------------------------------
// the shared quality measure

// The brushed region on a FINAL mesh: the stroke's rays are cast again on that mesh, and a face
// belongs to the region when its centroid lies within `radius` of the polyline through those hits
// (a ray that now misses is left out). Interior vertices: vertices of region faces that are within
// `radius` of the polyline and not on a mesh boundary; valence = number of incident edges.
// Returns min angle, share of triangles under 30°, share of interior vertices of valence 5-7,
// mean edge length (edges of region faces), counts; and the share of triangles under 30° in the
// rim just outside the region (centroid between 1 and `rimOuter` radii from the polyline), where
// a remeshed region meets the untouched mesh.
export function brushedRegionMetrics(mesh, stroke, { rimOuter = 1.5 } = {}) {
  const P = mesh.positions, F = mesh.indices, r = stroke.radius;
  const line = stroke.regionLine || stroke.rays.map((ray) => raycast(mesh, ray.origin, ray.direction)).filter(Boolean);
  const nv = P.length / 3;
  const valence = new Uint32Array(nv);
  const edgeFaces = new Map();  // undirected edge -> face count (boundary: 1)
  const key = (a, b) => (a < b ? a * nv + b : b * nv + a);
  for (let f = 0; f < F.length; f += 3)
    for (let k = 0; k < 3; ++k) {
      const e = key(F[f + k], F[f + (k + 1) % 3]);
      edgeFaces.set(e, (edgeFaces.get(e) || 0) + 1);
    }
  const onBoundary = new Uint8Array(nv);
  for (const [e, c] of edgeFaces) {
    const a = Math.floor(e / nv), b = e % nv;
    ++valence[a];
    ++valence[b];
    if (c === 1) onBoundary[a] = onBoundary[b] = 1;
  }
  let faces = 0, under30 = 0, minAngle = 180, sumMin = 0, rimFaces = 0, rimUnder30 = 0;
  const inRegionVertex = new Uint8Array(nv);
  const regionEdges = new Set();
  for (let f = 0; f < F.length; f += 3) {
    const ids = [F[f], F[f + 1], F[f + 2]];
    const [a, b, c] = ids.map((i) => vert(P, i));
    const centroid = scale(add(add(a, b), c), 1 / 3);
    const dist = distanceToPolyline(centroid, line);
    if (dist >= rimOuter * r) continue;
    const ang = (p, q, s) => {
      const u = sub(q, p), v = sub(s, p);
      return (Math.atan2(norm(cross(u, v)), dot(u, v)) * 180) / Math.PI;
    };
    const m = Math.min(ang(a, b, c), ang(b, c, a), ang(c, a, b));
    if (dist >= r) {
      ++rimFaces;
      if (m < 30) ++rimUnder30;
      continue;
    }
    ++faces;
    minAngle = Math.min(minAngle, m);
    sumMin += m;
    if (m < 30) ++under30;
    for (let k = 0; k < 3; ++k) {
      if (distanceToPolyline(vert(P, ids[k]), line) < r) inRegionVertex[ids[k]] = 1;
      regionEdges.add(key(ids[k], ids[(k + 1) % 3]));
    }
  }
  let interior = 0, regular = 0;
  for (let v = 0; v < nv; ++v) {
    if (!inRegionVertex[v] || onBoundary[v]) continue;
    ++interior;
    if (valence[v] >= 5 && valence[v] <= 7) ++regular;
  }
  let edgeSum = 0;
  for (const e of regionEdges) edgeSum += norm(sub(vert(P, Math.floor(e / nv)), vert(P, e % nv)));
  return {
    faces,
    minAngle: faces ? minAngle : NaN,
    meanMinAngle: faces ? sumMin / faces : NaN,
    pctUnder30: faces ? (100 * under30) / faces : NaN,
    interior,
    pctValence5to7: interior ? (100 * regular) / interior : NaN,
    meanEdge: regionEdges.size ? edgeSum / regionEdges.size : NaN,
    rimFaces,
    pctUnder30Rim: rimFaces ? (100 * rimUnder30) / rimFaces : NaN,
    totalFaces: F.length / 3,
  };
}

// ---------------------------------------------------------------------------------------------
// the tools both have, and how strengths map so that one stamp moves the surface by the same
// amount at the brush centre (from the two implementations' constants: Sculptor pinch 0.05 and
// crease 0.07 per unit strength, adasculpt pinch/crease 0.25 tangential; draw and inflate are
// 0.1 * radius in both, flatten and smooth a fraction of the distance in both)

export const TOOLS = {
  draw: { sculptor: 'brush', strength: 0.5, ours: 0.5 },
  inflate: { sculptor: 'inflate', strength: 0.5, ours: 0.5 },
  smooth: { sculptor: 'smooth', strength: 0.5, ours: 0.5 },
  flatten: { sculptor: 'flatten', strength: 0.5, ours: 0.5 },
  pinch: { sculptor: 'pinch', strength: 0.75, ours: 0.75 * (0.05 / 0.25) },
  crease: { sculptor: 'crease', strength: 0.75, ours: 0.75 * (0.07 / 0.25) },
  // Snake hook: both move the vertices under the brush by the pointer's motion times the falloff;
  // strength is ignored by both.
  grab: { sculptor: 'drag', strength: 0.5, ours: 0.5 },
};

// ---------------------------------------------------------------------------------------------
// adasculpt side: Session.replay of {"brush": ...} steps

// The render buffers keep a slot for every face, deleted ones drawn as (0, 0, 0) until the core
// compacts the mesh (not after every stroke): the metrics read only the live triangles.
function liveTriangles(indices) {
  const out = [];
  for (let f = 0; f < indices.length; f += 3) {
    const a = indices[f], b = indices[f + 1], c = indices[f + 2];
    if (a !== b && b !== c && a !== c) out.push(a, b, c);
  }
  return Uint32Array.from(out);
}

// `strokes`: [{tool, stroke}] applied in order on one fresh copy of `mesh`. `length`: the uniform
// target edge length (min_length = max_length), absolute. Returns the final mesh, the wall time
// of the replay call per stamp (minus an empty replay's: settings and JSON) and the core's
// per-stamp median (frame_ms_median: one path point = one stamp here).
export function runOurs(M, mesh, strokes, { length, epsilon }) {
  const settings = length ? { min_length: length, max_length: length } : {};
  if (epsilon) settings.epsilon = epsilon;
  const steps = strokes.map(({ tool, stroke }) => ({
    brush: {
      tool,
      path: stroke.path,
      radius: stroke.radius,
      strength: TOOLS[tool].ours,
      spacing: stroke.spacing,
    },
  }));
  const stamps = strokes.reduce((n, s) => n + s.stroke.path.length - (s.stroke.kind === 'drag' ? 1 : 0), 0);
  const s = new M.Session();
  try {
    s.loadArrays(mesh.positions, mesh.indices);
    const empty = JSON.stringify({ version: 1, settings, steps: [] });
    const full = JSON.stringify({ version: 1, settings, steps });
    let t0 = performance.now();
    s.replay(empty);
    const emptyMs = performance.now() - t0;
    t0 = performance.now();
    const rep = s.replay(full);
    const ms = performance.now() - t0 - emptyMs;
    return {
      mesh: { positions: Float64Array.from(s.positions()), indices: liveTriangles(s.indices()) },
      stamps,
      msPerStamp: ms / stamps,
      stampMedian: rep.frameMsMedian,
      report: rep,
    };
  } finally {
    s.delete();
  }
}

// ---------------------------------------------------------------------------------------------
// Sculptor side (three.js addon, imported from node_modules at run time; CPU only, no renderer)

let THREE = null, Sculptor = null;
export async function loadSculptor() {
  if (!Sculptor) {
    THREE = await import('three');
    ({ Sculptor } = await import('three/addons/misc/Sculptor.js'));
  }
  return { THREE, Sculptor };
}

// Same contract as runOurs. `detail`: Sculptor's adaptive-topology detail (0..1): it splits
// edges longer than radius * sqrt(0.2 (1.1 - detail)) and collapses those shorter than that
// over 2.05, within the brush.
export function runSculptor(mesh, strokes, { detail }) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(mesh.positions), 3));
  geometry.setIndex(new THREE.BufferAttribute(Uint32Array.from(mesh.indices), 1));
  const object = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial());
  const sculptor = new Sculptor(object, new THREE.PerspectiveCamera());
  sculptor.setDetail(detail);
  const ray = new THREE.Ray();
  const perStamp = [];
  let ms = 0, stamps = 0, missed = 0;
  for (const { tool, stroke } of strokes) {
    sculptor.setTool(TOOLS[tool].sculptor).setStrength(TOOLS[tool].strength);
    if (stroke.kind === 'drag') {
      const r = dragWithPointer(sculptor, object, stroke, perStamp);
      ms += r.ms;
      stamps += r.stamps;
      missed += r.missed;
      continue;
    }
    const t0 = performance.now();
    for (const r of stroke.rays) {
      ray.origin.set(...r.origin);
      ray.direction.set(...r.direction);
      const a = performance.now();
      if (!sculptor.strokeFromRay(ray, stroke.radius)) ++missed;
      perStamp.push(performance.now() - a);
      ++stamps;
    }
    sculptor.endStroke();
    ms += performance.now() - t0;
  }
  const out = sculptor.getGeometry();
  sculptor.dispose();
  perStamp.sort((a, b) => a - b);
  return {
    mesh: { positions: out.getAttribute('position').array, indices: out.getIndex().array },
    stamps,
    missed,
    msPerStamp: ms / stamps,
    stampMedian: perStamp[Math.floor(perStamp.length / 2)],
  };
}

// Sculptor's drag needs pointer input: an orthographic camera looking along the stroke's view
// direction, a stand-in element (its listeners are called directly) whose pixels map to world
// units so that the brush size in pixels is the stroke's radius, and one pointermove per stamp
// (Sculptor stamps every 0.15 * size pixels of pointer travel; the moves are that far apart).
function dragWithPointer(sculptor, object, stroke, perStamp) {
  const SIZE = 50;  // pixels
  const half = stroke.diagonal;  // half the view's width in world units
  const W = (SIZE * 2 * half) / stroke.radius;  // element width in pixels: SIZE px = radius
  const camera = new THREE.OrthographicCamera(-half, half, half, -half, 0.01 * half, 8 * half);
  const c = new THREE.Vector3(...stroke.centre), d = new THREE.Vector3(...stroke.view);
  camera.up.set(Math.abs(d.y) > 0.9 ? 1 : 0, Math.abs(d.y) > 0.9 ? 0 : 1, 0);
  camera.position.copy(c).addScaledVector(d, -4 * half);
  camera.lookAt(c);
  camera.updateMatrixWorld(true);
  const listeners = {};
  const element = {
    addEventListener: (type, fn) => (listeners[type] = fn),
    removeEventListener: (type) => delete listeners[type],
    getBoundingClientRect: () => ({ left: 0, top: 0, width: W, height: W }),
  };
  const previousCamera = sculptor.camera;
  sculptor.camera = camera;
  sculptor.connect(element);
  sculptor.setSize(SIZE);
  const px = (p) => {
    const v = new THREE.Vector3(...p).project(camera);
    return { clientX: (v.x * 0.5 + 0.5) * W, clientY: (-v.y * 0.5 + 0.5) * W };
  };
  const ev = (p) => ({ button: 0, isPrimary: true, pointerId: 1, ...px(p) });
  const t0 = performance.now();
  listeners.pointerdown(ev(stroke.path[0]));
  const missed = sculptor.isSculpting() ? 0 : stroke.path.length - 1;
  for (let k = 1; k < stroke.path.length; ++k) {
    const a = performance.now();
    listeners.pointermove(ev(stroke.path[k]));
    perStamp.push(performance.now() - a);
  }
  listeners.pointerup(ev(stroke.path[stroke.path.length - 1]));
  const ms = performance.now() - t0;
  sculptor.disconnect();
  sculptor.camera = previousCamera;
  return { ms, stamps: stroke.path.length - 1, missed };
}

export const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};
