// Brushes in the browser: the tool palette and its keys, strokes with the mouse on the default
// sphere (inflate, draw, inverted draw), mirror symmetry (X by default), undo of a stroke, the
// scripting API against the core's replay, orbiting with a brush selected, pen pressure, and at
// most one wasm call per animation frame while stroking. Screenshots: test-results/brush-*.png.
import { test, expect } from '@playwright/test';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { watchErrors, open, stats, save, sameAs, snapshotCanvas, modelOnScreen, stroke } from './helpers.mjs';

const root = path.join(path.dirname(fileURLToPath(import.meta.url)), '..');
const shot = (page, name) => page.screenshot({ path: path.join(root, 'test-results', `brush-${name}.png`) });

// Distances of the vertices from the origin (the sphere's centre), split by the side of x = 0:
// {min, max, raisedRight, raisedLeft, dentedRight, dentedLeft} (raised: > 1.02, dented: < 0.98),
// and the enclosed volume (divergence theorem over the faces).
const shape = (page) => page.evaluate(async () => {
  const text = new TextDecoder().decode(await window.app.export('off'));
  const lines = text.split('\n').filter((l) => l.trim() && !l.startsWith('#'));
  const nv = Number(lines[1].trim().split(/\s+/)[0]);
  const r = { min: Infinity, max: 0, raisedRight: 0, raisedLeft: 0, dentedRight: 0, dentedLeft: 0, volume: 0 };
  const p = [];
  for (let i = 2; i < 2 + nv; i++) {
    const [x, y, z] = lines[i].trim().split(/\s+/).map(Number);
    p.push([x, y, z]);
    const d = Math.hypot(x, y, z);
    r.min = Math.min(r.min, d);
    r.max = Math.max(r.max, d);
    if (d > 1.02) r[x > 0 ? 'raisedRight' : 'raisedLeft']++;
    if (d < 0.98) r[x > 0 ? 'dentedRight' : 'dentedLeft']++;
  }
  // Exact mirror symmetry across x = 0: vertices whose mirror image is not exactly a vertex (the
  // export is lossless, so the text holds the doubles exactly).
  const key = (x, y, z) => `${x === 0 ? 0 : x},${y},${z}`;
  const at = new Set(p.map(([x, y, z]) => key(x, y, z)));
  r.mirrorMissing = p.filter(([x, y, z]) => !at.has(key(-x, y, z))).length;
  for (let i = 2 + nv; i < lines.length; i++) {
    const [, a, b, c] = lines[i].trim().split(/\s+/).map(Number);
    const [A, B, C] = [p[a], p[b], p[c]];
    r.volume += (A[0] * (B[1] * C[2] - B[2] * C[1]) - A[1] * (B[0] * C[2] - B[2] * C[0]) + A[2] * (B[0] * C[1] - B[1] * C[0])) / 6;
  }
  return r;
});

const pressed = (page) => page.locator('.adasculpt-tools button[aria-pressed="true"]');

test('the palette: keys 1-8 and the buttons pick tools; brush defaults, symmetry X', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  expect(await page.evaluate(() => window.app.tool)).toBe('pull');
  await expect(pressed(page)).toHaveText(/Pull/);
  const expected = ['pull', 'draw', 'inflate', 'smooth', 'flatten', 'pinch', 'crease', 'snakeHook'];
  for (let i = 8; i >= 1; i--) {
    await page.keyboard.press(String(i));
    expect(await page.evaluate(() => window.app.tool)).toBe(expected[i - 1]);
    await expect(pressed(page)).toHaveAttribute('data-tool', expected[i - 1]);
  }
  await page.locator('.adasculpt-tools button[data-tool="inflate"]').click();
  expect(await page.evaluate(() => window.app.tool)).toBe('inflate');
  await expect(pressed(page)).toHaveText(/Inflate/);
  // The panel: symmetry x by default; ] and = raise radius and strength.
  const symmetry = page.locator('.lil-controller', { hasText: 'symmetry' }).locator('select');
  await expect(symmetry).toHaveValue('x');
  const radius = page.locator('.lil-controller').filter({ has: page.locator('.lil-name', { hasText: /^radius \(%\)$/ }) }).locator('input');
  const strength = page.locator('.lil-controller', { hasText: 'strength' }).locator('input');
  const r0 = Number(await radius.inputValue()), s0 = Number(await strength.inputValue());
  await page.keyboard.press(']');
  await page.keyboard.press('=');
  expect(Number(await radius.inputValue())).toBeGreaterThan(r0);
  expect(Number(await strength.inputValue())).toBeGreaterThan(s0);
  // setParams sets the same brush settings.
  await page.evaluate(() => window.app.setParams({ brushRadius: '8%', brushStrength: 0.3, symmetry: 'z' }));
  await expect(radius).toHaveValue('8');
  await expect(strength).toHaveValue('0.3');
  await expect(symmetry).toHaveValue('z');
  const message = await page.evaluate(() => { try { window.app.setTool('hammer'); return ''; } catch (e) { return e.message; } });
  expect(message).toContain("unknown tool 'hammer'");
  // The help line documents the keys.
  await expect(page.locator('.adasculpt-help')).toContainText('2–8 brushes');
  expect(errors).toEqual([]);
});

