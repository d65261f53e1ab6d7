// SlotRayTree: boxes over the render buffers' face slots, for picking the surface under the pointer
// without testing every triangle (a brute-force pass cost ~20-30 ms per pointer move at 1.1M triangles).
//
// Why not a BVH library (three-mesh-bvh): its trees are built for a fixed set of triangles, so a
// stroke that appends face slots and rewrites others every frame would force a rebuild of the whole
// tree. Here the leaves are groups of 32 face slots: when a mesh arrives its slots are sorted along a
// Morton curve of their centroids (loaded files list triangles in any order), and slots appended
// later follow in slot order (a stroke appends them all in its brushed region). 32 consecutive leaves
// make a box of the next level, and so on. A changed triangle stays in its slot's leaf, so a frame
// costs the boxes above the slots it changed (the core lists them: RenderChanges.dirtyFacesPtr).
// Changes are only marked when they arrive (apply() of every frame); the boxes are refitted at the
// next ray, so frames nobody picks in cost nothing more.
//
// Exact: the boxes are padded (relative 1e-6, far above rounding), a box is skipped only when the
// ray enters it beyond the best hit so far, and every triangle is tested as by the brute force
// (intersectSlot); among equally near hits the lowest slot wins, as in the brute force's slot order.

const FAN = 32;  // slots per leaf box, boxes per parent box
const SHIFT = 5; // log2(FAN)
const EPS = 1e-12;

// Möller–Trumbore, both sides, for face slot f (idx offset 3f). Returns t (> 0) of the hit or -1;
// the barycentrics go to out[0], out[1]. Deleted slots (0,0,0) are skipped. Shared by the tree and
// the brute force so both find the same hits.
export function intersectSlot(p, idx, f, ray, out) {
  const o = 3 * f;
  const a = 3 * idx[o], b = 3 * idx[o + 1], c = 3 * idx[o + 2];
  if (a === b) return -1;
  const ax = p[a], ay = p[a + 1], az = p[a + 2];
  const e1x = p[b] - ax, e1y = p[b + 1] - ay, e1z = p[b + 2] - az;
  const e2x = p[c] - ax, e2y = p[c + 1] - ay, e2z = p[c + 2] - az;
  const dx = ray.dx, dy = ray.dy, dz = ray.dz;
  const px = dy * e2z - dz * e2y, py = dz * e2x - dx * e2z, pz = dx * e2y - dy * e2x;
  const det = e1x * px + e1y * py + e1z * pz;
  if (det > -EPS && det < EPS) return -1;
  const inv = 1 / det;
  const tx = ray.ox - ax, ty = ray.oy - ay, tz = ray.oz - az;
  const u = (tx * px + ty * py + tz * pz) * inv;
  if (u < 0 || u > 1) return -1;
  const qx = ty * e1z - tz * e1y, qy = tz * e1x - tx * e1z, qz = tx * e1y - ty * e1x;
  const v = (dx * qx + dy * qy + dz * qz) * inv;
  if (v < 0 || u + v > 1) return -1;
  const t = (e2x * qx + e2y * qy + e2z * qz) * inv;
  if (!(t > 0)) return -1;
  out[0] = u;
  out[1] = v;
  return t;
}

export class SlotRayTree {
  constructor() {
    this.capacity = 0;   // face slots the levels cover
    this.levels = [];    // per level: {boxes: Float64Array(6n), mark: Uint8Array(n), list: Uint32Array(n), dirty: 0}
    this.order = new Uint32Array(0); // the slots in leaf order (leaf b: order[32b .. 32b + 31])
    this.rank = new Uint32Array(0);  // slot -> its place in order
    this.allDirty = true;  // refit every box at the next update
    this.unsorted = true;  // and sort the slots first (a new mesh)
    this.uv = new Float64Array(2); // scratch of intersectSlot
    this.refitted = 0;   // leaf boxes refitted by the last update (tests: work follows the change)
  }

