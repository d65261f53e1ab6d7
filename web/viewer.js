// The app's scene: renderer, camera, OrbitControls, lights, the surface (matcap or standard
// material, flat/smooth; its geometry is kept by the AdaptiveSculptor), its wireframe overlay, and
// the Pull tool's falloff drawn by the surface shader (distance to the handle centre: no per-vertex
// work in JS). Renders on demand.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const HANDLE_COLOR = new THREE.Color(1.0, 0.55, 0.15);
const ROI_COLOR = new THREE.Color(0.25, 0.6, 1.0);

export function createViewer(root) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0x23262e, 1);
  renderer.domElement.className = 'adasculpt-canvas';
  root.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = makeBackground();
  const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
  camera.position.set(0, 0, 5);
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
  const matcap = new THREE.MeshMatcapMaterial({ matcap: makeMatcap(), polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  const standard = new THREE.MeshStandardMaterial({ color: 0xc9a58f, roughness: 0.55, metalness: 0.0, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  for (const m of [matcap, standard]) addBrushFalloff(m, brush);
  const wireMaterial = new THREE.LineBasicMaterial({ color: 0x1b1d22, transparent: true, opacity: 0.45 });

  const surface = new THREE.Mesh(new THREE.BufferGeometry(), matcap);
  surface.frustumCulled = false; // the core moves vertices: a cached bounding sphere would go stale
  const wire = new THREE.LineSegments(new THREE.BufferGeometry(), wireMaterial);
  wire.frustumCulled = false;
  wire.visible = false;
  scene.add(surface, wire);

  let needsRender = true;
  const requestRender = () => { needsRender = true; };
  controls.addEventListener('change', requestRender);

  // A panel over the right edge hides part of the canvas: shift the projection centre into the
  // free part (the canvas still fills the container, so nothing jumps when the panel closes).
  let insetRight = 0;
  const resize = () => {
    const w = Math.max(1, root.clientWidth), h = Math.max(1, root.clientHeight);
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    const inset = Math.min(insetRight, w / 2);
    if (inset > 0) camera.setViewOffset(w, h, inset / 2, 0, w, h);
    else camera.clearViewOffset();
    camera.updateProjectionMatrix();
    requestRender();
  };
  const observer = new ResizeObserver(resize);
  observer.observe(root);
  resize();

  return {
    renderer, scene, camera, controls, surface, wire, requestRender,
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

    // Frames the box: centre as orbit target, distance so that its bounding sphere fits the free
    // part of the canvas (left of the inset).
    fitView(box) {
      if (box.isEmpty()) return;
      const sphere = box.getBoundingSphere(new THREE.Sphere());
      const w = Math.max(1, root.clientWidth), h = Math.max(1, root.clientHeight);
      const freeAspect = Math.max(0.2, (w - Math.min(insetRight, w / 2)) / h);
      const halfV = THREE.MathUtils.degToRad(camera.fov) / 2;
      const halfH = Math.atan(Math.tan(halfV) * freeAspect);
      const dist = (sphere.radius / Math.sin(Math.min(halfV, halfH))) * 1.08;
      const dir = new THREE.Vector3(0.35, 0.25, 1).normalize();
      controls.target.copy(sphere.center);
      camera.position.copy(sphere.center).addScaledVector(dir, dist);
      camera.near = dist / 100;
      camera.far = dist * 100;
      camera.updateProjectionMatrix();
      controls.update();
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
      matcap.matcap.dispose();
      scene.background.dispose();
      renderer.dispose();
      renderer.forceContextLoss(); // browsers keep only a few live WebGL contexts per page
      renderer.domElement.remove();
    },
  };
}

// The falloff the grab will apply, drawn on the surface: the handle region solid, the ROI fading
// out, and thin rings at both radii. Euclidean distance to the centre, a good preview of the
// geodesic radii the core uses on the parts a user grabs.
function addBrushFalloff(material, brush) {
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
  };
}

function rgb(c) { return `${c.r.toFixed(3)}, ${c.g.toFixed(3)}, ${c.b.toFixed(3)}`; }

// A clay matcap painted once into a canvas (no image file to fetch): soft key light from the upper
// left, a cool fill from below, a gentle rim and a small highlight.
function makeMatcap() {
  const size = 256;
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const ctx = canvas.getContext('2d');
  const img = ctx.createImageData(size, size);
  const L = new THREE.Vector3(-0.45, 0.55, 0.7).normalize();
  const F = new THREE.Vector3(0.3, -0.8, 0.5).normalize();
  const H = L.clone().add(new THREE.Vector3(0, 0, 1)).normalize(); // Blinn half vector, view along +z
  const base = [0.80, 0.64, 0.55];
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
      const spec = Math.pow(Math.max(0, n.dot(H)), 40) * 0.35;
      for (let k = 0; k < 3; k++) {
        const cool = [0.55, 0.62, 0.8][k];
        const v = base[k] * (0.18 + 0.85 * diff) + cool * 0.22 * fill + 0.25 * rim + spec;
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
