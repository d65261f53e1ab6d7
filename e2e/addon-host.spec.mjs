// The package as a host project gets it: `npm pack` of this repository, installed into a copy of
// tests/addon-host (a three.js page with its own scene, lights, camera, OrbitControls and render
// loop), built and served by vite without the source tree. The page sculpts its own mesh with
// AdaptiveSculptor through real pointer events, receives `end` events, and after dispose() holds no
// listener, scene object or GPU resource of ours. Needs the wasm build (public/wasm) for the tarball.
import { test, expect } from '@playwright/test';
import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const port = Number(process.env.ADASCULPT_E2E_PORT || 4173) + 7;
const vite = path.join(root, 'node_modules', 'vite', 'bin', 'vite.js');
let dir = null;
let server = null;

test.describe.configure({ mode: 'serial' });

test.beforeAll(async () => {
  test.skip(!fs.existsSync(path.join(root, 'public', 'wasm', 'adasculpt.wasm')), 'no wasm build (scripts/build.sh wasm)');
  test.setTimeout(180_000);
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'adasculpt-host-'));
  const run = (cmd, args, cwd) => execFileSync(cmd, args, { cwd, stdio: ['ignore', 'pipe', 'pipe'], encoding: 'utf8' });
  const tarball = run('npm', ['pack', '--silent', '--pack-destination', dir], root).trim().split('\n').pop();
  const app = path.join(dir, 'app');
  fs.cpSync(path.join(root, 'tests', 'addon-host'), app, { recursive: true });
  // From npm's cache when it has them (npm ci filled it with three and lil-gui), else the registry.
  run('npm', ['install', '--prefer-offline', '--no-audit', '--no-fund', '--ignore-scripts', path.join(dir, tarball)], app);
  // The host builds with vite (the repository's copy of the tool; nothing of the source tree is read).
  run(process.execPath, [vite, 'build', '--logLevel', 'warn'], app);
  server = spawn(process.execPath, [vite, 'preview', '--port', String(port)], { cwd: app, stdio: 'ignore' });
  for (let i = 0; i < 100; i++) {
    try {
      if ((await fetch(`http://127.0.0.1:${port}/`)).ok) return;
    } catch { /* not up yet */ }
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error('vite preview of the host did not start');
});

test.afterAll(() => {
  if (server) server.kill();
  if (dir) fs.rmSync(dir, { recursive: true, force: true });
});

test('a host page sculpts its own mesh with the packed AdaptiveSculptor; dispose leaves nothing behind', async ({ page }) => {
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(`http://127.0.0.1:${port}/`);
  await page.waitForFunction(() => document.documentElement.dataset.ready === 'true', null, { timeout: 30_000 });
  // The package's files came from node_modules/adasculpt, the wasm as a build asset of the host.
  const assets = await page.evaluate(() => performance.getEntriesByType('resource').map((r) => r.name));
  expect(assets.some((u) => /\/assets\/adasculpt-[^/]*\.wasm$/.test(u))).toBe(true);

  const r0 = await page.evaluate(() => window.host.maxRadius());
  const cameraBefore = await page.evaluate(() => window.host.camera.position.toArray());
  const c = await page.evaluate(() => window.host.clayCentre());
  // A draw stroke across the mesh, with the mouse.
  await page.mouse.move(c.x - 60, c.y + 20);
  await page.mouse.down();
  for (let i = 1; i <= 12; i++) await page.mouse.move(c.x - 60 + 10 * i, c.y + 20 - 3 * i);
  await page.mouse.up();
  await page.waitForFunction(() => window.host.events.some((e) => e.type === 'end'));
  const after = await page.evaluate(() => ({
    events: window.host.events, changes: window.host.changes, r: window.host.maxRadius(),
    same: window.host.sameGeometry(), camera: window.host.camera.position.toArray(),
  }));
  console.log(`host stroke: ${JSON.stringify(after.events)}; ${after.changes} change events; radius ${r0.toFixed(4)} -> ${after.r.toFixed(4)}`);
  expect(after.events.map((e) => e.type)).toEqual(['start', 'end']);
  const end = after.events[1];
  expect(end.tool).toBe('draw');
  expect(end.timings.frames).toBeGreaterThan(0);
  expect(end.timings.stamps).toBeGreaterThan(0);
  expect(end.vertices).toBeGreaterThan(0);
  expect(after.changes).toBeGreaterThan(0);
  expect(after.same).toBe(true);                  // the host's geometry object, changed in place
  expect(after.r).toBeGreaterThan(r0 * 1.01);     // the surface was raised
  expect(after.camera).toEqual(cameraBefore);     // the press on the mesh did not orbit

  // A drag on empty space belongs to the host's OrbitControls: the view turns, the mesh stays.
  await page.mouse.move(30, 30);
  await page.mouse.down();
  await page.mouse.move(130, 60, { steps: 5 });
  await page.mouse.up();
  const orbit = await page.evaluate(() => ({ n: window.host.events.length, camera: window.host.camera.position.toArray() }));
  expect(orbit.n).toBe(2);
  expect(orbit.camera).not.toEqual(cameraBefore);

  // Hover over the mesh so that the cursor has GPU resources, then dispose.
  const c2 = await page.evaluate(() => window.host.clayCentre());
  await page.mouse.move(c2.x, c2.y);
  await page.mouse.move(c2.x + 5, c2.y + 5);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const hovering = await page.evaluate(() => ({ ...window.host.gpu(), cursor: window.host.clay.children.length }));
  const left = await page.evaluate(() => window.host.dispose());
  console.log(`after dispose: ${JSON.stringify(left)}`);
  expect(hovering.cursor).toBe(1);                              // our brush ring, a child of the mesh
  expect(hovering.geometries).toBeGreaterThan(left.geometries[0]); // ... drawn: it had GPU buffers
  expect(left.ourListeners).toEqual([]);
  expect(left.geometries[1]).toBe(left.geometries[0]);
  expect(left.textures[1]).toBe(left.textures[0]);
  expect(left.programs[1]).toBe(left.programs[0]);
  expect(left.children[1]).toBe(left.children[0]);
  expect(left.sessionDeleted).toBe(true);
  // And the canvas no longer sculpts.
  const r1 = await page.evaluate(() => window.host.maxRadius());
  const c3 = await page.evaluate(() => window.host.clayCentre());
  await page.mouse.move(c3.x, c3.y);
  await page.mouse.down();
  await page.mouse.move(c3.x + 40, c3.y, { steps: 4 });
  await page.mouse.up();
  expect(await page.evaluate(() => window.host.maxRadius())).toBe(r1);
  expect(errors).toEqual([]);
});