  // Buffers of `faceCapacity` slots (MeshBuffers.allocate). Growing keeps the slots' leaves (the new
  // slots follow in slot order); everything is refitted at the next ray.
  resize(faceCapacity) {
    if (faceCapacity !== this.capacity) {
      const order = new Uint32Array(faceCapacity), rank = new Uint32Array(faceCapacity);
      const kept = Math.min(this.capacity, faceCapacity);
      if (faceCapacity > this.capacity) {
        order.set(this.order);
        rank.set(this.rank);
      } else {
        this.unsorted = true; // shrunk (a new mesh): sorted again anyway
      }
      for (let f = kept; f < faceCapacity; f++) order[f] = rank[f] = f;
      this.order = order;
      this.rank = rank;
      this.capacity = faceCapacity;
      this.levels = [];
      let n = Math.max(1, Math.ceil(faceCapacity / FAN));
      for (;;) {
        this.levels.push({ boxes: new Float64Array(6 * n), mark: new Uint8Array(n), list: new Uint32Array(n), dirty: 0 });
        if (n <= FAN) break;
        n = Math.ceil(n / FAN);
      }
    }
    this.invalidateAll();
  }

  // Every box is refitted at the next update; with `newMesh`, the slots are sorted again first.
  invalidateAll(newMesh = false) {
    this.allDirty = true;
    if (newMesh) this.unsorted = true;
    for (const l of this.levels) {
      if (l.dirty) l.mark.fill(0);
      l.dirty = 0;
    }
  }

  // slots: the face slots whose triangle changed (any array-like of slot numbers, duplicates fine).
  invalidate(slots, count = slots.length) {
    if (this.allDirty || !this.levels.length) return;
    const leaf = this.levels[0];
    const rank = this.rank;
    for (let i = 0; i < count; i++) {
      const f = slots[i];
      if (f >= this.capacity) continue;
      const b = rank[f] >>> SHIFT;
      if (leaf.mark[b]) continue;
      leaf.mark[b] = 1;
      leaf.list[leaf.dirty++] = b;
    }
  }

  // Brings the boxes up to date with the buffers: p = positions (xyz per vertex slot), idx = indices
  // (3 per face slot), faceCount = the live slots (those past it count as empty).
  update(p, idx, faceCount) {
    if (!this.levels.length) return;
    const leaf = this.levels[0];
    if (this.allDirty) {
      if (this.unsorted) this.sortSlots(p, idx, faceCount);
      const n = leaf.mark.length;
      for (let b = 0; b < n; b++) fitLeaf(leaf.boxes, b, this.order, p, idx, faceCount);
      this.refitted = n;
      for (let k = 1; k < this.levels.length; k++) {
        const below = this.levels[k - 1].boxes, level = this.levels[k];
        for (let b = 0; b < level.mark.length; b++) fitParent(level.boxes, b, below);
      }
      this.allDirty = false;
      return;
    }
    this.refitted = leaf.dirty;
    for (let k = 0; k < this.levels.length; k++) {
      const level = this.levels[k];
      if (!level.dirty) break;
      const up = this.levels[k + 1];
      for (let i = 0; i < level.dirty; i++) {
        const b = level.list[i];
        level.mark[b] = 0;
        if (k === 0) fitLeaf(level.boxes, b, this.order, p, idx, faceCount);
        else fitParent(level.boxes, b, this.levels[k - 1].boxes);
        if (up) {
          const parent = b >>> SHIFT;
          if (!up.mark[parent]) {
            up.mark[parent] = 1;
            up.list[up.dirty++] = parent;
          }
        }
      }
      level.dirty = 0;
    }
  }

  // The live slots along a Morton curve of their centroids (8 bits per axis over their box), the
  // rest after them in slot order. Key = code * 2^29 + slot in one double: a numeric sort of a
  // Float64Array, exact below 2^53 (slots < 2^29).
  sortSlots(p, idx, faceCount) {
    const box = emptyBox(scratchBox);
    for (let f = 0; f < faceCount; f++) {
      const o = 3 * f;
      if (idx[o] !== idx[o + 1]) expandBox(box, p, 3 * idx[o]);
    }
    const lx = box[0], ly = box[1], lz = box[2], hx = box[3], hy = box[4], hz = box[5];
    const span = Math.max(hx - lx, hy - ly, hz - lz) || 1;
    const scale = 255.999 / span;
    const keys = new Float64Array(faceCount);
    const cell = (v, lo) => Math.min(255, Math.max(0, Math.floor((v - lo) * scale)));
    for (let f = 0; f < faceCount; f++) {
      const o = 3 * f;
      let code = 0xffffff; // empty slots last
      if (idx[o] !== idx[o + 1]) {
        const a = 3 * idx[o], b = 3 * idx[o + 1], c = 3 * idx[o + 2];
        code = morton3(cell((p[a] + p[b] + p[c]) / 3, lx), cell((p[a + 1] + p[b + 1] + p[c + 1]) / 3, ly),
          cell((p[a + 2] + p[b + 2] + p[c + 2]) / 3, lz));
      }
      keys[f] = code * 536870912 + f;
    }
    keys.sort();
    for (let i = 0; i < faceCount; i++) {
      const f = keys[i] % 536870912;
      this.order[i] = f;
      this.rank[f] = i;
    }
    for (let f = faceCount; f < this.capacity; f++) this.order[f] = this.rank[f] = f;
    this.unsorted = false;
  }

