// node:test of web/memory-estimate.js: triangle counts from headers (PLY, OFF, binary STL) and
// sizes (OBJ, ASCII STL), and the refusal message the page shows for a file too large for it.
import test from 'node:test';
import assert from 'node:assert';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { estimateFaces, checkMemory, BYTES_PER_FACE, MAX_WASM_BYTES, isOutOfMemory } from '../../web/memory-estimate.js';

const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
const enc = (s) => new TextEncoder().encode(s);

test('header counts of the bundled models', () => {
  const fandisk = fs.readFileSync(path.join(root, 'public', 'models', 'fandisk.off'));
  assert.strictEqual(estimateFaces(fandisk.subarray(0, 65536), fandisk.length, 'fandisk.off'), 12946);
  const ply = enc('ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\nelement face 7\n' +
    'property list uchar int vertex_indices\nend_header\n');
  assert.strictEqual(estimateFaces(ply, 1000, 'm.ply'), 7);
  assert.strictEqual(estimateFaces(enc('OFF 10 16 0\n'), 1000, 'mesh'), 16);      // sniffed, counts on the OFF line
  const stl = new Uint8Array(84);
  new DataView(stl.buffer).setUint32(80, 1000, true);
  assert.strictEqual(estimateFaces(stl, 84 + 50 * 1000, 'part.stl'), 1000);
});

test('formats without counts are estimated from the size', () => {
  const sphere = fs.readFileSync(path.join(root, 'public', 'models', 'sphere.obj'));
  const est = estimateFaces(sphere.subarray(0, 65536), sphere.length, 'sphere.obj');
  assert.ok(est > 5120 / 2 && est < 5120 * 2, `OBJ estimate ${est} for 5120 triangles`);
  assert.strictEqual(estimateFaces(enc('solid x\n'), 250 * 1000, 'a.stl'), 1000);
});

test('a file that does not fit is refused with sizes in MB; one that fits is not', () => {
  const huge = checkMemory(enc('ply\nformat ascii 1.0\nelement vertex 5000000\nelement face 10000000\nend_header\n'),
    200, 'huge.ply', 0);
  assert.strictEqual(huge.ok, false);
  assert.strictEqual(huge.faces, 10_000_000);
  assert.match(huge.message, /^huge\.ply: needs about 5246 MB \(10,000,000 triangles\), more than the 2048 MB this page can use; the current mesh is unchanged$/);
  // What the current mesh holds comes off the limit.
  const faces = Math.floor((MAX_WASM_BYTES - 1e6) / BYTES_PER_FACE);
  const head = enc(`OFF\n${faces} ${faces} 0\n`);
  assert.strictEqual(checkMemory(head, 1000, 'a.off', 0).ok, true);
  assert.strictEqual(checkMemory(head, 1000, 'a.off', 100e6).ok, false);
  assert.ok(isOutOfMemory(new Error('std::bad_alloc')));
  assert.ok(!isOutOfMemory(new Error('a.off: line 3: bad vertex')));
});
