// The three.js side of the core's RenderBuffers: a BufferGeometry (positions, normals, indices per
// vertex/face SLOT) and a wireframe LineSegments geometry sharing its positions. apply() copies only
// the dirty ranges the core reports out of wasm memory and marks them with addUpdateRange, so the
// GPU upload follows the ROI, not the mesh; when the core's capacity grows, new attributes (a new
// geometry) are made. Views into wasm memory are built from the reported pointers right here,
// after the call that produced them: memory growth detaches every older view.
import * as THREE from 'three';

export class MeshBuffers {
  constructor(Module) {
    this.M = Module;
    this.geometry = null;
    this.lines = null;
    this.vertexCapacity = 0;
    this.faceCapacity = 0;
    this.vertexCount = 0;
    this.faceCount = 0;
    this.onGeometry = null; // (geometry, lineGeometry) when the geometries were replaced
  }

  // ch: the object Session.changes()/grabDrag() returns. Returns true when anything changed.
  apply(ch) {
    if (!ch) return false;
    const heap = this.M.HEAPU8.buffer;
    const pos = new Float32Array(heap, ch.positionsPtr, ch.vertexCount * 3);
    const nrm = new Float32Array(heap, ch.normalsPtr, ch.vertexCount * 3);
    const idx = new Uint32Array(heap, ch.indicesPtr, ch.faceCount * 3);
    const fresh = !this.geometry || ch.reallocated ||
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
    }
    if (fe > fb && (fresh || ch.indicesChanged)) {
      copyRange(g.index, idx, 3 * fb, 3 * fe, fresh);
      this.writeLines(idx, fb, fe, fresh);
    }
    this.vertexCount = ch.vertexCount;
    this.faceCount = ch.faceCount;
    g.setDrawRange(0, 3 * ch.faceCount);
    this.lines.setDrawRange(0, 6 * ch.faceCount);
    if (fresh && this.onGeometry) this.onGeometry(this.geometry, this.lines);
    return fresh || ve > vb || fe > fb;
  }

  allocate(vertexCapacity, faceCapacity) {
    const old = [this.geometry, this.lines];
    const g = new THREE.BufferGeometry();
    const position = new THREE.BufferAttribute(new Float32Array(3 * vertexCapacity), 3).setUsage(THREE.DynamicDrawUsage);
    const normal = new THREE.BufferAttribute(new Float32Array(3 * vertexCapacity), 3).setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('position', position);
    g.setAttribute('normal', normal);
    g.setIndex(new THREE.BufferAttribute(new Uint32Array(3 * faceCapacity), 1).setUsage(THREE.DynamicDrawUsage));
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', position); // shared: a moved vertex moves its wire too
    lines.setIndex(new THREE.BufferAttribute(new Uint32Array(6 * faceCapacity), 1).setUsage(THREE.DynamicDrawUsage));
    this.geometry = g;
    this.lines = lines;
    this.vertexCapacity = vertexCapacity;
    this.faceCapacity = faceCapacity;
    for (const o of old) if (o) o.dispose();
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

  // Axis-aligned box of the first vertexCount slots (after a load or a grab there is no garbage).
  boundingBox() {
    const box = new THREE.Box3();
    if (!this.geometry) return box;
    const p = this.geometry.attributes.position.array;
    const v = new THREE.Vector3();
    for (let i = 0; i < this.vertexCount; i++) box.expandByPoint(v.fromArray(p, 3 * i));
    return box;
  }

  dispose() {
    if (this.geometry) this.geometry.dispose();
    if (this.lines) this.lines.dispose();
    this.geometry = this.lines = null;
  }
}

function copyRange(attr, src, begin, end, fresh) {
  attr.array.set(src.subarray(begin, end), begin);
  if (!fresh) attr.addUpdateRange(begin, end - begin);
  attr.needsUpdate = true;
}
