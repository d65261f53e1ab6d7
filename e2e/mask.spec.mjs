// Masking (issue 19), with real mouse and keyboard on the default sphere: the mask tool (key M)
// paints, Ctrl erases, the tint shows where the mask is, undo/redo restore it exactly; a masked
// half stays bit-identical through draw, inflate, smooth, pull and snake-hook strokes across it,
// and through an autosave restore. Screenshots: test-results/mask-*.png.
import { test, expect } from '@playwright/test';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { watchErrors, open, snapshotCanvas, stroke, modelOnScreen } from './helpers.mjs';

const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..');
const shot = (page, name) => page.screenshot({ path: path.join(root, 'test-results', `mask-${name}.png`) });
const pressed = (page) => page.locator('.adasculpt-tools button[aria-pressed="true"]');
const maskValues = (page) => page.evaluate(() => Array.from(window.app.mask.values()));
const count = (values, pred) => values.filter(pred).length;

// The fully masked vertices as the lossless OFF export prints them (17 digits: the doubles bit for
// bit), sorted. The mask and the render buffers' float positions are per vertex slot; each masked
// slot is matched to its export line through the float32 rounding of the exported doubles.
const maskedVertices = (page) => page.evaluate(async () => {
  const values = window.app.mask.values();
  const pos = window.app.session.positions();
  const text = new TextDecoder().decode(await window.app.export('off'));
  const lines = text.split('\n').filter((l) => l.trim() && !l.startsWith('#'));
  const nv = Number(lines[1].trim().split(/\s+/)[0]);
  const exact = new Map();
  for (let i = 2; i < 2 + nv; i++) {
    const [x, y, z] = lines[i].trim().split(/\s+/).map(Number);
    exact.set(`${Math.fround(x)},${Math.fround(y)},${Math.fround(z)}`, lines[i].trim());
  }
  const out = [];
  const all = []; // every live vertex with its mask (deleted slots keep stale values: left out)
  for (let i = 0; i < values.length; i++) {
    const key = `${pos[3 * i]},${pos[3 * i + 1]},${pos[3 * i + 2]}`;
    if (exact.has(key)) all.push(`${exact.get(key)} ${values[i]}`);
    if (values[i] === 1) out.push(exact.get(key) ?? `no exported vertex at ${key}`);
  }
  let hash = 0; // of the whole export: did a stroke change anything at all
  for (let i = 0; i < text.length; i++) hash = (hash * 31 + text.charCodeAt(i)) | 0;
  return { lines: out.sort(), all: all.sort(), vertices: nv, hash };
});

// Pixels of the canvas that got darker by more than 40 (sum over RGB) since the snapshot kept as
// window.__before (taken by the first call with keep = true).
const darkened = (page, keep = false) => snapshotCanvas(page).then(() => page.evaluate((k) => {
  const g = window.__canvas2d;
  const now = g.getImageData(0, 0, g.canvas.width, g.canvas.height).data;
  if (k) window.__before = now;
  const b = window.__before;
  let n = 0;
  for (let i = 0; i < now.length; i += 4) if (b[i] + b[i + 1] + b[i + 2] - (now[i] + now[i + 1] + now[i + 2]) > 40) n++;
  return n;
}, keep));

test('mask tool by key M: the mouse paints a tinted mask, Ctrl erases, undo and redo restore it exactly', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  await page.keyboard.press('m');
  expect(await page.evaluate(() => window.app.tool)).toBe('mask');
  await expect(pressed(page)).toHaveText(/Mask/);
  await expect(page.locator('.adasculpt-help')).toContainText('Ctrl/Alt erase');
  await page.evaluate(() => window.app.setParams({ brushRadius: '12%', brushStrength: 1 }));
  expect(await darkened(page, true)).toBe(0);
  expect(count(await maskValues(page), (v) => v > 0)).toBe(0);

  await stroke(page, { fx: -0.5, fy: -0.2, dx: 1.0, dy: 0 });
  const painted = await maskValues(page);
  const full = count(painted, (v) => v === 1);
  console.log(`painted: ${full} vertices fully masked, ${count(painted, (v) => v > 0 && v < 1)} partly, of ${painted.length}`);
  expect(full).toBeGreaterThan(30);
  expect(painted.every((v) => v >= 0 && v <= 1)).toBe(true);
  // The tint: a band of the model is drawn darker.
  const dark = await darkened(page);
  console.log(`tint: ${dark} pixels darker`);
  expect(dark).toBeGreaterThan(1500);
  await shot(page, 'painted');

  // Ctrl held: the same tool erases (part of the band).
  await stroke(page, { fx: -0.5, fy: -0.2, dx: 0.45, dy: 0, modifier: 'Control' });
  const erased = await maskValues(page);
  expect(count(erased, (v) => v === 1)).toBeLessThan(full - 10);
  expect(erased.every((v, i) => v <= painted[i])).toBe(true); // erasing never raises
  expect(await darkened(page)).toBeLessThan(dark);

  // Each stroke is one undo step, exact both ways.
  await page.keyboard.press('Control+z');
  expect(await maskValues(page)).toEqual(painted);
  await page.keyboard.press('Control+Shift+z');
  expect(await maskValues(page)).toEqual(erased);

  // The whole-mask operations of window.app (and the panel's buttons).
  await page.evaluate(() => window.app.mask.invert());
  const inverted = await maskValues(page);
  expect(inverted.map((v, i) => Math.abs(v - (1 - erased[i])) < 1e-6).every(Boolean)).toBe(true);
  await page.getByText('clear mask').click();
  expect(count(await maskValues(page), (v) => v !== 0)).toBe(0);
  expect(await darkened(page)).toBe(0);
  // (lil-gui keeps the keys its buttons hear: a click on the canvas beside the model gives them back)
  const m = await modelOnScreen(page);
  await page.mouse.click(m.x, m.y + 1.3 * m.r);
  await page.keyboard.press('Control+z');
  expect(await maskValues(page)).toEqual(inverted);
  await page.evaluate(() => window.app.mask.clear());
  // The same tool by name, and back.
  expect(await page.evaluate(() => window.app.setTool('draw') && window.app.setTool('mask') && window.app.tool)).toBe('mask');
  expect(errors).toEqual([]);
});

