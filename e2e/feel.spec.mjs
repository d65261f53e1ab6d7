// Brush feel, detail control and the camera's gestures (issue 19), driven by real mouse, keyboard
// and touch events: falloff presets change a stamp's profile, the stabiliser calms a zig-zag hand,
// spacing sets the stamps per stroke, constant detail sets how fine a stroke remeshes, the detail
// flood fill remeshes the whole mesh to the detail, an orbit drag over the model turns around the
// point under the press, and two fingers orbit and pinch-zoom without sculpting.
import { test, expect } from '@playwright/test';
import { watchErrors, open, stats, save, sameAs } from './helpers.mjs';

// A panel control by its exact label (lil-gui: .lil-controller > .lil-name).
const control = (page, name) => page.locator('.adasculpt-panel .lil-controller')
  .filter({ has: page.locator('.lil-name', { hasText: new RegExp(`^${name.replace(/[()%×.]/g, '\\$&')}$`) }) });
const setNumber = async (page, name, value) => {
  const input = control(page, name).locator('input');
  await input.fill(String(value));
  await input.press('Enter');
};

// The live vertices (the lossless OFF export).
const vertices = (page) => page.evaluate(async () => {
  const text = new TextDecoder().decode(await window.app.export('off'));
  const lines = text.split('\n').filter((l) => l.trim() && !l.startsWith('#'));
  const nv = Number(lines[1].trim().split(/\s+/)[0]);
  return lines.slice(2, 2 + nv).map((l) => l.trim().split(/\s+/).map(Number));
});

// A world point on the page (client pixels), through the app's camera.
const toScreen = (page, p) => page.evaluate((q) => {
  const c = window.app.sculptor.camera;
  c.updateMatrixWorld();
  const v = c.position.clone().set(q[0], q[1], q[2]).project(c);
  const r = document.querySelector('canvas').getBoundingClientRect();
  return [r.left + ((v.x + 1) / 2) * r.width, r.top + ((1 - v.y) / 2) * r.height];
}, p);

const view = (page) => page.evaluate(() => window.app.view.state());
// The app hears keys while it has the focus (lil-gui's controls keep theirs to themselves).
const keys = (page) => page.locator('.adasculpt-root').focus();

// Front view of the default sphere (radius 1 at the origin), a brush tool by its key, symmetry off.
async function frontWithBrush(page, key) {
  await open(page);
  await keys(page);
  await page.keyboard.press('Shift+Digit1');
  await page.keyboard.press(key);
  await control(page, 'symmetry').locator('select').selectOption('off');
  await keys(page);
}

test('falloff presets: one constant dab raises its rim as far as its centre, a sharp one does not', async ({ page }) => {
  const errors = watchErrors(page);
  await frontWithBrush(page, '2');
  for (let i = 0; i < 6; i++) await page.keyboard.press(']'); // radius 5% x 1.15^6 = 11.6% of the diagonal
  for (let i = 0; i < 10; i++) await page.keyboard.press('='); // strength 1
  const params = await page.evaluate(() => window.app.sculptor.params);
  expect(params.strength).toBe(1);
  const [cx, cy] = await toScreen(page, [0, 0, 1]); // the front pole
  // One dab at the pole; the raise of the vertices at half the radius over the raise near the centre.
  const profile = async (falloff) => {
    await control(page, 'falloff').locator('select').selectOption(falloff);
    expect((await page.evaluate(() => window.app.sculptor.params)).falloff).toBe(falloff);
    await page.mouse.click(cx, cy);
    await expect.poll(async () => (await stats(page)).canUndo).toBe(true);
    const p = await vertices(page);
    const band = (lo, hi) => {
      const raise = p.filter(([x, y, z]) => z > 0 && Math.hypot(x, y) >= lo && Math.hypot(x, y) < hi)
        .map(([x, y, z]) => Math.hypot(x, y, z) - 1);
      return raise.reduce((a, b) => a + b, 0) / raise.length;
    };
    const r = params.radius;
    const ratio = band(0.45 * r, 0.6 * r) / band(0, 0.15 * r);
    await keys(page);
    await page.keyboard.press('Control+z');
    await expect.poll(async () => (await stats(page)).canUndo).toBe(false);
    return ratio;
  };
  const sharp = await profile('sharp');
  const constant = await profile('constant');
  console.log(`raise at half the radius / at the centre: sharp ${sharp.toFixed(3)}, constant ${constant.toFixed(3)}`);
  expect(constant).toBeGreaterThan(0.85);
  expect(sharp).toBeLessThan(0.5);
  expect(constant - sharp).toBeGreaterThan(0.4);
  expect(errors).toEqual([]);
});

