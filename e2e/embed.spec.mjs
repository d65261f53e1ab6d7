// Embedding: web/embed.html (two createSculptApp instances in an ordinary page, no cross-origin
// isolation) and web/element.html (<adasculpt-viewer> from markup). Each instance renders, a drag in
// one leaves the other alone, dispose of one leaves the other working, and a disposed app leaves no
// window/document listener, canvas, WebGL context or wasm Session behind.
// Screenshots: test-results/embed-*.png, test-results/element-*.png.
import { test, expect } from '@playwright/test';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..');
const shot = (page, name) => page.screenshot({ path: path.join(root, 'test-results', `${name}.png`), fullPage: true });

function watchErrors(page) {
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  return errors;
}

// Records every listener added to window or document and not removed since: window.__globalListeners().
const trackGlobalListeners = () => {
  const live = new Map(); // key -> count
  const key = (t, type, fn, opt) => {
    const capture = typeof opt === 'boolean' ? opt : !!(opt && opt.capture);
    if (!fn.__listenerId) Object.defineProperty(fn, '__listenerId', { value: Math.random().toString(36).slice(2) });
    return `${t === window ? 'window' : 'document'}:${type}:${capture}:${fn.__listenerId}`;
  };
  const add = EventTarget.prototype.addEventListener;
  const remove = EventTarget.prototype.removeEventListener;
  // Only the page's own code (Playwright's injected scripts add capture listeners of their own).
  const fromPage = () => (new Error().stack || '').includes(location.origin);
  EventTarget.prototype.addEventListener = function (type, fn, opt) {
    if ((this === window || this === document) && fn && !(opt && opt.once) && fromPage()) live.set(key(this, type, fn, opt), type);
    return add.call(this, type, fn, opt);
  };
  EventTarget.prototype.removeEventListener = function (type, fn, opt) {
    if ((this === window || this === document) && fn) live.delete(key(this, type, fn, opt));
    return remove.call(this, type, fn, opt);
  };
  window.__globalListeners = () => Array.from(live.keys()).sort();
};

async function ready(page, url) {
  await page.goto(url);
  await page.waitForFunction(() => document.documentElement.dataset.ready === 'true', null, { timeout: 30_000 });
}

// Colour spread over a 5x5 grid of a canvas: a shaded model gives many different colours, the plain
// background (or a blank canvas) few.
function canvasSpread(page, index) {
  return page.evaluate((i) => {
    const c = document.querySelectorAll('canvas')[i];
    const t = document.createElement('canvas');
    t.width = c.width;
    t.height = c.height;
    const g = t.getContext('2d');
    g.drawImage(c, 0, 0);
    let lo = 765, hi = 0;
    for (let y = 1; y <= 5; y++) {
      for (let x = 1; x <= 5; x++) {
        const d = g.getImageData(Math.floor((x / 6) * c.width), Math.floor((y / 6) * c.height), 1, 1).data;
        const s = d[0] + d[1] + d[2];
        lo = Math.min(lo, s);
        hi = Math.max(hi, s);
      }
    }
    return hi - lo;
  }, index);
}

// From (fx, fy) of the canvas (the model sits left of centre when the panel is open).
async function dragCanvas(page, index, dx, dy, fx = 0.5, fy = 0.5) {
  const box = await page.locator('canvas').nth(index).boundingBox();
  const x = box.x + box.width * fx, y = box.y + box.height * fy;
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + dx / 2, y + dy / 2, { steps: 6 });
  await page.mouse.move(x + dx, y + dy, { steps: 6 });
  await page.mouse.up();
}

// OFF text of an app's current mesh (exact: %.17g coordinates).
const offOf = (page, expr) => page.evaluate(async (e) => new TextDecoder().decode(await eval(e).export('off')), expr);

test('the embed page: two independent instances; a drag in one leaves the other; dispose of one leaves the other working', async ({ page }) => {
  await page.addInitScript(trackGlobalListeners);
  const errors = watchErrors(page);
  await ready(page, '/embed.html');
  expect(await page.evaluate(() => window.crossOriginIsolated)).toBe(false);
  const counts = await page.evaluate(() => [window.embedded.left.stats().vertices, window.embedded.right.stats().vertices]);
  expect(counts).toEqual([2562, 6475]);
  expect(await page.locator('canvas').count()).toBe(2);
  expect(await canvasSpread(page, 0), 'left canvas shows the model').toBeGreaterThan(60);
  expect(await canvasSpread(page, 1), 'right canvas shows the model').toBeGreaterThan(60);
  await shot(page, 'embed-two-instances');

  // A mouse drag on the left model changes the left mesh only.
  const left0 = await offOf(page, 'window.embedded.left');
  const right0 = await offOf(page, 'window.embedded.right');
  await dragCanvas(page, 0, 0, -90);
  const left1 = await offOf(page, 'window.embedded.left');
  expect(left1).not.toBe(left0);
  expect(await offOf(page, 'window.embedded.right')).toBe(right0);
  expect(await page.evaluate(() => window.embedded.right.stats().canUndo)).toBe(false);
  await shot(page, 'embed-left-pulled');

  // Dispose the right one (the page's button): its canvas, context and wasm Session go; the left one still sculpts.
  const gl = await page.evaluateHandle(() => document.querySelectorAll('canvas')[1].getContext('webgl2'));
  await page.click('#dispose');
  expect(await page.locator('canvas').count()).toBe(1);
  expect(await gl.evaluate((g) => g.isContextLost())).toBe(true);
  expect(await page.evaluate(() => window.embedded.right.session.isDeleted())).toBe(true);
  await dragCanvas(page, 0, 60, 0);
  expect(await offOf(page, 'window.embedded.left')).not.toBe(left1);
  expect(await page.evaluate(() => window.embedded.left.undo())).toBe(true);
  expect(await offOf(page, 'window.embedded.left')).toBe(left1);
  expect(await canvasSpread(page, 0)).toBeGreaterThan(60);

  // Disposing the left one too leaves the page as it was: no window/document listener of either app.
  await page.evaluate(() => window.embedded.left.dispose());
  expect(await page.evaluate(() => window.__globalListeners())).toEqual([]);
  expect(await page.locator('canvas').count()).toBe(0);
  expect(errors).toEqual([]);
});

