// The real page in headless Chromium, driven the way a person does: load, look, drag, rotate/scale,
// undo/redo, open files (input and drop), a malformed file, panel epsilon + whole-mesh remesh.
// Screenshots go to test-results/*.png (check them by eye).
import { test, expect } from '@playwright/test';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { watchErrors, open, stats, save, sameAs, snapshotCanvas, stroke } from './helpers.mjs';

const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..');
const shot = (page, name) => page.screenshot({ path: path.join(root, 'test-results', `${name}.png`) });

// RGB of canvas pixels at fractions of its size (the WebGL canvas keeps its drawing buffer).
async function pixels(page, points) {
  await snapshotCanvas(page);
  return page.evaluate((pts) => {
    const g = window.__canvas2d;
    const { width, height } = g.canvas;
    return pts.map(([fx, fy]) => Array.from(g.getImageData(Math.floor(fx * width), Math.floor(fy * height), 1, 1).data.slice(0, 3)));
  }, points);
}

// Drags with the left button from the canvas centre by (dx, dy); `during` runs mid-drag.
async function dragOnModel(page, dx, dy, during) {
  const box = await page.locator('canvas').boundingBox();
  const x = box.x + box.width / 2, y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + dx / 2, y + dy / 2, { steps: 8 });
  if (during) await during(x + dx / 2, y + dy / 2);
  await page.mouse.move(x + dx, y + dy, { steps: 8 });
  await page.mouse.up();
}

test('loads without console errors and shows the model', async ({ page }) => {
  const errors = watchErrors(page);
  const t0 = Date.now();
  await open(page);
  const s = await stats(page);
  console.log(`first render ${s.firstRenderMs.toFixed(0)} ms after navigation start (test wall ${Date.now() - t0} ms)`);
  expect(s.vertices).toBe(2562);
  expect(s.faces).toBe(5120);
  const [centre, corner] = await pixels(page, [[0.5, 0.5], [0.02, 0.98]]);
  const diff = centre.reduce((acc, v, i) => acc + Math.abs(v - corner[i]), 0);
  expect(diff, `model pixel ${centre} vs background ${corner}`).toBeGreaterThan(60);
  await shot(page, 'app-loaded');
  expect(errors).toEqual([]);
});

test('a mouse drag on the model pulls it; quality stays good', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  const before = await page.evaluate(() => window.app.bounds());
  const v0 = (await stats(page)).vertices;
  await dragOnModel(page, 0, -140);
  await page.waitForTimeout(100);
  const after = await page.evaluate(() => window.app.bounds());
  const s = await stats(page);
  console.log(`after drag: ${s.vertices} vertices, min angle ${s.minAngle.toFixed(2)}, mean min ${s.meanMinAngle.toFixed(2)}, core ${s.coreMs.toFixed(2)} ms`);
  // The handle is on the front of the sphere (the view looks at it from above-right): it moves up
  // and the surface around it follows, so the top of the bounding box rises.
  expect(after.max[1] - before.max[1], 'the surface moved up').toBeGreaterThan(0.05);
  expect(s.vertices).not.toBe(v0);
  expect(s.minAngle).toBeGreaterThan(5);
  expect(s.meanMinAngle).toBeGreaterThan(35);
  expect(s.canUndo).toBe(true);
  await shot(page, 'app-pulled');
  expect(errors).toEqual([]);
});

test('rotate (R) and scale (S) during a drag', async ({ page }) => {
  await open(page);
  await save(page, 'start');
  const v0 = (await stats(page)).vertices;
  // Scale: press S mid-drag, then move right: the handle region grows (the sphere gets a bump).
  await dragOnModel(page, 160, 0, async () => page.keyboard.press('s'));
  expect(await sameAs(page, 'start')).toBe(false);
  expect((await stats(page)).vertices).not.toBe(v0);
  await save(page, 'scaled');
  // Rotate: press R mid-drag, then move: the surface changes again.
  await dragOnModel(page, 120, 40, async () => page.keyboard.press('r'));
  expect(await sameAs(page, 'scaled')).toBe(false);
  const s = await stats(page);
  expect(s.minAngle).toBeGreaterThan(2);
  await shot(page, 'app-rotated-scaled');
});