// A zig-zag drag across the front of the sphere (the middle 60 % of its width on the screen): 16 px
// up and down every 20th of the way.
async function zigzag(page, [cx, cy, r]) {
  await page.evaluate(() => {
    if (!window.__ends) window.app.addEventListener('end', (e) => window.__ends.push(e.timings.stamps));
    window.__ends = [];
  });
  await page.mouse.move(cx - 0.6 * r, cy);
  await page.mouse.down();
  for (let i = 1; i <= 20; i++) await page.mouse.move(cx - 0.6 * r + 0.06 * r * i, cy + (i % 2 ? 16 : -16), { steps: 3 });
  await page.mouse.up();
  await expect.poll(() => page.evaluate(() => window.__ends.length)).toBe(1);
  return page.evaluate((y0) => {
    const s = window.app.sculptor.brushTool.lastSamples;
    return { samples: s.length, deviation: Math.max(...s.map(([, y]) => Math.abs(y - y0))), stamps: window.__ends[0] };
  }, cy);
}

test('the stabiliser calms a zig-zag hand; spacing sets the stamps per stroke', async ({ page }) => {
  const errors = watchErrors(page);
  await frontWithBrush(page, '2');
  const [cx, cy] = await toScreen(page, [0, 0, 1]);
  const centre = [cx, cy, cx - (await toScreen(page, [-1, 0, 0]))[0]]; // the sphere's radius on the screen
  expect(centre[2]).toBeGreaterThan(100);
  const free = await zigzag(page, centre);
  await setNumber(page, 'stabilizer (px, 0 off)', 40);
  expect((await page.evaluate(() => window.app.sculptor.params)).stabilizer).toBe(40);
  await keys(page);
  await page.keyboard.press('Control+z');
  const lazy = await zigzag(page, centre);
  console.log(`zig-zag: free ${JSON.stringify(free)}, stabilised ${JSON.stringify(lazy)}`);
  expect(free.deviation).toBeGreaterThan(14);
  expect(lazy.deviation).toBeLessThan(free.deviation * 0.4); // the corners are cut
  expect(lazy.stamps).toBeLessThan(free.stamps);             // a shorter, calmer path
  // Spacing: a stamp every 0.1 radius gives several times the stamps of one every 0.5 radius.
  await setNumber(page, 'stabilizer (px, 0 off)', 0);
  const stampsAt = async (spacing) => {
    await setNumber(page, 'spacing (× radius)', spacing);
    expect((await page.evaluate(() => window.app.sculptor.params)).spacing).toBe(spacing);
    await keys(page);
    await page.keyboard.press('Control+z');
    return (await zigzag(page, centre)).stamps;
  };
  const dense = await stampsAt(0.1);
  const sparse = await stampsAt(0.5);
  console.log(`stamps: spacing 0.1 -> ${dense}, 0.5 -> ${sparse}`);
  expect(dense).toBeGreaterThan(3 * sparse);
  expect(errors).toEqual([]);
});

test('constant detail: a finer edge length gives more vertices under the same stroke; pixels follow the zoom', async ({ page }) => {
  const errors = watchErrors(page);
  await frontWithBrush(page, '3'); // inflate
  await control(page, 'detail').locator('select').selectOption({ label: 'constant' });
  expect((await page.evaluate(() => window.app.sculptor.params)).detailMode).toBe('constant');
  const [cx, cy] = await toScreen(page, [0, 0, 1]);
  const brushed = async (pct) => {
    await setNumber(page, 'edge length (%)', pct);
    await keys(page);
    await page.mouse.move(cx - 40, cy);
    await page.mouse.down();
    await page.mouse.move(cx + 40, cy, { steps: 12 });
    await page.mouse.up();
    await expect.poll(async () => (await stats(page)).canUndo).toBe(true);
    const n = (await vertices(page)).filter(([x, y, z]) => z > 0 && Math.hypot(x, y) < 0.25).length;
    await page.keyboard.press('Control+z');
    await expect.poll(async () => (await stats(page)).canUndo).toBe(false);
    return n;
  };
  const fine = await brushed(0.4);
  const coarse = await brushed(2);
  console.log(`vertices within 0.25 of the stroke's middle: 0.4% -> ${fine}, 2% -> ${coarse}`);
  expect(fine).toBeGreaterThan(2 * coarse);
  // Screen pixels: zooming in makes the same pixel count a shorter edge.
  await control(page, 'detail').locator('select').selectOption({ label: 'screen pixels' });
  const far = await page.evaluate(() => window.app.sculptor.detailLength());
  await page.mouse.move(30, 560); // off the model: the wheel zooms
  for (let i = 0; i < 5; i++) await page.mouse.wheel(0, -300);
  const near = await page.evaluate(() => window.app.sculptor.detailLength());
  expect(near).toBeGreaterThan(0);
  expect(near).toBeLessThan(far * 0.8);
  // Brush radius: a share of the radius, so ']' makes it coarser.
  await control(page, 'detail').locator('select').selectOption({ label: 'brush radius' });
  const small = await page.evaluate(() => window.app.sculptor.detailLength());
  await keys(page);
  await page.keyboard.press(']');
  expect(await page.evaluate(() => window.app.sculptor.detailLength())).toBeCloseTo(small * 1.15, 6);
  expect(errors).toEqual([]);
});

