// The camera a sculptor cannot lose (issue 19, View): F / the Frame button frame the model, the wheel
// stops at zoom limits set from the model's size, Shift+digits and the numpad give the axis views
// without touching the tool keys 1–8, O toggles orthographic, and strokes still land under the pointer.
import { test, expect } from '@playwright/test';
import { watchErrors, open, stats, snapshotCanvas } from './helpers.mjs';

const view = (page) => page.evaluate(() => window.app.view.state());
const len = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
const unit = (s) => { const d = s.position.map((x, i) => x - s.target[i]); const l = Math.hypot(...d); return d.map((x) => x / l); };

// Fraction of sampled canvas pixels that differ from the background of their row (the background is
// a vertical gradient, so a row's leftmost pixel is its background colour).
async function coverage(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await snapshotCanvas(page);
  return page.evaluate(() => {
    const g = window.__canvas2d;
    const { width, height } = g.canvas;
    const d = g.getImageData(0, 0, width, height).data;
    let hit = 0, n = 0;
    for (let y = 0; y < height; y += 4) {
      const o0 = 4 * (y * width + 1);
      for (let x = 0; x < width; x += 4) {
        const o = 4 * (y * width + x);
        n++;
        if (Math.abs(d[o] - d[o0]) + Math.abs(d[o + 1] - d[o0 + 1]) + Math.abs(d[o + 2] - d[o0 + 2]) > 24) hit++;
      }
    }
    return hit / n;
  });
}

// The centre of the model's silhouette on the page (the canvas fills the page).
async function modelCentre(page) {
  await snapshotCanvas(page);
  return page.evaluate(() => {
    const g = window.__canvas2d;
    const { width, height } = g.canvas;
    const d = g.getImageData(0, 0, width, height).data;
    let x0 = width, x1 = 0, y0 = height, y1 = 0;
    for (let y = 0; y < height; y += 2) {
      const o0 = 4 * (y * width + 1);
      for (let x = 120; x < width * 0.66; x += 2) {
        const o = 4 * (y * width + x);
        if (Math.abs(d[o] - d[o0]) + Math.abs(d[o + 1] - d[o0 + 1]) + Math.abs(d[o + 2] - d[o0 + 2]) > 40) {
          x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
        }
      }
    }
    const s = window.devicePixelRatio || 1;
    return [(x0 + x1) / 2 / s, (y0 + y1) / 2 / s];
  });
}

async function wheelOnCanvas(page, dy, times) {
  const box = await page.locator('canvas').boundingBox();
  await page.mouse.move(box.x + 30, box.y + box.height - 60); // off the model: the wheel zooms
  for (let i = 0; i < times; i++) await page.mouse.wheel(0, dy);
}

test('the wheel stops before the model; F and the Frame button frame it again', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  const framed = await view(page);
  const full = await coverage(page);
  expect(full).toBeGreaterThan(0.05);
  await wheelOnCanvas(page, -400, 60); // far in
  const close = await view(page);
  expect(close.distance).toBeLessThan(framed.distance * 0.8);
  expect(close.distance).toBeGreaterThanOrEqual(close.minDistance * 0.999);
  expect(close.minDistance).toBeGreaterThan(close.modelRadius); // outside the model's bounding sphere
  expect(await coverage(page), 'zoomed in, the model still fills the view').toBeGreaterThan(0.5);
  await page.locator('canvas').focus();
  await page.keyboard.press('f');
  const again = await view(page);
  expect(again.distance).toBeCloseTo(framed.distance, 6);
  expect(len(again.target, framed.target)).toBeLessThan(1e-9);
  await wheelOnCanvas(page, 400, 80); // far out: the limit keeps the model visible
  const far = await view(page);
  expect(far.distance).toBeLessThanOrEqual(far.maxDistance * 1.001);
  expect(await coverage(page)).toBeGreaterThan(0.0005);
  // Right drag pans (the help bar says so); the Frame button brings the model back.
  const box = await page.locator('canvas').boundingBox();
  await page.mouse.move(box.x + 40, box.y + 40);
  await page.mouse.down({ button: 'right' });
  await page.mouse.move(box.x + 300, box.y + 200, { steps: 10 });
  await page.mouse.up({ button: 'right' });
  expect(len((await view(page)).target, framed.target)).toBeGreaterThan(0.05);
  await page.getByRole('button', { name: /Frame/ }).click();
  const back = await view(page);
  expect(len(back.target, framed.target)).toBeLessThan(1e-9);
  expect(back.distance).toBeCloseTo(framed.distance, 6);
  expect(await coverage(page)).toBeCloseTo(full, 1);
  expect(errors).toEqual([]);
});

