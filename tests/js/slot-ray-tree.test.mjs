// web/slot-ray-tree.js through web/mesh-buffers.js and web/surface-raycast.js, on the wasm module's
// render buffers: the tree's hit is the brute force's (same face slot, same distance, bit for bit) on
// random rays, after loading and after every frame of strokes that split and collapse, and after
// undo and redo; and a stroke's frames refit the leaf boxes around the brushed slots only.
// Loads public/wasm (or ADASCULPT_WASM_DIR); skips without a build.
import test from 'node:test';
import assert from 'node:assert';
import { createRequire } from 'node:module';
import * as THREE from 'three';
import { MeshBuffers } from '../../web/mesh-buffers.js';
import { raycastSurface } from '../../web/surface-raycast.js';

const require = createRequire(import.meta.url);
const { skip, loadModule, withSphere } = require('./wasm-module.cjs');
const M = await loadModule();

// Deterministic rays (no hidden randomness): a small linear congruential generator.
function rays(seed, n) {
  let x = seed >>> 0;
  const rnd = () => ((x = (Math.imul(x, 1664525) + 1013904223) >>> 0) / 4294967296) * 2 - 1;
  const out = [];
  for (let i = 0; i < n; i++) {
    const origin = new THREE.Vector3(rnd(), rnd(), rnd()).normalize().multiplyScalar(3);
    const target = new THREE.Vector3(rnd(), rnd(), rnd()).multiplyScalar(1.1);
    // Every 7th ray along an axis: directions with zero components (parallel slabs).
    const dir = i % 7 === 0 ? new THREE.Vector3(0, 0, origin.z > 0 ? -1 : 1) : target.sub(origin).normalize();
    if (i % 7 === 0) origin.set(rnd() * 0.9, rnd() * 0.9, origin.z);
    out.push(new THREE.Ray(origin, dir));
  }
  return out;
}

// Tree and brute force agree on every ray; returns how many rays hit.
function expectSameHits(geometry, list, where) {
  let hits = 0;
  for (const ray of list) {
    const fast = raycastSurface(geometry, ray);
    const slow = raycastSurface(geometry, ray, { bruteForce: true });
    if (!slow) {
      assert.strictEqual(fast, null, `${where}: the tree hit where the brute force missed`);
      continue;
    }
    hits++;
    assert.ok(fast, `${where}: the tree missed face ${slow.face}`);
    assert.strictEqual(fast.face, slow.face, `${where}: face slot`);
    assert.strictEqual(fast.distance, slow.distance, `${where}: distance`);
  }
  return hits;
}

const ARC = Array.from({ length: 8 }, (_, i) => {
  const a = -0.4 + 0.1 * i;
  return [0.35, Math.sin(a) * Math.sqrt(1 - 0.35 ** 2), Math.cos(a) * Math.sqrt(1 - 0.35 ** 2)];
});

test('the slot tree finds the brute force hit after loading, every stroke frame, undo and redo', { skip }, () => {
  withSphere(M, (s) => {
    const buffers = new MeshBuffers(M, new THREE.BufferGeometry());
    buffers.apply(s.changes());
    const list = rays(7, 300);
    assert.ok(expectSameHits(buffers.geometry, list, 'loaded') > 150, 'most rays hit the sphere');
    const facesBefore = s.changes().faces;
    let frames = 0;
    for (const [k, tool] of ['draw', 'crease', 'flatten', 'inflate'].entries()) {
      s.brushBegin({ tool, radius: 0.25, strength: 0.9, symmetry: 'x', detail: 0.03 + 0.02 * k });
      for (const p of ARC) {
        buffers.apply(s.brushStamp(Float64Array.from([...p.map((c) => c * (1 + 0.02 * k)), 1])));
        expectSameHits(buffers.geometry, rays(100 + frames, 40), `${tool} frame ${frames}`);
        frames++;
      }
      s.brushEnd();
      buffers.apply(s.changes());
      expectSameHits(buffers.geometry, list, `after ${tool}`);
    }
    assert.notStrictEqual(s.changes().faces, facesBefore, 'the strokes changed the topology');
    for (const step of ['undo', 'undo', 'redo', 'undo', 'undo', 'undo', 'redo']) {
      s[step]();
      buffers.apply(s.changes());
      expectSameHits(buffers.geometry, list, `after ${step}`);
    }
  });
});

test('a small stroke refits the leaf boxes of its slots, not all of them', { skip }, () => {
  withSphere(M, (s) => {
    const buffers = new MeshBuffers(M, new THREE.BufferGeometry());
    buffers.apply(s.changes());
    const ray = new THREE.Ray(new THREE.Vector3(0.35, 0, 3), new THREE.Vector3(0, 0, -1));
    assert.ok(raycastSurface(buffers.geometry, ray));
    const leaves = buffers.rayTree.levels[0].mark.length;
    assert.strictEqual(buffers.rayTree.refitted, leaves, 'the first ray after loading fits every leaf');
    s.brushBegin({ tool: 'draw', radius: 0.1, strength: 0.5, symmetry: 'none' });
    buffers.apply(s.brushStamp(Float64Array.from([...ARC[3], 1])));
    s.brushEnd();
    buffers.apply(s.changes());
    assert.ok(raycastSurface(buffers.geometry, ray));
    const refitted = buffers.rayTree.refitted;
    assert.ok(refitted > 0 && refitted < leaves / 4, `refitted ${refitted} of ${leaves} leaves`);
    assert.ok(raycastSurface(buffers.geometry, ray));
    assert.strictEqual(buffers.rayTree.refitted, 0, 'nothing changed: nothing refitted');
  });
});
