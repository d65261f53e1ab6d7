// The brush's picking ray in JS (web/surface-raycast.js) on the wasm module's render buffers: 1 and
// 16 disjoint copies of the bunny (70k and 1.1M triangles; rays and strokes on the first copy).
// Prints, per scene: the first ray after loading (fits every box), the median ray with the slot tree
// and by brute force, and during strokes the median frame's picking (refit of the changed slots +
// ray) next to the brute force. Times are CPU milliseconds of this process (process.cpuUsage),
// medians of many rays, so other jobs on the machine skew them little.
//   node tests/bench/raycast-wasm.mjs
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import * as THREE from 'three';
import { MeshBuffers } from '../../web/mesh-buffers.js';
import { raycastSurface } from '../../web/surface-raycast.js';

const require = createRequire(import.meta.url);
const { loadModule, skip, root } = require('../js/wasm-module.cjs');
const meshPath = process.env.ADASCULPT_BENCH_MESH || path.join(root, '..', 'shared', 'meshes', 'bunny.off');

const median = (v) => [...v].sort((a, b) => a - b)[Math.floor((v.length - 1) / 2)];
function cpuMs(fn) {
  const c = process.cpuUsage();
  const out = fn();
  const d = process.cpuUsage(c);
  return [(d.user + d.system) / 1000, out];
}

function loadCopies(M, s, copies) {
  const one = new M.Session();
  one.loadBytes(new Uint8Array(fs.readFileSync(meshPath)), path.basename(meshPath));
  const p = Float64Array.from(one.positions()), t = Uint32Array.from(one.indices());
  one.delete();
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < p.length; i += 3) lo = Math.min(lo, p[i]), hi = Math.max(hi, p[i]);
  const shift = 1.5 * (hi - lo), nv = p.length / 3;
  const P = new Float64Array(p.length * copies), T = new Uint32Array(t.length * copies);
  for (let c = 0; c < copies; c++) {
    for (let i = 0; i < p.length; i++) P[c * p.length + i] = p[i] + (i % 3 === 0 ? c * shift : 0);
    for (let i = 0; i < t.length; i++) T[c * t.length + i] = t[i] + c * nv;
  }
  s.loadArrays(P, T);
  return { lo, hi, p };
}

// Rays from in front of copy 0 through a grid of points on its box (deterministic).
function raysAt(p, n) {
  const box = new THREE.Box3();
  const v = new THREE.Vector3();
  for (let i = 0; i < p.length; i += 3) box.expandByPoint(v.fromArray(p, i));
  const c = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3());
  const eye = c.clone().add(new THREE.Vector3(0, 0, 2 * size.length()));
  const out = [];
  for (let i = 0; i < n; i++) {
    const target = c.clone().add(new THREE.Vector3(((i % 20) / 19 - 0.5) * size.x * 0.8, (Math.floor(i / 20) / (n / 20) - 0.5) * size.y * 0.8, 0));
    out.push(new THREE.Ray(eye.clone(), target.sub(eye).normalize()));
  }
  return out;
}

async function main() {
  const M = await loadModule();
  if (!M) { console.log(`skipped: ${skip}`); return; }
  for (const copies of [1, 16]) {
    const s = new M.Session();
    const { p } = loadCopies(M, s, copies);
    const buffers = new MeshBuffers(M, new THREE.BufferGeometry());
    buffers.apply(s.changes());
    const g = buffers.geometry;
    const rays = raysAt(p, 200);
    const [firstMs] = cpuMs(() => raycastSurface(g, rays[0]));
    const tree = [], brute = [];
    for (const r of rays) {
      tree.push(cpuMs(() => raycastSurface(g, r))[0]);
      brute.push(cpuMs(() => raycastSurface(g, r, { bruteForce: true }))[0]);
    }
    // Strokes: every frame is a stamp, the buffers' update, then the pick of the next sample.
    const strokeTree = [], strokeBrute = [];
    const radius = 0.03 * Math.hypot(...new THREE.Box3().setFromArray(p).getSize(new THREE.Vector3()).toArray());
    for (let k = 0; k < 6; k++) {
      s.brushBegin({ tool: k % 2 ? 'inflate' : 'draw', radius, strength: 0.5, symmetry: 'none' });
      for (let i = 0; i < 10; i++) {
        const ray = rays[(37 * k + 13 * i) % rays.length];
        const hit = raycastSurface(g, ray);
        if (!hit) continue;
        buffers.apply(s.brushStamp(Float64Array.from([hit.point.x, hit.point.y, hit.point.z, 1])));
        strokeTree.push(cpuMs(() => raycastSurface(g, rays[(37 * k + 13 * i + 1) % rays.length]))[0]);
        strokeBrute.push(cpuMs(() => raycastSurface(g, rays[(37 * k + 13 * i + 1) % rays.length], { bruteForce: true }))[0]);
      }
      s.brushEnd();
      buffers.apply(s.changes());
    }
    console.log(`copies=${copies} triangles=${s.changes().faces} first_ray_ms=${firstMs.toFixed(2)} ` +
      `ray_ms tree=${median(tree).toFixed(3)} brute=${median(brute).toFixed(3)} ` +
      `stroke_frame_pick_ms tree=${median(strokeTree).toFixed(3)} brute=${median(strokeBrute).toFixed(3)} ` +
      `frames=${strokeTree.length}`);
    buffers.dispose();
    s.delete();
  }
}

main().catch((e) => { console.error(e); process.exit(1); });
