// A host project's page: its own renderer, scene, lights, camera, OrbitControls and render loop, and
// two meshes of its own; it sculpts one of them with the installed package's AdaptiveSculptor.
// window.host exposes what e2e/addon-host.spec.mjs checks.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { AdaptiveSculptor } from 'adasculpt';

// Every listener added to the page's targets while it lives (to see that dispose removes ours).
const live = new Set();
const key = (t, type, fn, opts) => `${type}:${typeof opts === 'boolean' ? opts : !!(opts && opts.capture)}`;
const ids = new WeakMap();
let nextId = 1;
const id = (o) => { if (!ids.has(o)) ids.set(o, nextId++); return ids.get(o); };
const add = EventTarget.prototype.addEventListener;
const remove = EventTarget.prototype.removeEventListener;
// Playwright's injected script may add its own window listeners while it dispatches input (first a
// '__playwright_global_listeners_check__' one, then the rest in the same task): not ours, not counted.
let playwrightTask = false;
EventTarget.prototype.addEventListener = function (type, fn, opts) {
  if (String(type).startsWith('__playwright')) {
    playwrightTask = true;
    queueMicrotask(() => { playwrightTask = false; });
  }
  if (fn && !playwrightTask) live.add(`${id(this)}:${id(fn)}:${key(this, type, fn, opts)}`);
  return add.call(this, type, fn, opts);
};
EventTarget.prototype.removeEventListener = function (type, fn, opts) {
  if (fn) live.delete(`${id(this)}:${id(fn)}:${key(this, type, fn, opts)}`);
  return remove.call(this, type, fn, opts);
};

const renderer = new THREE.WebGLRenderer({ antialias: true });
renderer.setSize(innerWidth, innerHeight);
document.body.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x202228);
const camera = new THREE.PerspectiveCamera(45, innerWidth / innerHeight, 0.1, 100);
camera.position.set(0, 0, 6);
const controls = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.AmbientLight(0xffffff, 0.4));
const light = new THREE.DirectionalLight(0xffffff, 2);
light.position.set(2, 3, 4);
scene.add(light);

// The sculpted mesh, placed through its matrix (the sculptor works in its own coordinates).
const clay = new THREE.Mesh(new THREE.IcosahedronGeometry(1, 12), new THREE.MeshStandardMaterial({ color: 0xd0a080 }));
clay.position.set(-0.4, 0.2, 0);
clay.scale.setScalar(1.5);
scene.add(clay);
const other = new THREE.Mesh(new THREE.BoxGeometry(0.6, 0.6, 0.6), new THREE.MeshStandardMaterial({ color: 0x6080c0 }));
other.position.set(2.2, -1.2, 0);
scene.add(other);

renderer.setAnimationLoop(() => renderer.render(scene, camera));
await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));

const before = {
  listeners: new Set(live),
  geometries: renderer.info.memory.geometries,
  textures: renderer.info.memory.textures,
  programs: renderer.info.programs.length,
  children: clay.children.length,
};
const geometry = clay.geometry;
const sculptor = await AdaptiveSculptor.create(clay, camera, { tool: 'draw', radius: '20%', strength: 0.8, symmetry: 'off' });
sculptor.connect(renderer.domElement);
const events = [];
for (const type of ['start', 'end']) sculptor.addEventListener(type, (e) => events.push({ type, tool: e.tool, timings: e.timings, vertices: e.vertices }));
let changes = 0;
sculptor.addEventListener('change', () => { changes++; });

// Where a point of the scene is on the screen (CSS pixels).
function screenOf(v) {
  const p = v.clone().project(camera);
  const r = renderer.domElement.getBoundingClientRect();
  return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
}

window.host = {
  sculptor, events, clay, camera, renderer,
  get changes() { return changes; },
  sameGeometry: () => clay.geometry === geometry,
  gpu: () => ({ geometries: renderer.info.memory.geometries, programs: renderer.info.programs.length }),
  // The listeners added since the sculptor was created and still there (type:capture).
  newListeners: () => [...live].filter((l) => !before.listeners.has(l)).map((l) => l.split(':').slice(2).join(':')),
  clayCentre: () => screenOf(clay.getWorldPosition(new THREE.Vector3())),
  // Farthest live vertex from the mesh's own origin (draw raises the surface).
  maxRadius() {
    const p = clay.geometry.attributes.position;
    const idx = clay.geometry.index;
    const n = Math.min(idx.count, clay.geometry.drawRange.count);
    let m = 0;
    for (let i = 0; i < n; i++) {
      const v = idx.getX(i);
      m = Math.max(m, Math.hypot(p.getX(v), p.getY(v), p.getZ(v)));
    }
    return m;
  },
  dispose() {
    sculptor.dispose();
    return new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))).then(() => ({
      ourListeners: window.host.newListeners(),
      geometries: [before.geometries, renderer.info.memory.geometries],
      textures: [before.textures, renderer.info.memory.textures],
      programs: [before.programs, renderer.info.programs.length],
      children: [before.children, clay.children.length],
      sessionDeleted: (() => { try { sculptor.session.hasMesh(); return false; } catch { return true; } })(),
    }));
  },
};
document.documentElement.dataset.ready = 'true';