  // Nearest hit of ray ({ox, oy, oz, dx, dy, dz}) with t > 0 among face slots [0, faceCount):
  // {face, t, u, v} or null. Call update() first.
  raycast(p, idx, faceCount, ray) {
    if (!this.levels.length) return null;
    const inv = [1 / ray.dx, 1 / ray.dy, 1 / ray.dz];
    const s = { best: Infinity, face: -1, u: 0, v: 0, faceCount, p, idx, ray, inv };
    if (!this.scratch || this.scratch.length !== this.levels.length) {
      this.scratch = this.levels.map(() => ({ entry: new Float64Array(FAN), child: new Uint32Array(FAN) }));
    }
    const top = this.levels.length - 1;
    this.visitChildren(top, 0, this.levels[top].mark.length, s);
    return s.face < 0 ? null : { face: s.face, t: s.best, u: s.u, v: s.v };
  }

  // Boxes [first, end) of level k, nearest entry first, so that the best hit is found early and
  // prunes the boxes behind it.
  visitChildren(k, first, end, s) {
    const boxes = this.levels[k].boxes;
    const { entry, child } = this.scratch[k];
    let n = 0;
    for (let c = first; c < end; c++) {
      const e = boxEntry(boxes, c, s.ray, s.inv);
      if (e < 0 || e > s.best) continue;
      let j = n++;
      for (; j > 0 && entry[j - 1] > e; j--) {
        entry[j] = entry[j - 1];
        child[j] = child[j - 1];
      }
      entry[j] = e;
      child[j] = c;
    }
    for (let i = 0; i < n; i++) {
      if (entry[i] > s.best) break; // a tie is still searched: the lower slot wins
      const c = child[i];
      if (k === 0) this.searchLeaf(c, s);
      else this.visitChildren(k - 1, c << SHIFT, Math.min((c + 1) << SHIFT, this.levels[k - 1].mark.length), s);
    }
  }

  searchLeaf(b, s) {
    const end = Math.min((b + 1) << SHIFT, this.capacity);
    for (let i = b << SHIFT; i < end; i++) {
      const f = this.order[i];
      if (f >= s.faceCount) continue;
      const t = intersectSlot(s.p, s.idx, f, s.ray, this.uv);
      if (t > 0 && (t < s.best || (t === s.best && f < s.face))) {
        s.best = t;
        s.face = f;
        s.u = this.uv[0];
        s.v = this.uv[1];
      }
    }
  }
}

// 8-bit cells interleaved into a 24-bit Morton code.
function spread8(v) {
  v = (v | (v << 8)) & 0x00f00f;
  v = (v | (v << 4)) & 0x0c30c3;
  return (v | (v << 2)) & 0x249249;
}
function morton3(x, y, z) {
  return spread8(x) | (spread8(y) << 1) | (spread8(z) << 2);
}

const scratchBox = new Float64Array(6); // lo xyz, hi xyz

function emptyBox(box) {
  box[0] = box[1] = box[2] = Infinity;
  box[3] = box[4] = box[5] = -Infinity;
  return box;
}

// Grows box by the point at p[i..i+2].
function expandBox(box, p, i) {
  const x = p[i], y = p[i + 1], z = p[i + 2];
  if (x < box[0]) box[0] = x;
  if (x > box[3]) box[3] = x;
  if (y < box[1]) box[1] = y;
  if (y > box[4]) box[4] = y;
  if (z < box[2]) box[2] = z;
  if (z > box[5]) box[5] = z;
}

