// Ray against the drawn surface: the three.js copy of the core's render buffers, searched in JS.
// A brush stroke needs the surface point under every pointer sample, and asking the core would be
// a second wasm call per frame (its AABB tree is also stale while the stroke reshapes the mesh).
// A geometry kept by MeshBuffers has a SlotRayTree (slot-ray-tree.js) over its face slots, refitted
// from the slots each frame changed, so a ray costs the boxes it passes, not the mesh; without one
// every face slot is tested. Both find the same hit (the tests compare them on random rays).
// Deleted slots are (0,0,0) triangles and never hit.
import * as THREE from 'three';
import { intersectSlot } from './slot-ray-tree.js';

const trees = new WeakMap(); // geometry -> SlotRayTree (MeshBuffers registers its own)

// The tree that follows `geometry` (MeshBuffers keeps it in step with the buffers).
export function attachRayTree(geometry, tree) {
  trees.set(geometry, tree);
}

// geometry: the MeshBuffers geometry (position, normal, index; drawRange = the live face slots).
// Returns {point, normal, distance, face} of the nearest hit in front of the ray origin, or null.
// The normal is the interpolated vertex normal (falls back to the face normal), turned towards
// the ray. bruteForce: test every slot even when the geometry has a tree (tests, benchmarks).
export function raycastSurface(geometry, ray, { bruteForce = false } = {}) {
  if (!geometry || !geometry.index || !geometry.attributes.position) return null;
  const p = geometry.attributes.position.array;
  const idx = geometry.index.array;
  const count = Math.min(idx.length, Number.isFinite(geometry.drawRange.count) ? geometry.drawRange.count : idx.length);
  const faceCount = Math.floor(count / 3);
  const r = {
    ox: ray.origin.x, oy: ray.origin.y, oz: ray.origin.z,
    dx: ray.direction.x, dy: ray.direction.y, dz: ray.direction.z,
  };
  const tree = bruteForce ? null : trees.get(geometry);
  let hit;
  if (tree && tree.capacity * 3 === idx.length) {
    tree.update(p, idx, faceCount);
    hit = tree.raycast(p, idx, faceCount, r);
  } else {
    hit = bruteForceHit(p, idx, faceCount, r);
  }
  if (!hit) return null;
  const point = new THREE.Vector3(r.ox + r.dx * hit.t, r.oy + r.dy * hit.t, r.oz + r.dz * hit.t);
  const nrm = geometry.attributes.normal ? geometry.attributes.normal.array : null;
  const normal = hitNormal(p, nrm, idx, 3 * hit.face, hit.u, hit.v);
  if (normal.x * r.dx + normal.y * r.dy + normal.z * r.dz > 0) normal.negate();
  return { point, normal, distance: hit.t, face: hit.face };
}

// Every slot in order; the first of equally near hits wins (as in the tree).
function bruteForceHit(p, idx, faceCount, r) {
  const uv = new Float64Array(2);
  let best = Infinity, face = -1, u = 0, v = 0;
  for (let f = 0; f < faceCount; f++) {
    const t = intersectSlot(p, idx, f, r, uv);
    if (t > 0 && t < best) {
      best = t;
      face = f;
      u = uv[0];
      v = uv[1];
    }
  }
  return face < 0 ? null : { face, t: best, u, v };
}

function hitNormal(p, nrm, idx, f, u, v) {
  const i = [3 * idx[f], 3 * idx[f + 1], 3 * idx[f + 2]];
  const n = new THREE.Vector3();
  if (nrm) {
    const w = [1 - u - v, u, v];
    for (let k = 0; k < 3; k++) n.x += w[k] * nrm[i[k]], n.y += w[k] * nrm[i[k] + 1], n.z += w[k] * nrm[i[k] + 2];
  }
  if (n.lengthSq() > 1e-20) return n.normalize();
  const a = new THREE.Vector3().fromArray(p, i[0]);
  const e1 = new THREE.Vector3().fromArray(p, i[1]).sub(a);
  const e2 = new THREE.Vector3().fromArray(p, i[2]).sub(a);
  return e1.cross(e2).normalize();
}
