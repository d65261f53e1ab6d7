// The three.js side of the core's RenderBuffers, written into a BufferGeometry that is not ours to
// replace (the host's mesh.geometry): positions, normals, the mask and indices per vertex/face SLOT, and
// optionally a wireframe LineSegments geometry sharing the positions. apply() copies only the dirty
// ranges the core reports out of wasm memory and marks them with addUpdateRange, so the GPU upload
// follows the brushed region, not the mesh. The core's buffers grow with headroom; when their
// capacity changes the geometry keeps its identity and gets new attributes (its old GPU buffers
// are released first through geometry.dispose(), which three.js allows on a geometry still in use).
// Views into wasm memory are built from the reported pointers right here, after the call that
// produced them: memory growth detaches every older view.
import * as THREE from 'three';
import { SlotRayTree } from './slot-ray-tree.js';
import { attachRayTree } from './surface-raycast.js';

const corner = new THREE.Vector3(); // scratch: apply() allocates nothing per frame

export class MeshBuffers {
  // geometry: the BufferGeometry to keep in step; lines: also keep a wireframe index (this.lines).
  constructor(Module, geometry, { lines = false } = {}) {
    this.M = Module;
    this.geometry = geometry;
    this.lines = lines ? new THREE.BufferGeometry() : null;
    this.vertexCapacity = 0;
    this.faceCapacity = 0;
    this.vertexCount = 0;
    this.faceCount = 0;
    // Bounds of the live slots, grown by the box of each update's written positions (ch.box) and
    // measured again only after a rebuild (which reports all of them) or a reallocation: no pass
    // over every vertex per stroke. Vertices moved inwards or deleted leave it a little large.
    this.bounds = new THREE.Box3();
    // Picking (surface-raycast.js) over the face slots: told here which slots each update changed.
    this.rayTree = new SlotRayTree();
    attachRayTree(geometry, this.rayTree);
  }

  get allocated() { return this.vertexCapacity > 0; }

  // ch: the object Session.changes()/grabDrag()/brushStamp() returns. True when anything changed.
  apply(ch) {
    if (!ch) return false;
    const heap = this.M.HEAPU8.buffer;
    const pos = new Float32Array(heap, ch.positionsPtr, ch.vertexCount * 3);
    const nrm = new Float32Array(heap, ch.normalsPtr, ch.vertexCount * 3);
    const msk = new Float32Array(heap, ch.masksPtr, ch.vertexCount);
    const idx = new Uint32Array(heap, ch.indicesPtr, ch.faceCount * 3);
    const fresh = !this.allocated || ch.reallocated ||
      ch.vertexCapacity !== this.vertexCapacity || ch.faceCapacity !== this.faceCapacity;
    if (fresh) this.allocate(ch.vertexCapacity, ch.faceCapacity);
    const vb = fresh ? 0 : ch.vertexBegin;
    const ve = fresh ? ch.vertexCount : ch.vertexEnd;
    const fb = fresh ? 0 : ch.faceBegin;
    const fe = fresh ? ch.faceCount : ch.faceEnd;
    const g = this.geometry;
    if (ve > vb) {
      copyRange(g.attributes.position, pos, 3 * vb, 3 * ve, fresh);
      copyRange(g.attributes.normal, nrm, 3 * vb, 3 * ve, fresh);
      copyRange(g.attributes.mask, msk, vb, ve, fresh);
    }
    if (fresh || ch.rebuilt || ch.allFacesDirty || ch.allFacesDirty === undefined) {
      this.rayTree.invalidateAll(ch.rebuilt); // a rebuilt mesh (load, whole remesh) is sorted again
    } else if (ch.dirtyFaceCount > 0) {
      this.rayTree.invalidate(new Uint32Array(heap, ch.dirtyFacesPtr, ch.dirtyFaceCount));
    }
    if (fe > fb && (fresh || ch.indicesChanged)) {
      copyRange(g.index, idx, 3 * fb, 3 * fe, fresh);
      if (this.lines) this.writeLines(idx, fb, fe, fresh);
    }
    this.vertexCount = ch.vertexCount;
    this.faceCount = ch.faceCount;
    this.growBounds(ch, fresh);
    g.setDrawRange(0, 3 * ch.faceCount);
    if (this.lines) this.lines.setDrawRange(0, 6 * ch.faceCount);
    return fresh || ve > vb || fe > fb;
  }