test('inflate (key 3) by mouse: more vertices, larger volume; Ctrl+Z restores the exact prior stats', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  await save(page, 'start');
  const before = await stats(page);
  const shape0 = await shape(page);
  await page.keyboard.press('3');
  await stroke(page, { fy: 0.4, dx: 0.2, dy: -0.9 });
  const after = await stats(page);
  const shape1 = await shape(page);
  console.log(`inflate: ${before.vertices} -> ${after.vertices} vertices, volume ${shape0.volume.toFixed(4)} -> ` +
    `${shape1.volume.toFixed(4)}, max radius ${shape1.max.toFixed(4)}, min angle ${after.minAngle.toFixed(1)}, ` +
    `mean min ${after.meanMinAngle.toFixed(1)}`);
  expect(after.vertices).toBeGreaterThan(before.vertices);
  expect(shape1.volume).toBeGreaterThan(shape0.volume * 1.001);
  expect(shape1.max).toBeGreaterThan(1.02);
  expect(shape1.min).toBeGreaterThan(0.995);
  expect(after.minAngle).toBeGreaterThan(5);
  expect(after.canUndo).toBe(true);
  await shot(page, 'inflated');
  await page.keyboard.press('Control+z');
  const undone = await stats(page);
  for (const k of ['vertices', 'faces', 'minAngle', 'meanMinAngle', 'canUndo']) expect(undone[k], k).toEqual(before[k]);
  // The whole quality report too, but for the history flags and the last frame's timings.
  const report = ({ canUndo: _u, canRedo: _r, lastFrame: _f, ...q }) => q;
  expect(report(undone.quality)).toEqual(report(before.quality));
  expect(await sameAs(page, 'start')).toBe(true);
  expect(errors).toEqual([]);
});

test('draw (key 2) raises the surface on both sides of x = 0, exactly mirrored (symmetry X by default); Ctrl held digs in', async ({ page }) => {
  await open(page);
  await page.keyboard.press('2');
  // Right of the centre, not crossing x = 0: only the mirror stroke can touch the left side.
  await stroke(page, { fx: 0.45, fy: 0.35, dy: -0.7 });
  const drawn = await shape(page);
  console.log(`draw: ${JSON.stringify(drawn)}`);
  expect(drawn.max).toBeGreaterThan(1.025);
  expect(drawn.raisedRight).toBeGreaterThan(5);
  expect(drawn.raisedLeft).toBeGreaterThan(5);
  expect(drawn.dentedRight + drawn.dentedLeft).toBe(0);
  expect(drawn.mirrorMissing).toBe(0);  // the sphere is symmetric: the result is, vertex for vertex
  await shot(page, 'drawn-symmetric');
  // Symmetry off in the panel: a second stroke lower down changes the right side only.
  await page.locator('.lil-controller', { hasText: 'symmetry' }).locator('select').selectOption('off');
  await page.keyboard.press('Control+z');
  await stroke(page, { fx: 0.45, fy: 0.35, dy: -0.7 });
  const oneSide = await shape(page);
  expect(oneSide.raisedRight).toBeGreaterThan(5);
  expect(oneSide.raisedLeft).toBe(0);
  expect(oneSide.mirrorMissing).toBeGreaterThan(0);
  // Inverted (Ctrl held while stroking): the surface goes in.
  await page.keyboard.press('Control+z');
  await stroke(page, { fx: 0.45, fy: 0.35, dy: -0.7, modifier: 'Control' });
  const dug = await shape(page);
  console.log(`inverted draw: ${JSON.stringify(dug)}`);
  expect(dug.min).toBeLessThan(0.975);
  expect(dug.raisedRight + dug.raisedLeft).toBe(0);
  await shot(page, 'drawn-inverted');
});