test('detail flood fill: the whole mesh at the constant detail in one undo step', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  await control(page, 'detail').locator('select').selectOption({ label: 'constant' });
  await setNumber(page, 'edge length (%)', 1);
  const before = await stats(page);
  const detail = await page.evaluate(() => window.app.sculptor.detailLength());
  expect(detail).toBeCloseTo(0.01 * before.settings.diagonal, 9);
  await page.getByText('detail flood fill').click();
  await expect(page.getByText('detail flood fill')).toBeVisible({ timeout: 30_000 }); // back from "flood filling… i/n"
  await expect.poll(async () => (await stats(page)).canUndo).toBe(true);
  const after = await stats(page);
  console.log(`flood fill at ${detail.toFixed(4)}: mean edge ${after.quality.edgeLengthMean.toFixed(4)}, ` +
    `${before.vertices} -> ${after.vertices} vertices`);
  expect(Math.abs(after.quality.edgeLengthMean - detail)).toBeLessThan(0.15 * detail);
  expect(Math.abs(before.quality.edgeLengthMean - detail)).toBeGreaterThan(0.3 * detail); // it did change
  await keys(page);
  await page.keyboard.press('Control+z');
  await expect.poll(async () => (await stats(page)).vertices).toBe(before.vertices);
  expect((await stats(page)).canUndo).toBe(false);
  expect(errors).toEqual([]);
});

test('an orbit drag over the model turns around the point under the press, which stays under it', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  const v0 = await view(page);
  expect(v0.pivot).toBeNull();
  // A point up and right of the front pole, well off the orbit centre on the screen.
  const surface = [0.45, 0.35, Math.sqrt(1 - 0.45 ** 2 - 0.35 ** 2)];
  const [px, py] = await toScreen(page, surface);
  await page.mouse.move(px, py);
  await page.mouse.down({ button: 'middle' });
  await page.mouse.move(px - 90, py + 40, { steps: 12 });
  await page.mouse.up({ button: 'middle' });
  const v1 = await view(page);
  expect(v1.pivot).not.toBeNull();
  const pivotOff = Math.hypot(...v1.pivot.map((x, i) => x - surface[i]));
  expect(pivotOff, 'the pivot is the surface point under the press').toBeLessThan(0.03);
  const [qx, qy] = await toScreen(page, v1.pivot);
  console.log(`pivot on screen: pressed at ${px.toFixed(1)}, ${py.toFixed(1)}; after the orbit ${qx.toFixed(1)}, ${qy.toFixed(1)}`);
  expect(Math.hypot(qx - px, qy - py)).toBeLessThan(2);
  // The view did turn (and the orbit centre moved with it); the mesh is untouched.
  const dir = (s) => { const d = s.position.map((x, i) => x - s.target[i]); const l = Math.hypot(...d); return d.map((x) => x / l); };
  const turned = Math.acos(Math.min(1, dir(v0).reduce((a, x, i) => a + x * dir(v1)[i], 0)));
  expect(turned).toBeGreaterThan(0.2);
  expect(Math.hypot(...v1.target.map((x, i) => x - v0.target[i]))).toBeGreaterThan(0.05);
  expect((await stats(page)).canUndo).toBe(false);
  // Turning around the orbit centre instead would have moved that point across the screen.
  expect(errors).toEqual([]);
});

// Touch through the DevTools protocol (real touch events, as a touch screen sends them).
async function touchScreen(page) {
  const cdp = await page.context().newCDPSession(page);
  return (type, points) => cdp.send('Input.dispatchTouchEvent', {
    type, touchPoints: points.map(([x, y], id) => ({ x, y, id, radiusX: 2, radiusY: 2, force: 1 })),
  });
}

