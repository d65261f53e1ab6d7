// Wasm heap per triangle (web/memory-estimate.js's BYTES_PER_FACE): a generated torus of F triangles
// loaded in a fresh WebAssembly module (node), then a grab (10 drag frames) and a brush stroke, as a
// user's first minutes do. Prints the module's memory size after each phase divided by F. The heap
// grows in steps and never shrinks, so each figure is an upper bound of what that phase needed.
//   node tests/bench/memory-per-face-wasm.mjs [faces ...]      (default 200000 1000000 2000000)
// Each size runs in its own process, so that one size's heap does not carry into the next.
import { execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import { torusArrays } from './torus.mjs';

const require = createRequire(import.meta.url);
const { loadModule, skip } = require('../js/wasm-module.cjs');
const self = fileURLToPath(import.meta.url);

async function measure(faces) {
  const M = await loadModule();
  const heap = () => M.HEAP8.buffer.byteLength;
  const start = heap();
  const s = new M.Session();
  const { p, t } = torusArrays(faces);
  s.loadArrays(p, t);
  const f = s.stats().faces;
  const afterLoad = heap();
  // A grab on the outer equator: handle 2 % and region 15 % of the diagonal, pulled outwards.
  const diag = s.settings().diagonal;
  s.grabBegin(1.3, 0, 0, 0.02 * diag, 0.15 * diag);
  for (let k = 1; k <= 10; k++) s.grabDrag(0.003 * diag * k, 0, 0, 0, 0, 1, 0, 1);
  s.grabEnd();
  const afterGrab = heap();
  // A draw stroke across the top of the tube.
  s.brushBegin({ tool: 'draw', radius: 0.03 * diag });
  const samples = [];
  for (let k = 0; k < 30; k++) {
    const u = 0.5 + 0.01 * k;
    samples.push(Math.cos(u), Math.sin(u), 0.3, 1);
  }
  s.brushStamp(Float64Array.from(samples));
  s.brushEnd();
  const afterStroke = heap();
  const changed = s.stats().faces - f;  // the grab and the stroke refine: a run that did nothing is no figure
  if (changed === 0) throw new Error('the grab and the stroke changed no faces');
  const per = (bytes) => ((bytes - start) / f).toFixed(0);
  console.log(`memory per face (wasm) ${String(f).padStart(8)} faces: after load ${per(afterLoad)}, ` +
    `after a grab ${per(afterGrab)}, after a stroke ${per(afterStroke)} bytes/face ` +
    `(module memory ${(afterStroke / 2 ** 20).toFixed(0)} MB; ${changed > 0 ? '+' : ''}${changed} faces by the grab and stroke)`);
  s.delete();
}

if (skip) {
  console.log(`memory per face (wasm): skipped, ${skip}`);
} else if (process.argv[2] === '--one') {
  await measure(Number(process.argv[3]));
} else {
  const sizes = process.argv.length > 2 ? process.argv.slice(2).map(Number) : [200000, 1000000, 2000000];
  for (const faces of sizes) {
    process.stdout.write(execFileSync(process.execPath, [self, '--one', String(faces)], { encoding: 'utf8' }));
  }
}