  // New attributes of the core's capacities, in the same geometry objects. Every other attribute
  // (uv, color, ...) goes: remeshing changes the vertices, so they would no longer match.
  allocate(vertexCapacity, faceCapacity) {
    const g = this.geometry;
    g.dispose(); // frees the old GPU buffers; three.js uploads the new ones at the next render
    for (const name of Object.keys(g.attributes)) g.deleteAttribute(name);
    g.morphAttributes = {};
    g.clearGroups();
    const dynamic = (array, size) => new THREE.BufferAttribute(array, size).setUsage(THREE.DynamicDrawUsage);
    const position = dynamic(new Float32Array(3 * vertexCapacity), 3);
    g.setAttribute('position', position);
    g.setAttribute('normal', dynamic(new Float32Array(3 * vertexCapacity), 3));
    // The sculpting mask per vertex (0..1), for a tint (viewer.js: addMaskTint; hosts may use it too).
    g.setAttribute('mask', dynamic(new Float32Array(vertexCapacity), 1));
    g.setIndex(dynamic(new Uint32Array(3 * faceCapacity), 1));
    if (this.lines) {
      this.lines.dispose();
      this.lines.setAttribute('position', position); // shared: a moved vertex moves its wire too
      this.lines.setIndex(dynamic(new Uint32Array(6 * faceCapacity), 1));
    }
    this.vertexCapacity = vertexCapacity;
    this.faceCapacity = faceCapacity;
    this.rayTree.resize(faceCapacity);
  }

  // Three segments per face slot (each interior edge is drawn twice: a small price for updating the
  // wireframe by face range, in step with the triangles, instead of rebuilding an edge list).
  writeLines(idx, fb, fe, fresh) {
    const attr = this.lines.index;
    const out = attr.array;
    for (let f = fb; f < fe; f++) {
      const a = idx[3 * f], b = idx[3 * f + 1], c = idx[3 * f + 2];
      const o = 6 * f;
      out[o] = a; out[o + 1] = b; out[o + 2] = b; out[o + 3] = c; out[o + 4] = c; out[o + 5] = a;
    }
    if (!fresh) attr.addUpdateRange(6 * fb, 6 * (fe - fb));
    attr.needsUpdate = true;
  }

  growBounds(ch, fresh) {
    const b = this.bounds;
    if (ch.rebuilt) b.makeEmpty(); // the box holds every live vertex
    if (ch.box) {
      b.expandByPoint(corner.set(ch.box[0], ch.box[1], ch.box[2]));
      b.expandByPoint(corner.set(ch.box[3], ch.box[4], ch.box[5]));
    }
    if (fresh && !ch.rebuilt) this.measureBounds(); // new arrays after an incremental update (rare)
  }

  // Axis-aligned box of the first vertexCount slots, one pass over them.
  measureBounds() {
    const box = this.bounds.makeEmpty();
    if (!this.allocated) return;
    const p = this.geometry.attributes.position.array;
    const v = new THREE.Vector3();
    for (let i = 0; i < this.vertexCount; i++) box.expandByPoint(v.fromArray(p, 3 * i));
  }

  // Axis-aligned box of the mesh (this.bounds: it may be a little larger than the live mesh, see
  // the constructor).
  boundingBox(box = new THREE.Box3()) {
    return box.copy(this.bounds);
  }

  // The geometry's boundingBox/boundingSphere from the live slots (three.js would measure the
  // whole capacity, unused zeros included), for the host's culling and raycasting.
  updateBounds() {
    const g = this.geometry;
    g.boundingBox = this.boundingBox(g.boundingBox || new THREE.Box3());
    g.boundingSphere = g.boundingBox.getBoundingSphere(g.boundingSphere || new THREE.Sphere());
  }

  // Only the wireframe geometry is ours; the surface geometry belongs to the caller.
  dispose() {
    if (this.lines) this.lines.dispose();
  }
}

function copyRange(attr, src, begin, end, fresh) {
  attr.array.set(src.subarray(begin, end), begin);
  if (!fresh) attr.addUpdateRange(begin, end - begin);
  attr.needsUpdate = true;
}