test('Ctrl+Z and Ctrl+Shift+Z restore the exact states', async ({ page }) => {
  await open(page);
  await save(page, 'start');
  await dragOnModel(page, 40, -120);
  await save(page, 'pulled');
  expect(await sameAs(page, 'start')).toBe(false);
  await page.keyboard.press('Control+z');
  expect(await sameAs(page, 'start')).toBe(true);
  expect((await stats(page)).vertices).toBe(2562);
  await page.keyboard.press('Control+Shift+z');
  expect(await sameAs(page, 'pulled')).toBe(true);
  await shot(page, 'app-redo');
});

test('opens OBJ, STL, PLY and OFF through the file input and by drag-and-drop; export round-trips', async ({ page }, info) => {
  const errors = watchErrors(page);
  await open(page);
  const fandisk = path.join(root, 'public', 'models', 'fandisk.off');
  await page.setInputFiles('input[type=file]', fandisk);
  await expect.poll(async () => (await stats(page)).vertices).toBe(6475);
  await shot(page, 'app-fandisk');
  // Every format, written by the app's own export of the fandisk and read back.
  for (const fmt of ['obj', 'stl', 'ply', 'off']) {
    // base64: a plain array of 600k numbers takes seconds to cross the protocol.
    const b64 = await page.evaluate(async (f) => {
      const bytes = new Uint8Array(await window.app.export(f));
      let bin = '';
      for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
      return btoa(bin);
    }, fmt);
    const file = info.outputPath(`fandisk-export.${fmt}`);
    fs.writeFileSync(file, Buffer.from(b64, 'base64'));
    await page.evaluate(() => window.app.load('models/sphere.obj'));
    await page.setInputFiles('input[type=file]', file);
    await expect.poll(async () => (await stats(page)).vertices, { message: fmt }).toBe(6475);
    expect((await stats(page)).faces).toBe(12946);
  }
  // Drag-and-drop of a file onto the viewer.
  const hemi = fs.readFileSync(path.join(root, 'public', 'models', 'hemisphere.off')).toString('base64');
  await page.evaluate((b64) => {
    const dt = new DataTransfer();
    dt.items.add(new File([Uint8Array.from(atob(b64), (c) => c.charCodeAt(0))], 'hemisphere.off'));
    const target = document.querySelector('.adasculpt-root');
    for (const type of ['dragenter', 'dragover', 'drop']) {
      target.dispatchEvent(new DragEvent(type, { dataTransfer: dt, bubbles: true, cancelable: true }));
    }
  }, hemi);
  await expect.poll(async () => (await stats(page)).vertices).toBe(1861);
  await shot(page, 'app-dropped-hemisphere');
  expect(errors).toEqual([]);
});

test('a file whose faces disagree about the outside opens, repaired, and the message says so', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  // An octahedron with two of its faces written the other way round.
  const off = 'OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n' +
    '3 0 2 4\n3 2 5 0\n3 0 4 3\n3 0 3 5\n3 1 4 2\n3 1 2 5\n3 4 3 1\n3 1 5 3\n';
  await page.setInputFiles('input[type=file]', { name: 'octahedron.off', mimeType: 'application/octet-stream', buffer: Buffer.from(off) });
  await expect.poll(async () => (await stats(page)).faces).toBe(8);
  const toast = page.locator('.adasculpt-toast', { hasText: 'octahedron.off' });
  await expect(toast).toContainText('repaired: reversed 2 face(s) to orient the surface consistently');
  await expect(page.locator('.adasculpt-toast.error')).toHaveCount(0);
  expect(errors).toEqual([]);
});

test('a malformed file shows a message and keeps the mesh', async ({ page }) => {
  await open(page);
  await save(page, 'before');
  const bad = path.join(root, 'tests', 'data', 'malformed', 'obj_index_out_of_range.obj');
  await page.setInputFiles('input[type=file]', bad);
  const toast = page.locator('.adasculpt-toast.error');
  await expect(toast).toBeVisible();
  await expect(toast).toContainText('obj_index_out_of_range.obj');
  console.log(`toast: ${await toast.textContent()}`);
  expect(await sameAs(page, 'before')).toBe(true);
  await shot(page, 'app-malformed');
});

