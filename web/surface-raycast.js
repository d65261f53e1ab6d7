// Ray against the drawn surface: the three.js copy of the core's render buffers, searched in JS.
// A brush stroke needs the surface point under every pointer sample, and asking the core would be
// a second wasm call per frame (its AABB tree is also stale while the stroke reshapes the mesh).
// Brute force over the face slots; deleted slots are (0,0,0) triangles and never hit. Plain loops
// over the typed arrays, no per-triangle objects: the whole drawn mesh costs well under a frame.
import * as THREE from 'three';

const EPS = 1e-12;

// geometry: the MeshBuffers geometry (position, normal, index; drawRange = the live face slots).
// Returns {point, normal, distance} of the nearest hit in front of the ray origin, or null. The
// normal is the interpolated vertex normal (falls back to the face normal), turned towards the ray.
export function raycastSurface(geometry, ray) {
  if (!geometry || !geometry.index || !geometry.attributes.position) return null;
  const p = geometry.attributes.position.array;
  const nrm = geometry.attributes.normal ? geometry.attributes.normal.array : null;
  const idx = geometry.index.array;
  const count = Math.min(idx.length, Number.isFinite(geometry.drawRange.count) ? geometry.drawRange.count : idx.length);
  const ox = ray.origin.x, oy = ray.origin.y, oz = ray.origin.z;
  const dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
  let best = Infinity, bestFace = -1, bestU = 0, bestV = 0;
  for (let f = 0; f + 2 < count; f += 3) {
    const a = 3 * idx[f], b = 3 * idx[f + 1], c = 3 * idx[f + 2];
    if (a === b) continue; // a deleted slot
    const ax = p[a], ay = p[a + 1], az = p[a + 2];
    const e1x = p[b] - ax, e1y = p[b + 1] - ay, e1z = p[b + 2] - az;
    const e2x = p[c] - ax, e2y = p[c + 1] - ay, e2z = p[c + 2] - az;
    // Möller–Trumbore, both sides.
    const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
    const det = e1x * px + e1y * py + e1z * pz;
    if (det > -EPS && det < EPS) continue;
    const inv = 1 / det;
    const tx = ox - ax, ty = oy - ay, tz = oz - az;
    const u = (tx * px + ty * py + tz * pz) * inv;
    if (u < 0 || u > 1) continue;
    const qx = ty * e1z - tz * e1y, qy = tz * e1x - tx * e1z, qz = tx * e1y - ty * e1x;
    const v = (dx * qx + dy * qy + dz * qz) * inv;
    if (v < 0 || u + v > 1) continue;
    const t = (e2x * qx + e2y * qy + e2z * qz) * inv;
    if (t > 0 && t < best) {
      best = t;
      bestFace = f;
      bestU = u;
      bestV = v;
    }
  }
  if (bestFace < 0) return null;
  const point = new THREE.Vector3(ox + dx * best, oy + dy * best, oz + dz * best);
  const normal = hitNormal(p, nrm, idx, bestFace, bestU, bestV);
  if (normal.x * dx + normal.y * dy + normal.z * dz > 0) normal.negate();
  return { point, normal, distance: best };
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