test('axis views from Shift+1–6 and the numpad leave the tool alone; app.view.set names them', async ({ page }) => {
  await open(page);
  await page.locator('canvas').focus();
  await page.keyboard.press('2'); // Draw
  expect(await page.evaluate(() => window.app.tool)).toBe('draw');
  const expectDir = async (d, key) => {
    const u = unit(await view(page));
    for (let i = 0; i < 3; i++) expect(u[i], `${key}: ${u}`).toBeCloseTo(d[i], 3);
  };
  const keys = [['Shift+Digit1', [0, 0, 1]], ['Shift+Digit2', [0, 0, -1]], ['Shift+Digit3', [-1, 0, 0]],
    ['Shift+Digit4', [1, 0, 0]], ['Shift+Digit5', [0, 1, 0]], ['Shift+Digit6', [0, -1, 0]],
    ['Numpad1', [0, 0, 1]], ['Control+Numpad1', [0, 0, -1]], ['Numpad3', [1, 0, 0]], ['Control+Numpad3', [-1, 0, 0]],
    ['Numpad7', [0, 1, 0]], ['Control+Numpad7', [0, -1, 0]]];
  for (const [key, d] of keys) {
    await page.keyboard.press(key);
    await expectDir(d, key);
  }
  expect(await page.evaluate(() => window.app.tool), 'view keys do not change the tool').toBe('draw');
  for (const [name, d] of [['front', [0, 0, 1]], ['right', [1, 0, 0]], ['top', [0, 1, 0]]]) {
    await page.evaluate((n) => window.app.view.set(n), name);
    await expectDir(d);
  }
  await expect(page.evaluate(() => window.app.view.set('diagonal'))).rejects.toThrow(/unknown view/);
});

test('O switches to orthographic and back with the same framing; a stroke still lands under the pointer', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  await page.evaluate(() => window.app.view.set('front'));
  const persp = await coverage(page);
  await page.locator('canvas').focus();
  await page.keyboard.press('o');
  const o = await view(page);
  expect(o.orthographic).toBe(true);
  expect(await page.getByRole('button', { name: /Ortho/ }).getAttribute('aria-pressed')).toBe('true');
  // Same height of the view at the target: about the same area covered (perspective shows the near half a bit larger).
  const ortho = await coverage(page);
  expect(Math.abs(ortho - persp)).toBeLessThan(persp * 0.15);
  // Zoom limits in orthographic: the zoom stops at maxZoom.
  await wheelOnCanvas(page, -400, 80);
  const z = await view(page);
  expect(z.zoom).toBeGreaterThan(1.5);
  expect(z.zoom).toBeLessThanOrEqual(z.maxZoom * 1.001);
  await page.keyboard.press('f');
  expect((await view(page)).zoom).toBe(1);
  // A draw stroke across the centre raises the front (+z) of the sphere, under the pointer.
  await page.keyboard.press('2');
  await page.evaluate(() => window.app.setParams({ symmetry: 'off' }));
  const zBefore = (await page.evaluate(() => window.app.bounds())).max[2];
  const [cx, cy] = await modelCentre(page);
  await page.mouse.move(cx - 20, cy);
  await page.mouse.down();
  await page.mouse.move(cx + 20, cy, { steps: 10 });
  await page.mouse.up();
  await expect.poll(async () => (await page.evaluate(() => window.app.bounds())).max[2]).toBeGreaterThan(zBefore + 1e-3);
  await page.keyboard.press('o');
  expect((await view(page)).orthographic).toBe(false);
  expect((await stats(page)).vertices).toBeGreaterThan(0);
  expect(errors).toEqual([]);
});
