// The app's scene: renderer, camera, OrbitControls, lights, the surface (matcap or standard
// material, flat/smooth; its geometry is kept by the AdaptiveSculptor), its wireframe overlay, and
// the Pull tool's falloff drawn by the surface shader (distance to the handle centre: no per-vertex
// work in JS). Renders on demand.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const HANDLE_COLOR = new THREE.Color(1.0, 0.55, 0.15);
const ROI_COLOR = new THREE.Color(0.25, 0.6, 1.0);
const MASK_TINT = new THREE.Color(0.28, 0.32, 0.45);

export function createViewer(root) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0x23262e, 1);
  renderer.domElement.className = 'adasculpt-canvas';
  root.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = makeBackground();
  const perspective = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
  perspective.position.set(0, 0, 5);
  const ortho = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.01, 1000);
  let camera = perspective; // the active one (view-controls.js switches)
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;

  scene.add(new THREE.HemisphereLight(0xdfe8ff, 0x3a3530, 1.2));
  const key = new THREE.DirectionalLight(0xffffff, 1.6);
  key.position.set(0.6, 1, 0.8);
  camera.add(key); // the light follows the view, like a studio key light
  scene.add(camera);

  const brush = {
    uBrushCenter: { value: new THREE.Vector3() },
    uBrushRadii: { value: new THREE.Vector2(0.1, 0.3) },
    uBrushOn: { value: 0 },
  };
  const matcaps = Object.fromEntries(Object.entries(MATCAPS).map(([k, spec]) => [k, makeMatcap(spec)]));
  const matcap = new THREE.MeshMatcapMaterial({ matcap: matcaps.clay, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  const standard = new THREE.MeshStandardMaterial({ color: 0xc9a58f, roughness: 0.55, metalness: 0.0, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  for (const m of [matcap, standard]) addBrushFalloff(m, brush, addMaskTint);
  const wireMaterial = new THREE.LineBasicMaterial({ color: 0x1b1d22, transparent: true, opacity: 0.45 });

  const surface = new THREE.Mesh(new THREE.BufferGeometry(), matcap);
  surface.frustumCulled = false; // the core moves vertices: a cached bounding sphere would go stale
  const wire = new THREE.LineSegments(new THREE.BufferGeometry(), wireMaterial);
  wire.frustumCulled = false;
  wire.visible = false;
  scene.add(surface, wire);
  const mirror = makeMirrorPlane();
  scene.add(mirror);

  let needsRender = true;
  const requestRender = () => { needsRender = true; };
  controls.addEventListener('change', requestRender);

  // A panel over the right edge hides part of the canvas: shift the projection centre into the
  // free part (the canvas still fills the container, so nothing jumps when the panel closes).
  // The same for the tool buttons (and stats) on the left edge.
  let insetRight = 0;
  let insetLeft = 0;
  let insetTop = 0; // the stats box
  const topOf = (h) => Math.min(insetTop, h / 4);
  let orthoHalfHeight = 1; // the orthographic frustum's half height at zoom 1
  const insets = (w) => {
    const r = Math.min(insetRight, w / 2);
    return [Math.min(insetLeft, (w - r) / 3), r];
  };
  const resize = () => {
    const w = Math.max(1, root.clientWidth), h = Math.max(1, root.clientHeight);
    renderer.setSize(w, h, false);
    perspective.aspect = w / h;
    Object.assign(ortho, { left: -orthoHalfHeight * w / h, right: orthoHalfHeight * w / h, top: orthoHalfHeight, bottom: -orthoHalfHeight });
    const [l, r] = insets(w);
    for (const c of [perspective, ortho]) {
      const t = topOf(h);
      if (l > 0 || r > 0 || t > 0) c.setViewOffset(w, h, (r - l) / 2, -t / 2, w, h);
      else c.clearViewOffset();
      c.updateProjectionMatrix();
    }
    requestRender();
  };
  const observer = new ResizeObserver(resize);
  observer.observe(root);
  resize();

  // Keeps near/far proportional to the distance, so zooming in close never clips the surface.
  controls.addEventListener('change', () => {
    const d = camera.position.distanceTo(controls.target);
    const near = Math.max(d / 100, 1e-6), far = d * 100 + modelRadius * 4;
    if (Math.abs(camera.near - near) > near * 1e-3 || Math.abs(camera.far - far) > far * 1e-3) {
      camera.near = near;
      camera.far = far;
      camera.updateProjectionMatrix();
    }
  });
  let modelRadius = 1;

  return {
    renderer, scene, controls, surface, wire, mirror, requestRender, matcaps: Object.keys(MATCAPS),
    get camera() { return camera; },
    get orthographic() { return camera === ortho; },
    get modelRadius() { return modelRadius; },
    get needsRender() { return needsRender; },

    setWireGeometry(lineGeometry) {
      wire.geometry.dispose();
      wire.geometry = lineGeometry;
      requestRender();
    },

    setInsetRight(px) {
      insetRight = px;
      resize();
    },
    setInsetLeft(px) {
      insetLeft = px;
      resize();
    },
    setInsetTop(px) {
      insetTop = px;
      resize();
    },

    // Frames the box: centre as orbit target, distance so that its bounding sphere fits the free
    // part of the canvas (between the insets), seen from `dir` (default: the current direction, or
    // the 3/4 view when the camera sits on the target). Sets the zoom limits from the model's size:
    // perspective from 1.05 radii of the target (the camera stays outside the model's bounding
    // sphere around a centred target: the view never goes empty) to 12 framing distances;
    // orthographic from 1/12 of the framed size to 20 times closer.
    fitView(box, dir) {
      if (box.isEmpty()) return;
      const sphere = box.getBoundingSphere(new THREE.Sphere());
      const w = Math.max(1, root.clientWidth), h = Math.max(1, root.clientHeight);
      const [l, r] = insets(w);
      const t = topOf(h);
      const freeAspect = Math.max(0.2, (w - l - r) / (h - t));
      const halfFull = THREE.MathUtils.degToRad(perspective.fov) / 2;
      const halfV = Math.atan(Math.tan(halfFull) * (h - t) / h);
      const halfH = Math.atan(Math.tan(halfV) * freeAspect);
      const dist = (sphere.radius / Math.sin(Math.min(halfV, halfH))) * 1.08;
      let d = dir ? dir.clone() : camera.position.clone().sub(controls.target);
      if (d.lengthSq() < 1e-20 || !dir && this._firstFit !== false) d = new THREE.Vector3(0.35, 0.25, 1);
      this._firstFit = false;
      d.normalize();
      modelRadius = sphere.radius;
      controls.target.copy(sphere.center);
      camera.position.copy(sphere.center).addScaledVector(d, dist);
      orthoHalfHeight = dist * Math.tan(halfFull);
      ortho.zoom = 1;
      controls.minDistance = sphere.radius * 1.05;
      controls.maxDistance = dist * 12;
      controls.minZoom = 1 / 12;
      controls.maxZoom = 20;
      resize();
      controls.update();
      requestRender();
    },

    // Perspective <-> orthographic with the same view: the orthographic frustum as high as the
    // perspective one at the target, and back at the distance that shows the same height.
    setOrthographic(on) {
      if (on === (camera === ortho)) return;
      const halfV = THREE.MathUtils.degToRad(perspective.fov) / 2;
      const offset = camera.position.clone().sub(controls.target);
      const next = on ? ortho : perspective;
      if (on) {
        orthoHalfHeight = offset.length() * Math.tan(halfV);
        ortho.zoom = 1;
      } else {
        const shown = orthoHalfHeight / ortho.zoom;
        const len = THREE.MathUtils.clamp(shown / Math.tan(halfV), controls.minDistance, controls.maxDistance);
        offset.setLength(len);
      }
      next.position.copy(controls.target).add(offset);
      next.quaternion.copy(camera.quaternion);
      next.up.copy(camera.up);
      const light = camera.children.slice();
      for (const c of light) next.add(c);
      scene.remove(camera);
      scene.add(next);
      camera = next;
      controls.object = next;
      resize();
      controls.update();
      requestRender();
      this.onCameraChange?.(next);
    },

    // The symmetric brush's mirror plane (axis 'x'|'y'|'z', null: hidden), sized to the box.
    setMirror(axis, box) {
      mirror.visible = !!axis && !box.isEmpty();
      if (mirror.visible) {
        const size = box.getSize(new THREE.Vector3()).multiplyScalar(1.15);
        const c = box.getCenter(new THREE.Vector3());
        mirror.position.set(axis === 'x' ? 0 : c.x, axis === 'y' ? 0 : c.y, axis === 'z' ? 0 : c.z);
        mirror.rotation.set(0, 0, 0);
        if (axis === 'x') { mirror.rotation.y = Math.PI / 2; mirror.scale.set(size.z, size.y, 1); }
        if (axis === 'y') { mirror.rotation.x = Math.PI / 2; mirror.scale.set(size.x, size.z, 1); }
        if (axis === 'z') mirror.scale.set(size.x, size.y, 1);
      }
      requestRender();
    },

    setMatcap(name) {
      if (!matcaps[name]) throw new Error(`unknown matcap '${name}'; one of ${Object.keys(MATCAPS).join(', ')}`);
      matcap.matcap = matcaps[name];
      matcap.needsUpdate = true;
      requestRender();
    },

    setShading({ mode, flat }) {
      const m = mode === 'standard' ? standard : matcap;
      for (const mat of [matcap, standard]) {
        if (mat.flatShading !== flat) { mat.flatShading = flat; mat.needsUpdate = true; }
      }
      surface.material = m;
      requestRender();
    },

    setWireframe(on) { wire.visible = on; requestRender(); },

    setBrush({ center, handleRadius, roiRadius, visible }) {
      if (center) brush.uBrushCenter.value.copy(center);
      if (handleRadius !== undefined) brush.uBrushRadii.value.set(handleRadius, roiRadius);
      brush.uBrushOn.value = visible ? 1 : 0;
      requestRender();
    },

    precompile() {
      renderer.compileAsync(scene, camera).catch(() => {});
    },

    render() {
      renderer.render(scene, camera);
      needsRender = false;
    },

    dispose() {
      observer.disconnect();
      surface.geometry.dispose();
      controls.dispose();
      for (const m of [matcap, standard, wireMaterial]) m.dispose();
      for (const t of Object.values(matcaps)) t.dispose();
      mirror.geometry.dispose();
      for (const c of mirror.children) c.geometry.dispose();
      mirror.material.dispose();
      mirror.children[0].material.dispose();
      scene.background.dispose();
      renderer.dispose();
      renderer.forceContextLoss(); // browsers keep only a few live WebGL contexts per page
      renderer.domElement.remove();
    },
  };
}

// The falloff the grab will apply, drawn on the surface: the handle region solid, the ROI fading
// out, and thin rings at both radii. Euclidean distance to the centre, a good preview of the
// geodesic radii the core uses on the parts a user grabs. `more`: further shader changes (the mask tint).
function addBrushFalloff(material, brush, more) {
  material.onBeforeCompile = (shader) => {
    Object.assign(shader.uniforms, brush);
    shader.vertexShader = shader.vertexShader
      .replace('#include <common>', '#include <common>\nvarying vec3 vBrushWorld;')
      .replace('#include <begin_vertex>', '#include <begin_vertex>\nvBrushWorld = (modelMatrix * vec4(transformed, 1.0)).xyz;');
    shader.fragmentShader = shader.fragmentShader
      .replace('#include <common>', `#include <common>
varying vec3 vBrushWorld;
uniform vec3 uBrushCenter;
uniform vec2 uBrushRadii;
uniform float uBrushOn;`)
      .replace('#include <dithering_fragment>', `#include <dithering_fragment>
if (uBrushOn > 0.5) {
  float d = distance(vBrushWorld, uBrushCenter);
  float w = fwidth(d) * 1.5;
  vec3 c = gl_FragColor.rgb;
  if (d < uBrushRadii.y) {
    float t = clamp((d - uBrushRadii.x) / max(uBrushRadii.y - uBrushRadii.x, 1e-9), 0.0, 1.0);
    float fall = d < uBrushRadii.x ? 1.0 : 1.0 - t * t * (3.0 - 2.0 * t);
    c = d < uBrushRadii.x ? mix(c, vec3(${rgb(HANDLE_COLOR)}), 0.45) : mix(c, vec3(${rgb(ROI_COLOR)}), 0.35 * fall);
  }
  float ring = max(1.0 - abs(d - uBrushRadii.x) / w, 1.0 - abs(d - uBrushRadii.y) / w);
  gl_FragColor.rgb = mix(c, vec3(1.0), 0.8 * clamp(ring, 0.0, 1.0));
}`);
    more(shader); // (after: its code goes right after the include, before the preview's)
  };
}

// The sculpting mask (the geometry's 'mask' attribute, web/mesh-buffers.js) as a dark tint: a
// fully masked part is drawn at a third of its brightness, bluish, so the user sees what will not
// move. A geometry without the attribute reads 0 (WebGL's default for a disabled attribute).
function addMaskTint(shader) {
  shader.vertexShader = shader.vertexShader
    .replace('#include <common>', '#include <common>\nattribute float mask;\nvarying float vMask;')
    .replace('#include <begin_vertex>', '#include <begin_vertex>\nvMask = mask;');
  shader.fragmentShader = shader.fragmentShader
    .replace('#include <common>', '#include <common>\nvarying float vMask;')
    .replace('#include <dithering_fragment>', `#include <dithering_fragment>
gl_FragColor.rgb = mix(gl_FragColor.rgb, gl_FragColor.rgb * vec3(${rgb(MASK_TINT)}), clamp(vMask, 0.0, 1.0));`);
}

function rgb(c) { return `${c.r.toFixed(3)}, ${c.g.toFixed(3)}, ${c.b.toFixed(3)}`; }

// The matcaps, painted into canvases (no image file to fetch): base colour, fill tint, rim and
// highlight strength and sharpness.
const MATCAPS = {
  clay: { base: [0.80, 0.64, 0.55], cool: [0.55, 0.62, 0.8], rim: 0.25, spec: 0.35, shine: 40 },
  'red wax': { base: [0.78, 0.22, 0.18], cool: [0.5, 0.3, 0.5], rim: 0.2, spec: 0.6, shine: 60 },
  jade: { base: [0.36, 0.66, 0.5], cool: [0.3, 0.5, 0.8], rim: 0.35, spec: 0.45, shine: 25 },
  'blue steel': { base: [0.42, 0.5, 0.66], cool: [0.7, 0.75, 0.9], rim: 0.5, spec: 0.9, shine: 90 },
  chalk: { base: [0.9, 0.9, 0.88], cool: [0.6, 0.6, 0.7], rim: 0.1, spec: 0.05, shine: 8 },
};

// One matcap: soft key light from the upper left, a tinted fill from below, a rim and a highlight.
function makeMatcap({ base, cool: coolTint, rim: rimK, spec: specK, shine }) {
  const size = 256;
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const ctx = canvas.getContext('2d');
  const img = ctx.createImageData(size, size);
  const L = new THREE.Vector3(-0.45, 0.55, 0.7).normalize();
  const F = new THREE.Vector3(0.3, -0.8, 0.5).normalize();
  const H = L.clone().add(new THREE.Vector3(0, 0, 1)).normalize(); // Blinn half vector, view along +z
  const n = new THREE.Vector3();
  for (let y = 0; y < size; y++) {
    for (let x = 0; x < size; x++) {
      const nx = (x + 0.5) / size * 2 - 1, ny = 1 - (y + 0.5) / size * 2;
      const r2 = nx * nx + ny * ny;
      const o = 4 * (y * size + x);
      if (r2 > 1) { img.data[o + 3] = 255; continue; }
      n.set(nx, ny, Math.sqrt(1 - r2));
      const diff = Math.max(0, n.dot(L));
      const fill = Math.max(0, n.dot(F));
      const rim = Math.pow(1 - n.z, 3);
      const spec = Math.pow(Math.max(0, n.dot(H)), shine) * specK;
      for (let k = 0; k < 3; k++) {
        const v = base[k] * (0.18 + 0.85 * diff) + coolTint[k] * 0.22 * fill + rimK * rim + spec;
        img.data[o + k] = Math.min(255, Math.round(255 * Math.pow(Math.min(v, 1), 1 / 1.1)));
      }
      img.data[o + 3] = 255;
    }
  }
  ctx.putImageData(img, 0, 0);
  const tex = new THREE.CanvasTexture(canvas);
  tex.colorSpace = THREE.SRGBColorSpace;
  return tex;
}

// A faint unit square (scaled and turned by setMirror) with a brighter outline: the mirror plane.
function makeMirrorPlane() {
  const material = new THREE.MeshBasicMaterial({ color: 0x7fd4ff, transparent: true, opacity: 0.16, side: THREE.DoubleSide, depthWrite: false });
  const plane = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), material);
  const edges = new THREE.LineSegments(new THREE.EdgesGeometry(plane.geometry),
    new THREE.LineBasicMaterial({ color: 0x7fd4ff, transparent: true, opacity: 0.5 }));
  plane.add(edges);
  plane.visible = false;
  plane.renderOrder = 2;
  plane.frustumCulled = false;
  return plane;
}

// A quiet vertical gradient behind the model.
function makeBackground() {
  const canvas = document.createElement('canvas');
  canvas.width = 2;
  canvas.height = 256;
  const ctx = canvas.getContext('2d');
  const g = ctx.createLinearGradient(0, 0, 0, 256);
  g.addColorStop(0, '#3a3f4b');
  g.addColorStop(1, '#16181d');
  ctx.fillStyle = g;
  ctx.fillRect(0, 0, 2, 256);
  const tex = new THREE.CanvasTexture(canvas);
  tex.colorSpace = THREE.SRGBColorSpace;
  return tex;
}
