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
export const snapshotCanvas = (page) => page.evaluate(() => {
  const c = document.querySelector('canvas');
  const t = document.createElement('canvas');
  t.width = c.width;
  t.height = c.height;
  const g = t.getContext('2d');
  g.drawImage(c, 0, 0);
  window.__canvas2d = g;
  return { width: c.width, height: c.height };
});
