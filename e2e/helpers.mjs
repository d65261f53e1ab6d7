// Helpers shared by the page's e2e specs (not a spec itself: Playwright only runs *.spec.mjs).

// Console errors and page errors fail the test that collected them.
export function watchErrors(page) {
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  return errors;
}

// Opens the page and waits for the first frame with the model.
export async function open(page, url = '/') {
  await page.goto(url);
  await page.waitForFunction(() => document.documentElement.dataset.ready === 'true' &&
    window.app.stats().firstRenderMs !== null, null, { timeout: 30_000 });
}

export const stats = (page) => page.evaluate(() => window.app.stats());

// Saves the current mesh (OFF bytes) under window.__saved[name] / compares with it.
export const save = (page, name) => page.evaluate(async (n) => {
  window.__saved = window.__saved || {};
  window.__saved[n] = new Uint8Array(await window.app.export('off'));
}, name);
export const sameAs = (page, name) => page.evaluate(async (n) => {
  const a = window.__saved[n], b = new Uint8Array(await window.app.export('off'));
  return a.length === b.length && a.every((x, i) => x === b[i]);
}, name);

// Copies the WebGL canvas (it keeps its drawing buffer) into a 2D canvas kept as window.__canvas2d,
// so that later page.evaluate calls can read its pixels with getImageData.
// Waits two animation frames first, so the copy shows the view after the last key or wheel event
// (the app renders in requestAnimationFrame; a copy taken before it shows the previous view).
export const snapshotCanvas = (page) => page.evaluate(async () => {
  await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
  const c = document.querySelector('canvas');
  const t = document.createElement('canvas');
  t.width = c.width;
  t.height = c.height;
  const g = t.getContext('2d');
  g.drawImage(c, 0, 0);
  window.__canvas2d = g;
  return { width: c.width, height: c.height };
});

// Where the model is drawn: {x, y, r} in page pixels, from the extent of the non-background pixels
// along the canvas row and column through the middle of the model (the panel shifts it left).
export async function modelOnScreen(page) {
  await snapshotCanvas(page);
  return page.evaluate(() => {
    const g = window.__canvas2d;
    const c = g.canvas;
    const px = (x, y) => g.getImageData(x, y, 1, 1).data;
    const bg = (y) => px(2, y); // the background is a vertical gradient: compare within the row
    const differs = (x, y, ref) => { const p = px(x, y); return Math.abs(p[0] - ref[0]) + Math.abs(p[1] - ref[1]) + Math.abs(p[2] - ref[2]) > 40; };
    const extent = (n, at) => { let lo = -1, hi = -1; for (let i = 0; i < n; i++) if (at(i)) { if (lo < 0) lo = i; hi = i; } return [lo, hi]; };
    const row = Math.floor(c.height / 2);
    const [x0, x1] = extent(Math.floor(c.width * 0.6), (x) => differs(x, row, bg(row)));
    const col = Math.floor((x0 + x1) / 2);
    const [y0, y1] = extent(c.height, (y) => differs(col, y, bg(y)));
    const scale = document.querySelector('canvas').getBoundingClientRect().width / c.width;
    return { x: ((x0 + x1) / 2) * scale, y: ((y0 + y1) / 2) * scale, r: ((x1 - x0) / 2) * scale };
  });
}

// A stroke with the left button: from the model's centre offset by (fx, fy) of its radius, by (dx, dy)
// of its radius; `modifier` (e.g. 'Control') held throughout. Exact positions: {x, y} in pixels.
export async function stroke(page, { fx = 0, fy = 0, dx = 0, dy = -0.8, steps = 16, modifier, at } = {}) {
  const m = await modelOnScreen(page);
  const x = at ? at.x : m.x + fx * m.r, y = at ? at.y : m.y + fy * m.r;
  dx *= m.r;
  dy *= m.r;
  if (modifier) await page.keyboard.down(modifier);
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + dx, y + dy, { steps });
  await page.mouse.up();
  if (modifier) await page.keyboard.up(modifier);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
}
