// Incremental autosave in the WebAssembly module (node): the dragon (or ADASCULPT_BENCH_MESH) loaded,
// one whole state saved, then brush strokes, each followed by Session.saveChanges() as
// web/autosave.js calls it; prints the time and size of the whole state and of each step's record,
// then the restore of the whole state plus the records, checked against the live export.
// ADASCULPT_BENCH_TORUS=2000000: a generated torus of that many triangles instead (the 2M target).
//   node tests/bench/autosave-wasm.mjs [strokes]
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';
import { torusArrays } from './torus.mjs';

const require = createRequire(import.meta.url);
const { loadModule, skip, root } = require('../js/wasm-module.cjs');

const meshPath = process.env.ADASCULPT_BENCH_MESH || path.join(root, '..', 'shared', 'meshes', 'dragon.off');
const strokes = Number(process.argv[2] || 8);
const median = (v) => [...v].sort((a, b) => a - b)[Math.floor((v.length - 1) / 2)];
const ms = (t0) => performance.now() - t0;

// A short stroke path over the surface: the nearest vertices to a line through vertex `seed`.
function strokePath(pos, seed, step, n) {
  const out = [];
  for (let i = 0; i < n; i++) {
    const q = [pos[3 * seed] + i * step, pos[3 * seed + 1], pos[3 * seed + 2]];
    let best = 0, bd = Infinity;
    for (let v = 0; v < pos.length / 3; v++) {
      const d = (pos[3 * v] - q[0]) ** 2 + (pos[3 * v + 1] - q[1]) ** 2 + (pos[3 * v + 2] - q[2]) ** 2;
      if (d < bd) { bd = d; best = v; }
    }
    out.push(pos[3 * best], pos[3 * best + 1], pos[3 * best + 2], 1);
  }
  return Float64Array.from(out);
}

// A torus of about `faces` triangles loaded into the session; returns its name.
function loadTorus(s, faces) {
  const { p, t } = torusArrays(faces);
  s.loadArrays(p, t);
  return `torus-${t.length / 3}`;
}

async function main() {
  if (skip) return console.log(`autosave (wasm): skipped, ${skip}`);
  const torus = Number(process.env.ADASCULPT_BENCH_TORUS || 0);
  if (!torus && !fs.existsSync(meshPath)) return console.log(`autosave (wasm): skipped, ${meshPath} not found`);
  const M = await loadModule();
  const s = new M.Session(), b = new M.Session();
  const name = torus ? loadTorus(s, torus) : path.basename(meshPath);
  if (!torus) s.loadBytes(new Uint8Array(fs.readFileSync(meshPath)), name);
  const faces = s.stats().faces;
  const diag = s.settings().diagonal;
  let t0 = performance.now();
  const state = s.saveState(96 * 2 ** 20);
  const fullMs = ms(t0);
  const records = [], times = [], ends = [];
  const pos = Float32Array.from(s.positions());
  for (let k = 0; k < strokes; k++) {
    const seed = Math.floor(((k * 7919) % 997) / 997 * (pos.length / 3));
    s.brushBegin({ tool: k % 2 ? 'inflate' : 'draw', radius: 0.02 * diag, strength: 0.5 });
    s.brushStamp(strokePath(pos, seed, 0.004 * diag, 8));
    t0 = performance.now();
    s.brushEnd();  // closes the undo step and writes it for the next record (ChangeJournal::commit)
    ends.push(ms(t0));
    if (k === strokes - 2) s.undo();  // an undo mark among the strokes
    t0 = performance.now();
    const r = s.saveChanges();
    times.push(ms(t0));
    if (!r) throw new Error('saveChanges gave no record');
    records.push(r);
  }
  t0 = performance.now();
  b.restoreSaved(state, records);
  const restoreMs = ms(t0);
  const same = Buffer.from(b.exportMesh('ply')).equals(Buffer.from(s.exportMesh('ply')));
  const kb = records.map((r) => r.byteLength / 1024);
  console.log(`autosave ${name} (wasm, ${faces} faces): whole state ${(state.byteLength / 2 ** 20).toFixed(1)} MB ` +
    `in ${fullMs.toFixed(0)} ms; per stroke record median ${median(times).toFixed(2)} ms, max ${Math.max(...times).toFixed(2)} ms, ` +
    `median ${median(kb).toFixed(0)} KB, max ${Math.max(...kb).toFixed(0)} KB (${strokes} strokes; brushEnd, which ` +
    `writes the step, median ${median(ends).toFixed(2)} ms); restore whole state + ` +
    `${records.length} records ${restoreMs.toFixed(0)} ms, ${same ? 'same export bytes' : 'EXPORT DIFFERS'}`);
  s.delete();
  b.delete();
  if (!same) process.exit(1);
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