test('epsilon in the panel + remesh whole mesh changes the resolution', async ({ page }) => {
  await open(page);
  const v0 = (await stats(page)).vertices;
  const eps = page.locator('.lil-controller', { hasText: 'epsilon (% diag)' }).locator('input');
  await eps.fill('0.01');
  await eps.press('Enter');
  await expect.poll(async () => (await stats(page)).settings.epsilon / (await stats(page)).settings.diagonal).toBeCloseTo(0.0001, 6);
  await page.getByText('remesh whole mesh').click();
  await expect(page.getByText('remesh whole mesh')).toBeVisible({ timeout: 30_000 }); // back from "remeshing… i/n"
  await expect.poll(async () => (await stats(page)).vertices, { timeout: 30_000 }).toBeGreaterThan(v0 * 1.3);
  const fine = await stats(page);
  console.log(`epsilon 0.01%: ${v0} -> ${fine.vertices} vertices, mean min angle ${fine.meanMinAngle.toFixed(1)}`);
  expect(fine.meanMinAngle).toBeGreaterThan(40);
  // Wireframe on, to look at the triangles.
  await page.locator('.lil-controller', { hasText: 'wireframe' }).locator('input').check();
  await shot(page, 'app-remeshed-wireframe');
  // A larger epsilon coarsens again.
  await eps.fill('0.5');
  await eps.press('Enter');
  await page.getByText('remesh whole mesh').click();
  await expect.poll(async () => (await stats(page)).vertices, { timeout: 30_000 }).toBeLessThan(fine.vertices * 0.7);
});

test('no self-crossings in the panel turns the region crossing guard of the core on; a Pull still sculpts', async ({ page }) => {
  await open(page);
  expect((await stats(page)).settings.guardCrossings).toBe(false);
  await page.locator('.lil-controller', { hasText: 'no self-crossings' }).locator('input').check();
  await expect.poll(async () => (await stats(page)).settings.guardCrossings).toBe(true);
  await save(page, 'before');
  await stroke(page, { dy: -0.6 });
  expect(await sameAs(page, 'before')).toBe(false);
  const after = await stats(page);
  expect(after.settings.guardCrossings).toBe(true);
  expect(after.meanMinAngle).toBeGreaterThan(35);
});

// The embed example and <adasculpt-viewer>: e2e/embed.spec.mjs.

test('dispose frees the app: repeated create/dispose leaves no canvas, listener or error behind', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  const result = await page.evaluate(async () => {
    window.app.dispose();
    const host = document.getElementById('sculpt');
    for (let i = 0; i < 6; i++) {
      const app = await window.createSculptApp(host, { model: 'models/hemisphere.off', keyboard: 'global' });
      if (app.stats().vertices !== 1861) throw new Error(`instance ${i}: ${app.stats().vertices} vertices`);
      app.dispose();
    }
    // A disposed app's keyboard shortcuts are gone: Ctrl+Z on window must not reach it (no error either).
    window.dispatchEvent(new KeyboardEvent('keydown', { key: 'z', ctrlKey: true }));
    return { canvases: document.querySelectorAll('canvas').length, children: host.children.length };
  });
  expect(result).toEqual({ canvases: 0, children: 0 });
  expect(errors).toEqual([]);
});

test('while dragging, at most one call into wasm per animation frame', async ({ page }) => {
  await open(page);
  await page.evaluate(() => {
    // Count every Session method call, per animation frame.
    const proto = Object.getPrototypeOf(window.app.session);
    window.__calls = { n: 0, frames: [] };
    for (const k of Object.getOwnPropertyNames(proto)) {
      const f = proto[k];
      if (k === 'constructor' || typeof f !== 'function') continue;
      proto[k] = function (...a) { window.__calls.n++; return f.apply(this, a); };
    }
    (function tick() {
      window.__calls.frames.push(window.__calls.n);
      window.__calls.n = 0;
      requestAnimationFrame(tick);
    })();
  });
  const box = await page.locator('canvas').boundingBox();
  const x = box.x + box.width / 2, y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down(); // pick + grabBegin happen here, in the event handler
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.evaluate(() => { window.__calls.frames = []; });
  for (let i = 1; i <= 30; i++) {
    await page.mouse.move(x + i * 2, y - i * 4);
    if (i % 3 === 0) await page.evaluate(() => new Promise((r) => requestAnimationFrame(r)));
  }
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const frames = await page.evaluate(() => window.__calls.frames);
  await page.mouse.up();
  console.log(`wasm calls per frame while dragging: ${JSON.stringify(frames)}`);
  expect(Math.max(...frames)).toBe(1);
  expect(frames.reduce((a, b) => a + b, 0)).toBeGreaterThan(3);
});
