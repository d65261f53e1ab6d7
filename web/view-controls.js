// The app's view commands (`app.view`): frame the model, the six axis views, perspective or
// orthographic, with their keys and two buttons under the tool palette. Keys never collide with
// the tool keys 1-8: F or Home or numpad "." frame, O or numpad 5 toggle orthographic, Shift+1..6
// (the digit row's codes, whatever the layout prints) or numpad 1/3/7 (with Ctrl: the opposite side)
// for the axis views.
import * as THREE from 'three';
import { isTextInput } from './tool-events.js';

// Where the camera sits, seen from the target (a hair off the pole for top/bottom, so that
// OrbitControls keeps +y up).
export const VIEWS = {
  front: [0, 0, 1], back: [0, 0, -1], right: [1, 0, 0], left: [-1, 0, 0], top: [0, 1, 1e-4], bottom: [0, -1, 1e-4],
};
const SHIFT_DIGITS = ['front', 'back', 'left', 'right', 'top', 'bottom'];
const NUMPAD = { Numpad1: ['front', 'back'], Numpad3: ['right', 'left'], Numpad7: ['top', 'bottom'] };

// viewer: web/viewer.js; bounds(): the model's Box3; onCamera(camera): the active camera changed.
// pivot(): the surface point the last orbit drag turned around (web/camera-gestures.js), or null.
export function createViewControls({ viewer, bounds, keyTarget, parent, onCamera, pivot = () => null }) {
  viewer.onCameraChange = onCamera;
  const view = {
    frame() { viewer.fitView(bounds()); },
    set(name) {
      const dir = VIEWS[name];
      if (!dir) throw new Error(`view.set: unknown view '${name}'; one of ${Object.keys(VIEWS).join(', ')}`);
      viewer.fitView(bounds(), new THREE.Vector3(...dir));
    },
    orthographic(on) {
      if (on !== undefined) viewer.setOrthographic(!!on);
      return viewer.orthographic;
    },
    // The camera, for scripts and tests: position, target, up, distance, zoom, projection, last orbit pivot.
    state() {
      const c = viewer.camera;
      return {
        position: c.position.toArray(), target: viewer.controls.target.toArray(), up: c.up.toArray(),
        distance: c.position.distanceTo(viewer.controls.target), zoom: c.zoom, orthographic: viewer.orthographic,
        minDistance: viewer.controls.minDistance, maxDistance: viewer.controls.maxDistance,
        minZoom: viewer.controls.minZoom, maxZoom: viewer.controls.maxZoom, modelRadius: viewer.modelRadius,
        pivot: pivot()?.toArray() ?? null,
      };
    },
  };

  const onKey = (e) => {
    if (e.metaKey || e.altKey || isTextInput(e.target)) return;
    let done = true;
    // The numpad by code first: without NumLock its 7 and 1 say 'Home' and 'End'.
    if (NUMPAD[e.code] && !e.shiftKey) view.set(NUMPAD[e.code][e.ctrlKey ? 1 : 0]);
    else if (!e.ctrlKey && !e.shiftKey && (e.key === 'f' || e.key === 'F' || e.code === 'Home' || e.code === 'NumpadDecimal')) view.frame();
    else if (!e.ctrlKey && !e.shiftKey && (e.key === 'o' || e.key === 'O' || e.code === 'Numpad5')) view.orthographic(!viewer.orthographic);
    else if (e.shiftKey && !e.ctrlKey && /^Digit[1-6]$/.test(e.code)) view.set(SHIFT_DIGITS[Number(e.code[5]) - 1]);
    else done = false;
    if (done) e.preventDefault();
  };
  keyTarget.addEventListener('keydown', onKey);

  let bar = null;
  let orthoButton = null;
  if (parent) {
    bar = document.createElement('div');
    bar.className = 'adasculpt-view';
    const button = (label, key, title, fn) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.title = title;
      b.innerHTML = `<span class="key">${key}</span>${label}`;
      b.addEventListener('click', fn);
      bar.appendChild(b);
      return b;
    };
    button('Frame', 'F', 'frame the model (F, Home)', () => view.frame());
    orthoButton = button('Ortho', 'O', 'orthographic / perspective (O, numpad 5)', () => view.orthographic(!viewer.orthographic));
    parent.appendChild(bar);
  }
  const refresh = () => orthoButton?.setAttribute('aria-pressed', String(viewer.orthographic));
  const prev = viewer.onCameraChange;
  viewer.onCameraChange = (c) => { refresh(); prev?.(c); };
  refresh();

  return {
    view,
    el: bar,
    dispose() {
      keyTarget.removeEventListener('keydown', onKey);
      bar?.remove();
    },
  };
}
