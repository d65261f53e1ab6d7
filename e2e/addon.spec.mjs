// web/addon.html: AdaptiveSculptor in a host scene (own lights, floor, a spinning torus knot, OrbitControls and
// render loop). The sculpted sphere is moved, turned and scaled, so the strokes go through its matrixWorld.
import { test, expect } from '@playwright/test';
import { watchErrors } from './helpers.mjs';

async function openDemo(page) {
  await page.goto('/addon.html');
  await page.waitForFunction(() => document.documentElement.dataset.ready === 'true', null, { timeout: 30_000 });
}

// The clay's centre on the screen and the radius of its silhouette there (CSS pixels).
const clayOnScreen = (page) => page.evaluate(() => {
  const { clay, renderer } = window.demo;
  const cam = window.demo.sculptor.camera;
  const c = clay.getWorldPosition(clay.position.clone());
  const p = c.clone().project(cam);
  const r = renderer.domElement.getBoundingClientRect();
  return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
});

// Local-space points of the clay farther than `r` from its own origin.
const raised = (page, r) => page.evaluate((rr) => {
  const g = window.demo.clay.geometry;
  const p = g.attributes.position, idx = g.index;
  const out = new Set();
  for (let i = 0; i < Math.min(idx.count, g.drawRange.count); i++) {
    const v = idx.getX(i);
    if (Math.hypot(p.getX(v), p.getY(v), p.getZ(v)) > rr) out.add(v);
  }
  return [...out].map((v) => [p.getX(v), p.getY(v), p.getZ(v)]);
}, r);

test('the addon sculpts the moved, turned and scaled sphere where the pointer is; the rest of the scene is untouched', async ({ page }) => {
  const errors = watchErrors(page);
  await openDemo(page);
  const knotBefore = await page.evaluate(() => Array.from(window.demo.knot.geometry.attributes.position.array.slice(0, 300)));
  const c = await clayOnScreen(page);
  await page.mouse.move(c.x - 40, c.y);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(c.x - 40 + 8 * i, c.y);
  await page.mouse.up();
  await page.waitForFunction(() => window.demo.ends.length === 1);
  const end = await page.evaluate(() => {
    const e = window.demo.ends[0];
    return { tool: e.tool, frames: e.timings.frames, vertices: e.vertices };
  });
  expect(end.tool).toBe('draw');
  expect(end.frames).toBeGreaterThan(0);
  // The raised vertices lie where the pointer went: their world positions project near the stroke.
  const up = await raised(page, 1.02);
  expect(up.length).toBeGreaterThan(5);
  const screen = await page.evaluate((pts) => {
    const { clay, renderer } = window.demo;
    const cam = window.demo.sculptor.camera;
    const r = renderer.domElement.getBoundingClientRect();
    return pts.map(([x, y, z]) => {
      const p = clay.localToWorld(clay.position.clone().set(x, y, z)).project(cam);
      return [r.left + ((p.x + 1) / 2) * r.width, r.top + ((1 - p.y) / 2) * r.height];
    });
  }, up);
  const cx = screen.reduce((a, p) => a + p[0], 0) / screen.length;
  const cy = screen.reduce((a, p) => a + p[1], 0) / screen.length;
  console.log(`stroke centre on screen ${c.x.toFixed(0)},${c.y.toFixed(0)}; raised vertices around ${cx.toFixed(0)},${cy.toFixed(0)} (${up.length})`);
  expect(Math.abs(cx - c.x)).toBeLessThan(40);
  expect(Math.abs(cy - c.y)).toBeLessThan(25);
  expect(await page.evaluate(() => Array.from(window.demo.knot.geometry.attributes.position.array.slice(0, 300)))).toEqual(knotBefore);
  // Ctrl+Z undoes the stroke: nothing raised any more.
  await page.keyboard.press('Control+z');
  expect((await raised(page, 1.02)).length).toBe(0);
  expect(errors).toEqual([]);
});

test('the app is built on the sculptor and dispatches its start, change and end', async ({ page }) => {
  const errors = watchErrors(page);
  await page.goto('/');
  await page.waitForFunction(() => document.documentElement.dataset.ready === 'true' && window.app.stats().firstRenderMs !== null);
  await page.evaluate(() => {
    window.__events = [];
    for (const type of ['start', 'change', 'end']) window.app.addEventListener(type, (e) => window.__events.push({ type, tool: e.tool, frames: e.timings?.frames }));
  });
  const box = await page.locator('canvas').boundingBox();
  const x = box.x + box.width * 0.4, y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x, y - 40, { steps: 6 });
  await page.mouse.up();
  await page.waitForFunction(() => window.__events.some((e) => e.type === 'end'));
  const events = await page.evaluate(() => window.__events);
  expect(events[0]).toEqual({ type: 'start', tool: 'pull' });
  expect(events.filter((e) => e.type === 'change').length).toBeGreaterThan(0);
  const end = events.find((e) => e.type === 'end');
  expect(end.tool).toBe('pull');
  expect(end.frames).toBeGreaterThan(0);
  expect(errors).toEqual([]);
});