test('a masked half stays bit-identical through draw, inflate, smooth, pull and snake-hook strokes across it, and an autosave restore', async ({ page }) => {
  test.setTimeout(90_000);
  const errors = watchErrors(page);
  await open(page);
  // The upper half of the sphere's front as seen: one wide zigzag mask stroke with the mouse.
  await page.keyboard.press('M');
  expect(await page.evaluate(() => window.app.tool)).toBe('mask');
  await page.evaluate(() => window.app.setParams({ brushRadius: '30%', brushStrength: 1 }));
  const m = await modelOnScreen(page);
  const at = (fx, fy) => [m.x + fx * m.r, m.y + fy * m.r];
  await page.mouse.move(...at(-0.75, -0.15));
  await page.mouse.down();
  for (const [fx, fy] of [[0.75, -0.15], [0.55, -0.6], [-0.55, -0.6], [-0.2, -0.9], [0.2, -0.9]]) {
    await page.mouse.move(...at(fx, fy), { steps: 12 });
  }
  await page.mouse.up();
  const masked = await maskedVertices(page);
  console.log(`masked: ${masked.lines.length} of ${masked.vertices} vertices`);
  expect(masked.lines.length).toBeGreaterThan(masked.vertices * 0.2);
  expect(masked.lines.length).toBeLessThan(masked.vertices * 0.75);
  expect(masked.lines.some((l) => l.startsWith('no exported vertex'))).toBe(false);
  await shot(page, 'half');

  // Strokes from the unmasked lower half up across the mask's rim, each with its key.
  await page.evaluate(() => window.app.setParams({ brushRadius: '10%', brushStrength: 0.9 }));
  let hash = masked.hash;
  for (const [key, tool] of [['2', 'draw'], ['3', 'inflate'], ['4', 'smooth'], ['1', 'pull'], ['8', 'snakeHook']]) {
    await page.keyboard.press(key);
    expect(await page.evaluate(() => window.app.tool)).toBe(tool);
    await stroke(page, { fx: 0.1, fy: 0.55, dx: 0.05, dy: -0.9, steps: 20 });
    const now = await maskedVertices(page);
    expect(now.lines, `${tool}: the masked vertices`).toEqual(masked.lines);
    console.log(`${tool}: ${now.vertices} vertices`);
    expect(now.hash, `${tool} changed the mesh`).not.toBe(hash);
    hash = now.hash;
  }
  await shot(page, 'strokes');

  // Autosave: the mask and its history come back after a reload.
  const saved = await maskedVertices(page);
  expect(await page.evaluate(() => window.app.autosave.flush())).toBe(true);
  await page.reload();
  await page.waitForFunction(() => document.documentElement.dataset.ready === 'true', null, { timeout: 30_000 });
  await page.locator('.adasculpt-restore').getByRole('button', { name: 'Restore' }).click();
  await expect.poll(() => page.evaluate(() => window.app.stats().vertices)).toBe(saved.vertices);
  const restored = await maskedVertices(page);
  expect(restored.all).toEqual(saved.all); // every vertex and its mask
  expect(restored.lines).toEqual(masked.lines);
  // Six undo steps back (five strokes and the mask): no mask at all.
  for (let i = 0; i < 6; i++) await page.keyboard.press('Control+z');
  expect(count(await maskValues(page), (v) => v !== 0)).toBe(0);
  expect(errors).toEqual([]);
});
