// Benchmark, not a test (never fails on numbers): a mouse pull on a 100k-triangle model in the real
// page, frame medians in the browser (core phases, render-buffer update, copy, render) beside the
// same session replayed by the core in wasm and by the native CLI. Runs only with ADASCULPT_BENCH=1:
//   ADASCULPT_BENCH=1 npx playwright test e2e/bench.spec.mjs
// ADASCULPT_BENCH_MESH picks the mesh (default ../shared/meshes/dragon.off). Headless Chromium
// renders with SwiftShader (on the CPU), so the render column is not a GPU figure.
import { test } from '@playwright/test';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..');
const mesh = process.env.ADASCULPT_BENCH_MESH || path.join(root, '..', 'shared', 'meshes', 'dragon.off');

const median = (xs) => { const s = [...xs].sort((a, b) => a - b); return s.length ? s[Math.floor(s.length / 2)] : NaN; };

// Opens the page and loads the benchmark mesh into it.
async function openWithMesh(page) {
  await page.goto('/');
  await page.waitForFunction(() => document.documentElement.dataset.ready === 'true');
  const b64 = fs.readFileSync(mesh).toString('base64');
  const loaded = await page.evaluate(async ([data, name]) => {
    const bytes = Uint8Array.from(atob(data), (c) => c.charCodeAt(0));
    return window.app.load(bytes.buffer, name.split('.').pop());
  }, [b64, path.basename(mesh)]);
  console.log(`${path.basename(mesh)}: ${loaded.vertices} vertices, ${loaded.faces} faces`);
  return b64;
}

test('pull on a 100k model: frame medians', async ({ page }) => {
  test.skip(!process.env.ADASCULPT_BENCH, 'set ADASCULPT_BENCH=1');
  test.skip(!fs.existsSync(mesh), `no ${mesh}`);
  test.setTimeout(180_000);
  const b64 = await openWithMesh(page);

  // A person's pull: press on the model centre, move 200 px up over 90 pointer moves.
  const box = await page.locator('canvas').boundingBox();
  const x = box.x + box.width / 2, y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.evaluate(() => window.app.takeFrameLog());
  await page.mouse.down();
  for (let i = 1; i <= 90; i++) {
    await page.mouse.move(x, y - (200 * i) / 90);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  }
  await page.mouse.up();
  const frames = await page.evaluate(() => window.app.takeFrameLog());
  const col = (k) => median(frames.map((f) => f[k])).toFixed(2);
  const phase = (k) => median(frames.map((f) => f.phases[k])).toFixed(2);
  console.log(`browser, mouse pull: ${frames.length} frames; median ms: core ${col('coreMs')} ` +
    `(roi ${phase('roi')}, field ${phase('field')}, refine ${phase('refine')}, deform ${phase('deform')}, remesh ${phase('remesh')}) ` +
    `+ buffers ${col('buffersMs')} + copy ${col('copyMs')} = ${(+col('coreMs') + +col('buffersMs') + +col('copyMs')).toFixed(2)} ` +
    `(+ render ${col('renderMs')} on SwiftShader)`);

  // The same session in the core, in wasm (browser) and native (CLI).
  const st = (await page.evaluate(() => window.app.stats())).settings;
  const session = { version: 1, steps: [{ grab: { center: [0, 0, 1e3], handle_radius: 0.03 * st.diagonal, roi_radius: 0.12 * st.diagonal,
    translate: [0, 0.12 * st.diagonal, 0.12 * st.diagonal], substeps: 60 } }] };
  await page.evaluate(async ([data, name]) => {
    const bytes = Uint8Array.from(atob(data), (c) => c.charCodeAt(0));
    await window.app.load(bytes.buffer, name.split('.').pop());
  }, [b64, path.basename(mesh)]);
  const wasm = await page.evaluate((s) => window.app.replay(s), session);
  console.log(`replay in the browser (wasm): ${wasm.frames} frames, median ${wasm.frameMsMedian.toFixed(2)} ms, p95 ${wasm.frameMsP95.toFixed(2)} ms`);
  const cli = [process.env.ADASCULPT_BUILD_ROOT, 'build'].filter(Boolean)
    .map((r) => path.resolve(root, r, 'native', 'adasculpt')).find((p) => fs.existsSync(p));
  if (cli) {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'adasculpt-bench-'));
    fs.writeFileSync(path.join(dir, 's.json'), JSON.stringify(session));
    const native = JSON.parse(execFileSync(cli, ['replay', mesh, path.join(dir, 's.json'), path.join(dir, 'o.off'), '--json'], { encoding: 'utf8' }));
    fs.rmSync(dir, { recursive: true, force: true });
    console.log(`replay native (${path.relative(root, cli)}): median ${native.frame_ms_median.toFixed(2)} ms, p95 ${native.frame_ms_p95.toFixed(2)} ms; ` +
      `wasm/native ${(wasm.frameMsMedian / native.frame_ms_median).toFixed(2)}x`);
  } else {
    console.log('no native build/native/adasculpt: native column skipped');
  }
});

// A draw stroke with the mouse (key 2) across the model: the frame log (brush frames: stamps, core,
// buffers, copy, render) and the animation-frame interval, which also holds the JS surface raycast.
test('draw stroke on a 100k model: frame medians', async ({ page }) => {
  test.skip(!process.env.ADASCULPT_BENCH, 'set ADASCULPT_BENCH=1');
  test.skip(!fs.existsSync(mesh), `no ${mesh}`);
  test.setTimeout(180_000);
  await openWithMesh(page);
  await page.keyboard.press('2');
  const box = await page.locator('canvas').boundingBox();
  const x = box.x + box.width / 3, y = box.y + box.height / 2; // left of the panel, where the model is drawn
  await page.mouse.move(x, y);
  await page.evaluate(() => {
    window.app.takeFrameLog();
    window.__intervals = [];
    let last = performance.now();
    (function tick(now) { window.__intervals.push(now - last); last = now; window.__raf = requestAnimationFrame(tick); })(last);
  });
  await page.mouse.down();
  for (let i = 1; i <= 90; i++) {
    await page.mouse.move(x + (120 * i) / 90, y - 40 * Math.sin(i / 10));
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  }
  await page.mouse.up();
  const { frames, intervals } = await page.evaluate(() => {
    cancelAnimationFrame(window.__raf);
    return { frames: window.app.takeFrameLog(), intervals: window.__intervals.slice(2) };
  });
  const col = (k) => median(frames.map((f) => f[k])).toFixed(2);
  const phase = (k) => median(frames.map((f) => f.phases[k])).toFixed(2);
  console.log(`browser, draw stroke: ${frames.length} frames, ${phase('stamps')} stamps per frame; median ms: core ${col('coreMs')} ` +
    `(deform ${phase('deform')}, remesh ${phase('remesh')}) + buffers ${col('buffersMs')} + copy ${col('copyMs')} ` +
    `+ render ${col('renderMs')} (SwiftShader) = ${col('totalMs')}; animation frame interval ${median(intervals).toFixed(1)} ms`);
});