test('app.replay of a brush session = app.brush.stroke of the same stroke, and undo works on both', async ({ page }) => {
  const errors = watchErrors(page);
  await open(page);
  const result = await page.evaluate(async () => {
    const app = window.app;
    const path = Array.from({ length: 8 }, (_, i) => [0.3, -0.3 + 0.08 * i, Math.sqrt(1 - 0.09 - (-0.3 + 0.08 * i) ** 2)]);
    const brush = { tool: 'inflate', path, radius: 0.2, strength: 0.6, symmetry: 'x' };
    const bytes = async () => new Uint8Array(await app.export('off'));
    const same = (a, b) => a.length === b.length && a.every((x, i) => x === b[i]);
    const start = await bytes();
    const report = await app.replay({ version: 1, steps: [{ brush }] });
    const replayed = await bytes();
    const replayedStats = app.stats();
    app.undo();
    const undoneReplay = same(await bytes(), start);
    // The same stroke drawn live on the freshly loaded model (after an undo the strokes' result
    // differs: the known defect tested below).
    await app.load('models/sphere.obj');
    app.brush.stroke(brush);
    const stroked = await bytes();
    app.undo();
    return { report, replayedVertices: replayedStats.vertices, sameAsStroke: same(replayed, stroked),
      changed: !same(replayed, start), undoneReplay, undoneStroke: same(await bytes(), start) };
  });
  console.log(`replay report: ${JSON.stringify(result.report)}`);
  expect(result.changed).toBe(true);
  expect(result.report.vertices).toBe(result.replayedVertices);
  expect(result.replayedVertices).toBeGreaterThan(2562);
  expect(result.sameAsStroke).toBe(true);
  expect(result.undoneReplay).toBe(true);
  expect(result.undoneStroke).toBe(true);
  // A bad brush step is a one-line message naming the field.
  const message = await page.evaluate(() => window.app.replay({ version: 1, steps: [{ brush: { tool: 'draw', path: [[0, 0, 1]] } }] })
    .then(() => '', (e) => e.message));
  expect(message).toContain("'radius' is missing");
  expect(errors).toEqual([]);
});

test('with a brush selected, a drag on empty space orbits and leaves the mesh alone', async ({ page }) => {
  await open(page);
  await page.evaluate(() => window.app.load('models/fandisk.off'));
  await page.keyboard.press('2');
  await save(page, 'fandisk');
  const probe = async () => {
    await snapshotCanvas(page);
    return page.evaluate(() => {
      const g = window.__canvas2d;
      return Array.from(g.getImageData(0, 0, g.canvas.width, g.canvas.height).data.filter((_, i) => i % 97 === 0));
    });
  };
  const view0 = await probe();
  await stroke(page, { at: { x: 40, y: 560 }, dx: 1, dy: 0 });
  const view1 = await probe();
  const changedPixels = view0.filter((v, i) => Math.abs(v - view1[i]) > 10).length;
  expect(changedPixels, 'the view rotated').toBeGreaterThan(50);
  expect(await sameAs(page, 'fandisk')).toBe(true);
  expect((await stats(page)).canUndo).toBe(false);
});

test('pen pressure scales a stroke; the mouse strokes at full strength', async ({ page }) => {
  await open(page);
  await page.keyboard.press('2');
  // Synthetic pen events (Playwright's mouse is a mouse): the same stroke at pressure 0.15 and 1.
  const m = await modelOnScreen(page);
  const raise = (pressure) => page.evaluate(async ([p, m]) => {
    await window.app.load('models/sphere.obj');
    const c = document.querySelector('canvas');
    const ev = (type, i) => new PointerEvent(type, { pointerId: 7, pointerType: 'pen', pressure: p, button: 0, buttons: 1,
      clientX: m.x + 0.2 * m.r, clientY: m.y + 0.4 * m.r - 0.08 * m.r * i, bubbles: true, cancelable: true, isPrimary: true });
    const frame = () => new Promise((f) => requestAnimationFrame(f));
    c.dispatchEvent(ev('pointerdown', 0));
    for (let i = 1; i <= 10; i++) { c.dispatchEvent(ev('pointermove', i)); await frame(); }
    c.dispatchEvent(ev('pointerup', 10));
    await frame();
    const pos = window.app.session.positions();
    let max = 0;
    for (let v = 0; v < pos.length; v += 3) max = Math.max(max, Math.hypot(pos[v], pos[v + 1], pos[v + 2]));
    return max - 1;
  }, [pressure, m]);
  const light = await raise(0.15);
  const firm = await raise(1);
  console.log(`pen raise: pressure 0.15 -> ${light.toFixed(4)}, pressure 1 -> ${firm.toFixed(4)}`);
  expect(firm).toBeGreaterThan(0.03);
  expect(light).toBeGreaterThan(0);
  expect(light).toBeLessThan(firm * 0.5);
});

