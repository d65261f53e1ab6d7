// A host's TypeScript, type-checked against the package's declarations (not run): the imports
// resolve through package.json "exports" like in an installed package.
import * as THREE from 'three';
import { AdaptiveSculptor, createSculptApp, type SculptorParams, type StrokeTimings, type ToolName } from 'adasculpt';
import 'adasculpt/element';

export async function addon(renderer: THREE.WebGLRenderer, camera: THREE.PerspectiveCamera): Promise<number> {
  const mesh = new THREE.Mesh(new THREE.IcosahedronGeometry(1, 8), new THREE.MeshStandardMaterial());
  const sculptor = await AdaptiveSculptor.create(mesh, camera, {
    tool: 'draw', radius: '5%', strength: 0.5, symmetry: 'x', epsilon: 0.001, keyTarget: window,
  });
  sculptor.connect(renderer.domElement);
  sculptor.addEventListener('start', (e) => console.log(e.tool));
  sculptor.addEventListener('change', (e) => { if (e.timings) console.log(e.timings.total, e.vertices); });
  let last: StrokeTimings | null = null;
  sculptor.addEventListener('end', (e) => { last = e.timings; console.log(e.tool, e.faces); });
  const tools: ToolName[] = ['pull', 'snakeHook'];
  for (const t of tools) sculptor.setTool(t);
  const p: SculptorParams = sculptor.setParams({ radius: 0.1, handleRadius: '3%', minLength: '0.1%', features: 45 });
  sculptor.grab.begin({ center: [0, 0, 1] });
  const frame = sculptor.grab.drag({ translate: new THREE.Vector3(0, 0, 0.1), rotate: { axis: [0, 1, 0], degrees: 10 } });
  sculptor.grab.end();
  sculptor.brush.stroke({ tool: 'inflate', path: [[0, 0, 1], { x: 0.1, y: 0, z: 1 }], pressure: [1, 0.5] });
  const counts = await sculptor.remesh({ iterations: 3, onProgress: ({ done, total }) => console.log(done, total) });
  const report = sculptor.replay({ version: 1, steps: [{ undo: 1 }] });
  sculptor.undo();
  sculptor.redo();
  const q = sculptor.session.stats();
  const settings = sculptor.session.settings();
  console.log(p.percent.radius, frame.timings.stamps, counts.vertices, report, q.minAngleDeg, settings.minLength, last);
  sculptor.disconnect();
  sculptor.dispose();
  return sculptor.diagonal;
}

export async function app(container: HTMLElement): Promise<void> {
  const a = await createSculptApp(container, { model: 'models/bunny.obj', ui: false, keyboard: 'global', autosave: 'k' });
  a.addEventListener('end', (e) => console.log(e.timings.medianFrameMs));
  a.setParams({ epsilon: '0.05%', brushRadius: '8%', brushStrength: 0.3, symmetry: 'off' });
  a.setTool('crease');
  a.setTool('mask');
  a.mask.invert();
  a.mask.clear();
  a.mask.stroke({ path: [[0, 0, 1]], erase: true, radius: 0.2 });
  const masked: Float32Array = a.mask.values();
  console.log(masked.length);
  const s = a.stats();
  const bytes: ArrayBuffer = await a.export('ply');
  const saved = await a.autosave.saved();
  console.log(s.quality.genus, s.settings.diagonal, a.sculptor.tool, bytes.byteLength, saved?.savedAt);
  a.dispose();
  const el = document.createElement('adasculpt-viewer');
  el.addEventListener('adasculpt-ready', (e) => e.detail.undo());
}

// Brush feel and detail control (issue 19): falloff, spacing, stabiliser, detail modes, flood fill, the orbit pivot.
import type { SculptApp } from 'adasculpt';
export async function feel(sculptor: AdaptiveSculptor, a: SculptApp): Promise<number> {
  const p: SculptorParams = sculptor.setParams({ falloff: 'sharp', spacing: 0.1, stabilizer: 30, detailMode: 'pixels', pixelDetail: 6 });
  a.setParams({ detailMode: 'constant', constantDetail: '0.5%', brushDetail: 20 });
  sculptor.brush.stroke({ path: [[0, 0, 1]], falloff: 'constant', detail: 0.01 });
  const counts = await sculptor.floodFill({ iterations: 2 });
  const stats = await a.floodFill();
  const point = sculptor.surfacePoint(100, 100);
  const pivot = a.view.state().pivot;
  sculptor.session.remeshDetail(1, 0.02);
  console.log(p.falloff, p.percent.constantDetail, counts.vertices, stats.quality.edgeLengthMean, point?.x, pivot?.[0]);
  return sculptor.detailLength();
}