test('<adasculpt-viewer>: attributes set the model and parameters, it sizes to its box, removing it disposes the app', async ({ page }) => {
  await page.addInitScript(trackGlobalListeners);
  const errors = watchErrors(page);
  await ready(page, '/element.html');
  const app = 'document.querySelector("adasculpt-viewer").app';
  const s = await page.evaluate((e) => eval(e).stats(), app);
  expect(s.vertices).toBe(6475); // fandisk
  expect(s.settings.epsilon / s.settings.diagonal).toBeCloseTo(0.001, 9); // epsilon="0.1%"
  expect(s.settings.features).toBe(45);
  expect(await canvasSpread(page, 0)).toBeGreaterThan(60);
  // The canvas fills the element (420 px high from the page's CSS) and follows its size.
  const box = await page.locator('adasculpt-viewer').boundingBox();
  const canvasBox = await page.locator('canvas').boundingBox();
  expect(Math.round(canvasBox.height)).toBe(420);
  expect(Math.round(canvasBox.width)).toBe(Math.round(box.width));
  await page.evaluate(() => { document.querySelector('adasculpt-viewer').style.height = '300px'; });
  await expect.poll(async () => Math.round((await page.locator('canvas').boundingBox()).height)).toBe(300);
  await expect.poll(() => page.evaluate(() => document.querySelector('canvas').height / devicePixelRatio)).toBe(300);
  await shot(page, 'element-fandisk');

  // Attribute changes: parameters go to setParams, src to load (the parameters apply again after it).
  await page.evaluate(() => document.querySelector('adasculpt-viewer').setAttribute('epsilon', '0.2%'));
  const eps = await page.evaluate((e) => { const t = eval(e).stats().settings; return t.epsilon / t.diagonal; }, app);
  expect(eps).toBeCloseTo(0.002, 9);
  await page.evaluate(() => document.querySelector('adasculpt-viewer').setAttribute('src', 'models/sphere.obj'));
  await expect.poll(() => page.evaluate((e) => eval(e).stats().vertices, app)).toBe(2562);
  await expect.poll(() => page.evaluate((e) => eval(e).stats().settings.features, app)).toBe(45);

  // A mouse drag sculpts it.
  const before = await offOf(page, app);
  // The model is framed in the part of the box the panel and the tool buttons leave free (left of centre).
  await dragCanvas(page, 0, 0, -60, 0.4, 0.62);
  await shot(page, 'element-sphere-pulled');
  expect(await offOf(page, app)).not.toBe(before);

  // Removing the element disposes the app.
  const gl = await page.evaluateHandle(() => document.querySelector('canvas').getContext('webgl2'));
  const session = await page.evaluateHandle((e) => eval(e).session, app);
  await page.click('#remove');
  expect(await page.locator('canvas').count()).toBe(0);
  expect(await gl.evaluate((g) => g.isContextLost())).toBe(true);
  expect(await session.evaluate((x) => x.isDeleted())).toBe(true);
  expect(await page.evaluate(() => window.__globalListeners())).toEqual([]);

  // Created from script, too: a second element in a sized box.
  await page.evaluate(() => new Promise((resolve, reject) => {
    const host = document.createElement('div');
    host.style.cssText = 'width: 320px; height: 240px';
    const el = document.createElement('adasculpt-viewer');
    el.setAttribute('src', 'models/hemisphere.off');
    el.setAttribute('ui', 'off');
    el.style.height = '100%';
    el.addEventListener('adasculpt-ready', resolve, { once: true });
    el.addEventListener('adasculpt-error', (e) => reject(e.detail), { once: true });
    host.appendChild(el);
    document.body.appendChild(host);
  }));
  expect(await page.evaluate(() => document.querySelectorAll('adasculpt-viewer')[0].app.stats().vertices)).toBe(1861);
  expect(Math.round((await page.locator('canvas').boundingBox()).width)).toBe(320);
  expect(errors).toEqual([]);
});
