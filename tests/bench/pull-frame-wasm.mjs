// The pull scene of tests/bench/pull_frame_bench.cpp in the WebAssembly module (node): the raw
// dragon loaded, remeshed as the scene says, then the same grab several times (each undone), each
// run reporting the core time per frame (Session.replay's frame_ms_*: the time inside the wasm
// call, what a browser frame spends in the core). Prints one line with the medians over the runs.
//   node tests/bench/pull-frame-wasm.mjs [scene.json] [runs]
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const { loadModule, skip, root } = require('../js/wasm-module.cjs');

const scenePath = process.argv[2] || path.join(root, 'build', 'bench', 'pull-scene.json');
const runs = Number(process.argv[3] || 3);
const dragon = path.join(root, '..', 'shared', 'meshes', 'dragon.off');

const median = (v) => {
  const s = [...v].sort((a, b) => a - b);
  return s.length ? s[Math.floor((s.length - 1) / 2)] : 0;
};

async function main() {
  if (skip) return console.log(`pull (wasm): skipped, ${skip}`);
  if (!fs.existsSync(dragon)) return console.log('pull (wasm): skipped, ../shared/meshes/dragon.off not found');
  if (!fs.existsSync(scenePath)) return console.log(`pull (wasm): skipped, no scene ${scenePath} (adasculpt_bench --benchmark_filter=PullScene)`);
  const scene = JSON.parse(fs.readFileSync(scenePath, 'utf8'));
  const prepare = { version: 1, steps: scene.steps.filter((s) => !s.grab) };
  const pull = { version: 1, steps: scene.steps.filter((s) => s.grab) };
  const Module = await loadModule();
  const session = new Module.Session();
  session.loadBytes(new Uint8Array(fs.readFileSync(dragon)), 'dragon.off');
  session.replay(prepare);
  const figures = [];
  let capped = false;
  for (let i = 0; i < runs; i++) {
    // The bindings return a plain object with camelCase keys (issue 20); the figures keep the
    // core's names below.
    const out = session.replay(pull);
    const r = Object.fromEntries(Object.entries(out).map(([k, v]) => [k.replace(/[A-Z]/g, (c) => `_${c.toLowerCase()}`), v]));
    figures.push(r);
    capped = capped || r.roi_capped;
    session.undo();
  }
  const m = (k) => median(figures.map((r) => r[k]));
  console.log(`pull dragon (wasm core time)       ${figures[0].faces} faces: frame ms median/p95/max ` +
    `${m('frame_ms_median').toFixed(2)} / ${m('frame_ms_p95').toFixed(2)} / ${m('frame_ms_max').toFixed(2)}; ` +
    `phase medians roi ${m('roi_ms_median').toFixed(2)} field ${m('field_ms_median').toFixed(2)} ` +
    `refine ${m('refine_ms_median').toFixed(2)} remesh ${m('remesh_ms_median').toFixed(2)}; ${runs} runs` +
    `${capped ? ' (ROI capped)' : ''}`);
  session.delete();
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
