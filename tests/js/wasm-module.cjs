// Shared by the node:test files of the WebAssembly module (not a test itself: node --test only runs
// *.test.* files). Finds the module (public/wasm, or ADASCULPT_WASM_DIR), says why tests skip when it
// is missing, and loads it. CommonJS: the MODULARIZE build is CommonJS in node, and node 20's fetch
// cannot read a file path, so the wasm bytes go in as wasmBinary.
const fs = require('node:fs');
const path = require('node:path');

const root = path.join(__dirname, '..', '..');
const wasmDir = path.resolve(root, process.env.ADASCULPT_WASM_DIR || path.join('public', 'wasm'));
const haveWasm = fs.existsSync(path.join(wasmDir, 'adasculpt.wasm'));
const skip = !haveWasm && `no wasm module in ${wasmDir} (scripts/build.sh wasm)`;
const sphereObj = fs.readFileSync(path.join(root, 'public', 'models', 'sphere.obj'));

// The module instance, or null without a build (tests then skip).
async function loadModule() {
  if (!haveWasm) return null;
  const create = require(path.join(wasmDir, 'adasculpt.js'));
  return create({ wasmBinary: fs.readFileSync(path.join(wasmDir, 'adasculpt.wasm')) });
}

// fn(session) on a new Session holding the default sphere; the session is deleted after.
function withSphere(Module, fn) {
  const s = new Module.Session();
  try {
    s.loadBytes(new Uint8Array(sphereObj), 'sphere.obj');
    return fn(s);
  } finally {
    s.delete();
  }
}

module.exports = { root, wasmDir, haveWasm, skip, sphereObj, loadModule, withSphere };
