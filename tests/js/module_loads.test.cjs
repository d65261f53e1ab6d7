// Smoke test of the WebAssembly build (public/wasm/adasculpt.{js,wasm}, made by `scripts/build.sh wasm`).
// CommonJS on purpose: the MODULARIZE build is a CommonJS module in node. Node 20's global fetch cannot load
// a file path, so the wasm bytes are handed over as wasmBinary.
const test = require('node:test');
const assert = require('node:assert');
const fs = require('node:fs');
const path = require('node:path');

const root = path.join(__dirname, '..', '..');
const wasmDir = path.join(root, 'public', 'wasm');
const hasBindings = fs.existsSync(path.join(root, 'cpp', 'bindings')) &&
  fs.readdirSync(path.join(root, 'cpp', 'bindings')).some((f) => f.endsWith('.cpp'));

test('module loads', { skip: !hasBindings && 'no cpp/bindings/*.cpp yet: no wasm module is built' }, async () => {
  const createAdasculptModule = require(path.join(wasmDir, 'adasculpt.js'));
  assert.strictEqual(typeof createAdasculptModule, 'function');
  const M = await createAdasculptModule({ wasmBinary: fs.readFileSync(path.join(wasmDir, 'adasculpt.wasm')) });
  assert.ok(M, 'module object');
  assert.strictEqual(typeof M._malloc, 'function');
  assert.strictEqual(typeof M._free, 'function');
  assert.ok(M.HEAPF32 instanceof Float32Array);
});