test('touch: two fingers pinch-zoom and orbit without sculpting; one finger on the model sculpts', async ({ page }) => {
  const errors = watchErrors(page);
  await frontWithBrush(page, '2');
  const touch = await touchScreen(page);
  const [cx, cy] = await toScreen(page, [0, 0, 1]);
  // One finger off the model (below it) orbits.
  const r = cx - (await toScreen(page, [-1, 0, 0]))[0];
  const below = [cx, cy + 1.3 * r];
  expect(await page.evaluate(([x, y]) => window.app.sculptor.surfacePoint(x, y), below)).toBeNull();
  const v0 = await view(page);
  await touch('touchStart', [below]);
  for (let i = 1; i <= 6; i++) await touch('touchMove', [[below[0] + 10 * i, below[1]]]);
  await touch('touchEnd', []);
  expect(Math.hypot(...(await view(page)).position.map((x, i) => x - v0.position[i]))).toBeGreaterThan(0.05);
  await page.keyboard.press('Shift+Digit1'); // front again
  const d0 = (await view(page)).distance;
  // Both fingers land on the model and spread apart: zoom in.
  await touch('touchStart', [[cx - 20, cy], [cx + 20, cy]]);
  for (let i = 1; i <= 8; i++) await touch('touchMove', [[cx - 20 - 8 * i, cy], [cx + 20 + 8 * i, cy]]);
  await touch('touchEnd', []);
  const d1 = (await view(page)).distance;
  expect(d1).toBeLessThan(d0 * 0.85);
  // Two fingers moving together: orbit.
  const dirOf = (s) => s.position.map((x, i) => x - s.target[i]);
  const before = dirOf(await view(page));
  await touch('touchStart', [[cx - 30, cy], [cx + 30, cy]]);
  for (let i = 1; i <= 8; i++) await touch('touchMove', [[cx - 30 + 10 * i, cy], [cx + 30 + 10 * i, cy]]);
  await touch('touchEnd', []);
  const after = dirOf(await view(page));
  expect(Math.hypot(...after.map((x, i) => x - before[i]))).toBeGreaterThan(0.05);
  let s = await stats(page);
  expect(s.canUndo, 'no stroke, no undo step').toBe(false);
  // One finger on the model (over the orbit centre, the sphere's): a stroke (one undo step), and the view stays.
  const v = await view(page);
  const [sx, sy] = await toScreen(page, v.target);
  await touch('touchStart', [[sx - 30, sy]]);
  for (let i = 1; i <= 8; i++) await touch('touchMove', [[sx - 30 + 8 * i, sy]]);
  await touch('touchEnd', []);
  await expect.poll(async () => (await stats(page)).canUndo).toBe(true);
  s = await stats(page);
  expect(s.vertices).not.toBe(0);
  expect(Math.hypot(...(await view(page)).position.map((x, i) => x - v.position[i]))).toBeLessThan(1e-9);
  await keys(page);
  await page.keyboard.press('Control+z');
  expect((await stats(page)).canUndo).toBe(false);
  expect(errors).toEqual([]);
});

test('touch with the Pull tool: a pinch on the model zooms without a grab; one finger on the model pulls', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  expect(await page.evaluate(() => window.app.tool)).toBe('pull');
  const touch = await touchScreen(page);
  const v = await view(page);
  const [cx, cy] = await toScreen(page, v.target); // over the sphere's centre: on the model
  await touch('touchStart', [[cx - 20, cy], [cx + 20, cy]]);
  for (let i = 1; i <= 8; i++) await touch('touchMove', [[cx - 20 - 8 * i, cy], [cx + 20 + 8 * i, cy]]);
  await touch('touchEnd', []);
  expect((await view(page)).distance).toBeLessThan(v.distance * 0.85);
  expect((await stats(page)).canUndo, 'no grab, no undo step').toBe(false);
  await save(page, 'before pull');
  const zoomed = await view(page);
  const [sx, sy] = await toScreen(page, zoomed.target);
  await touch('touchStart', [[sx, sy]]);
  for (let i = 1; i <= 8; i++) await touch('touchMove', [[sx, sy - 8 * i]]);
  await touch('touchEnd', []);
  await expect.poll(async () => (await stats(page)).canUndo).toBe(true);
  expect(await sameAs(page, 'before pull'), 'the finger pulled the surface').toBe(false);
  const outward = (await vertices(page)).reduce((m, p) => Math.max(m, Math.hypot(...p)), 0);
  expect(outward, 'out of the sphere').toBeGreaterThan(1.01);
  expect(Math.hypot(...(await view(page)).position.map((x, i) => x - zoomed.position[i])), 'the view stayed').toBeLessThan(1e-9);
  expect(errors).toEqual([]);
});