test('while stroking, at most one call into wasm per animation frame', async ({ page }) => {
  await open(page);
  await page.keyboard.press('3');
  const m = await modelOnScreen(page);
  await page.evaluate(() => {
    const proto = Object.getPrototypeOf(window.app.session);
    window.__calls = { n: 0, frames: [], names: new Set() };
    for (const k of Object.getOwnPropertyNames(proto)) {
      const f = proto[k];
      if (k === 'constructor' || typeof f !== 'function') continue;
      proto[k] = function (...a) { window.__calls.n++; window.__calls.names.add(k); return f.apply(this, a); };
    }
    (function tick() {
      window.__calls.frames.push(window.__calls.n);
      window.__calls.n = 0;
      requestAnimationFrame(tick);
    })();
  });
  const x = m.x, y = m.y + 0.5 * m.r;
  await page.mouse.move(x, y);
  // Hovering with a brush costs no wasm call at all (the cursor ray is cast in JS).
  await page.evaluate(() => { window.__calls.frames = []; });
  for (let i = 1; i <= 6; i++) await page.mouse.move(x + i, y - i);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const hover = await page.evaluate(() => window.__calls.frames);
  await page.mouse.down(); // brushBegin happens here, in the event handler
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.evaluate(() => { window.__calls.frames = []; window.__calls.names.clear(); });
  for (let i = 1; i <= 30; i++) {
    await page.mouse.move(x + i, y - i * 3);
    if (i % 3 === 0) await page.evaluate(() => new Promise((r) => requestAnimationFrame(r)));
  }
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const { frames, names } = await page.evaluate(() => ({ frames: window.__calls.frames, names: [...window.__calls.names] }));
  await page.mouse.up();
  console.log(`wasm calls per frame while stroking: ${JSON.stringify(frames)} (${names.join(', ')}); hovering: ${JSON.stringify(hover)}`);
  expect(Math.max(...hover)).toBe(0);
  expect(Math.max(...frames)).toBe(1);
  expect(frames.reduce((a, b) => a + b, 0)).toBeGreaterThan(3);
  expect(names).toEqual(['brushStamp']);
  await shot(page, 'cursor');
});

// Once a defect (issue 18): after a replayed stroke was undone, the same stroke gave another result
// (sphere, inflate: 2,674 vertices instead of 2,776): the next stroke's remesher took over the arrays
// the last one had left on the mesh. A remesher now removes its arrays, and undo brings back where
// the last stroke ended (native tests: SculptUndoLog.AStrokeUndoneAndDrawnAgainGivesTheSameMesh,
// SculptRedraw.*, which also redraws a stroke that followed another one).
test('a replayed stroke, undone and drawn again, gives the same mesh as the replay', async ({ page }) => {
  await open(page);
  const same = await page.evaluate(async () => {
    const app = window.app;
    const path = Array.from({ length: 8 }, (_, i) => [0.3, -0.3 + 0.08 * i, Math.sqrt(1 - 0.09 - (-0.3 + 0.08 * i) ** 2)]);
    const brush = { tool: 'inflate', path, radius: 0.2, strength: 0.6, symmetry: 'x' };
    const bytes = async () => new Uint8Array(await app.export('off'));
    await app.replay({ version: 1, steps: [{ brush }] });
    const first = await bytes();
    app.undo();
    app.brush.stroke(brush);
    const again = await bytes();
    return first.length === again.length && first.every((x, i) => x === again[i]);
  });
  expect(same).toBe(true);
});