// Box of leaf b: its live slots' corners, padded. An empty leaf gets an inverted box (never hit).
function fitLeaf(boxes, b, order, p, idx, faceCount) {
  const box = emptyBox(scratchBox);
  const end = Math.min((b + 1) << SHIFT, order.length);
  for (let i = b << SHIFT; i < end; i++) {
    const f = order[i];
    if (f >= faceCount) continue;
    const o = 3 * f;
    if (idx[o] === idx[o + 1]) continue; // a deleted slot
    for (let k = 0; k < 3; k++) expandBox(box, p, 3 * idx[o + k]);
  }
  const lx = box[0], ly = box[1], lz = box[2], hx = box[3], hy = box[4], hz = box[5];
  const o = 6 * b;
  if (lx > hx) {
    boxes[o] = boxes[o + 1] = boxes[o + 2] = Infinity;
    boxes[o + 3] = boxes[o + 4] = boxes[o + 5] = -Infinity;
    return;
  }
  // Padding keeps the box conservative against the rounding of the ray and triangle arithmetic.
  const pad = 1e-6 * Math.max(hx - lx, hy - ly, hz - lz, Math.abs(lx), Math.abs(hx), Math.abs(ly),
    Math.abs(hy), Math.abs(lz), Math.abs(hz)) + 1e-30;
  boxes[o] = lx - pad; boxes[o + 1] = ly - pad; boxes[o + 2] = lz - pad;
  boxes[o + 3] = hx + pad; boxes[o + 4] = hy + pad; boxes[o + 5] = hz + pad;
}

function fitParent(boxes, b, below) {
  const o = 6 * b;
  let lx = Infinity, ly = Infinity, lz = Infinity, hx = -Infinity, hy = -Infinity, hz = -Infinity;
  const end = Math.min((b + 1) << SHIFT, below.length / 6);
  for (let c = b << SHIFT; c < end; c++) {
    const i = 6 * c;
    if (below[i] < lx) lx = below[i];
    if (below[i + 1] < ly) ly = below[i + 1];
    if (below[i + 2] < lz) lz = below[i + 2];
    if (below[i + 3] > hx) hx = below[i + 3];
    if (below[i + 4] > hy) hy = below[i + 4];
    if (below[i + 5] > hz) hz = below[i + 5];
  }
  boxes[o] = lx; boxes[o + 1] = ly; boxes[o + 2] = lz;
  boxes[o + 3] = hx; boxes[o + 4] = hy; boxes[o + 5] = hz;
}

// Where the ray (t >= 0) enters box b, or -1 when it misses. An axis the ray is parallel to
// (inverse direction infinite) only checks that the origin lies within the slab. Unrolled: this
// runs for every box visited, and allocates nothing.
function boxEntry(boxes, b, ray, inv) {
  const o = 6 * b;
  if (!(boxes[o] <= boxes[o + 3])) return -1; // empty
  let near = 0, far = Infinity, t0, t1;
  if (Number.isFinite(inv[0])) {
    t0 = (boxes[o] - ray.ox) * inv[0]; t1 = (boxes[o + 3] - ray.ox) * inv[0];
    if (t0 > t1) { const s = t0; t0 = t1; t1 = s; }
    if (t0 > near) near = t0;
    if (t1 < far) far = t1;
  } else if (ray.ox < boxes[o] || ray.ox > boxes[o + 3]) return -1;
  if (Number.isFinite(inv[1])) {
    t0 = (boxes[o + 1] - ray.oy) * inv[1]; t1 = (boxes[o + 4] - ray.oy) * inv[1];
    if (t0 > t1) { const s = t0; t0 = t1; t1 = s; }
    if (t0 > near) near = t0;
    if (t1 < far) far = t1;
  } else if (ray.oy < boxes[o + 1] || ray.oy > boxes[o + 4]) return -1;
  if (Number.isFinite(inv[2])) {
    t0 = (boxes[o + 2] - ray.oz) * inv[2]; t1 = (boxes[o + 5] - ray.oz) * inv[2];
    if (t0 > t1) { const s = t0; t0 = t1; t1 = s; }
    if (t0 > near) near = t0;
    if (t1 < far) far = t1;
  } else if (ray.oz < boxes[o + 2] || ray.oz > boxes[o + 5]) return -1;
  return near > far ? -1 : near;
}
