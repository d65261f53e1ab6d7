// A 2M-triangle mesh in the browser (issue 18): it loads, a brush stroke with the mouse sculpts it,
// Ctrl+Z brings back exactly the loaded mesh (same export bytes), and the autosave (larger than
// IndexedDB takes in one value: it is stored in pieces) writes and restores. The mesh is a torus
// generated here (1000 x 1000 quads, binary PLY, 38 MB) and served by a route, so nothing large is
// committed. Figures are printed (load, stroke, undo, autosave and restore times).
import { test, expect } from '@playwright/test';
import { open, watchErrors } from './helpers.mjs';

const AROUND = 1000, ALONG = 1000;  // 2 x AROUND x ALONG triangles

// A torus (radii 1 and 0.35) as binary little-endian PLY: float positions, uchar-count int faces.
function torusPly() {
  const nv = AROUND * ALONG, nf = 2 * nv;
  const header = Buffer.from(`ply\nformat binary_little_endian 1.0\nelement vertex ${nv}\n` +
    'property float x\nproperty float y\nproperty float z\n' +
    `element face ${nf}\nproperty list uchar int vertex_indices\nend_header\n`, 'latin1');
  const body = Buffer.alloc(nv * 12 + nf * 13);
  let o = 0;
  for (let j = 0; j < ALONG; j++) {
    const u = (2 * Math.PI * j) / ALONG;
    for (let i = 0; i < AROUND; i++) {
      const v = (2 * Math.PI * i) / AROUND, r = 1 + 0.35 * Math.cos(v);
      body.writeFloatLE(r * Math.cos(u), o); body.writeFloatLE(r * Math.sin(u), o + 4);
      body.writeFloatLE(0.35 * Math.sin(v), o + 8);
      o += 12;
    }
  }
  const id = (i, j) => (j % ALONG) * AROUND + (i % AROUND);
  const tri = (a, b, c) => { body.writeUInt8(3, o); body.writeInt32LE(a, o + 1); body.writeInt32LE(b, o + 5); body.writeInt32LE(c, o + 9); o += 13; };
  for (let j = 0; j < ALONG; j++)
    for (let i = 0; i < AROUND; i++) {
      tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return Buffer.concat([header, body]);
}

// SHA-256 of the current mesh's export, computed in the page (the bytes never cross to node).
const meshDigest = (page) => page.evaluate(async () => {
  const bytes = await window.app.export('off');
  const d = new Uint8Array(await crypto.subtle.digest('SHA-256', bytes));
  return Array.from(d, (b) => b.toString(16).padStart(2, '0')).join('');
});

test('a 2M-triangle mesh loads, takes a stroke with the mouse, undoes exactly and autosaves', async ({ page }) => {
  test.setTimeout(240_000);
  const errors = watchErrors(page);
  const ply = torusPly();
  await page.route('**/large-torus.ply', (route) => route.fulfill({ body: ply, contentType: 'application/octet-stream' }));
  await open(page);

  const t0 = Date.now();
  const loaded = await page.evaluate(() => window.app.load('/large-torus.ply'));
  const loadMs = Date.now() - t0;
  expect(loaded.faces).toBe(2 * AROUND * ALONG);
  const before = await meshDigest(page);
  // The whole state once (132 MB, stored in pieces): later steps are saved as small records.
  const t5 = Date.now();
  await page.evaluate(() => window.app.autosave.flush());
  const wholeStateMs = Date.now() - t5;

  // Draw across the front of the framed torus with the mouse.
  await page.keyboard.press('2');  // Draw
  await page.evaluate(() => window.app.setParams({ radius: '4%', strength: 0.6 }));
  const box = await page.locator('canvas').boundingBox();
  const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
  const pick = await page.evaluate(([x, y]) => window.app.sculptor.surfacePoint(x, y), [cx - box.width * 0.2, cy]);
  expect(pick, 'the stroke starts on the torus').toBeTruthy();
  const t1 = Date.now();
  await page.mouse.move(cx - box.width * 0.2, cy);
  await page.mouse.down();
  for (let k = 1; k <= 8; k++) await page.mouse.move(cx - box.width * 0.2, cy - k * 6);
  await page.mouse.up();
  // The stroke's history step is recorded when the last frame has run; on a loaded 2-core CI
  // machine that took more than the default 5 s once (the figure printed below says how long).
  await expect.poll(() => page.evaluate(() => window.app.session.canUndo()), { timeout: 60_000 }).toBe(true);
  const strokeMs = Date.now() - t1;
  const sculpted = await meshDigest(page);
  expect(sculpted).not.toBe(before);

  // The step is autosaved (the debounced write may already have run: then flush has nothing to do).
  const flush = await page.evaluate(async () => {
    const t = performance.now();
    const wrote = await window.app.autosave.flush();
    return { wrote, ms: performance.now() - t, toasts: document.querySelector('.adasculpt-toasts')?.innerText ?? '' };
  });
  expect(flush.toasts, 'no autosave error').not.toContain('Autosave failed');
  await expect.poll(() => page.evaluate(async () => (await window.app.autosave.saved())?.changes ?? 0),
    { timeout: 60_000 }).toBeGreaterThanOrEqual(1);
  const record = await page.evaluate(() => window.app.autosave.saved());
  expect(record.faces).toBeGreaterThan(2 * AROUND * ALONG - 100_000);
  expect(record.lastBytes).toBeLessThan(16 * 2 ** 20);
  const autosaveMs = flush.wrote ? `${flush.ms.toFixed(0)} ms` : 'written before the flush,';

  const t3 = Date.now();
  await page.keyboard.press('Control+z');
  await expect.poll(() => page.evaluate(() => window.app.session.canUndo()), { timeout: 60_000 }).toBe(false);
  const undoMs = Date.now() - t3;
  expect(await meshDigest(page)).toBe(before);
  // The autosave after the undo reads back (its pieces joined) to the same mesh, the stroke redoable.
  await page.evaluate(() => window.app.autosave.flush());
  const t4 = Date.now();
  const restored = await page.evaluate(() => window.app.autosave.restore());
  const restoreMs = Date.now() - t4;
  expect(restored.faces).toBe(2 * AROUND * ALONG);
  expect(await meshDigest(page)).toBe(before);
  expect(await page.evaluate(() => window.app.session.canRedo())).toBe(true);
  const memoryBytes = await page.evaluate(() => window.app.session.memoryBytes());
  console.log(`2M triangles: load ${loadMs} ms, stroke ${strokeMs} ms (with rendering), autosave of the step ` +
    `${autosaveMs} ${(record.lastBytes / 1024).toFixed(0)} kB (whole state ${wholeStateMs} ms), undo ${undoMs} ms, restore ${restoreMs} ms; history + mesh ${(memoryBytes / 2 ** 20).toFixed(0)} MB`);
  expect(errors).toEqual([]);
});
