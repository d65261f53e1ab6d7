// The control panel (lil-gui): remeshing settings, grab radii, brush settings, display, whole-mesh remesh with
// progress, files and history. Lengths are shown in percent of the bounding-box diagonal.
import GUI from 'lil-gui';
import { SYMMETRY } from './settings.js';
import { MASK_OPS } from './mask-api.js';
import { FALLOFFS } from './brush-feel.js';

// The detail modes as the panel names them (web/brush-feel.js explains each).
const DETAIL_LABELS = { 'ε (relative)': 'relative', constant: 'constant', 'brush radius': 'brush', 'screen pixels': 'pixels' };

export const SAMPLES = { sphere: 'models/sphere.obj', fandisk: 'models/fandisk.off', hemisphere: 'models/hemisphere.off' };

// state: the panel's values (percent lengths, radii, display); actions: what the buttons do.
export function createPanel(parent, state, actions) {
  const gui = new GUI({ container: parent, title: 'adasculpt', width: 250 });
  gui.domElement.classList.add('adasculpt-panel');

  const files = gui.addFolder('Model');
  const ui = { sample: state.sample || 'sphere', format: 'obj' };
  let sampleCtl = files.add(ui, 'sample', Object.keys(SAMPLES)).name('model').onChange((v) => actions.loadSample(v));
  files.add({ open: () => actions.open() }, 'open').name('open file… (obj stl ply off)');
  files.add(ui, 'format', ['obj', 'stl', 'ply', 'off']).name('export format');
  files.add({ save: () => actions.exportMesh(ui.format) }, 'save').name('export / download');

  const remesh = gui.addFolder('Remeshing');
  const settingsChanged = () => actions.settings();
  remesh.add(state, 'epsilon', 0.005, 1, 0.005).name('epsilon (% diag)').onFinishChange(settingsChanged);
  remesh.add(state, 'minLength', 0.01, 5, 0.01).name('min length (%)').onFinishChange(settingsChanged);
  remesh.add(state, 'maxLength', 0.5, 20, 0.1).name('max length (%)').onFinishChange(settingsChanged);
  remesh.add(state, 'features', 0, 90, 1).name('features (deg, 0 off)').onFinishChange(settingsChanged);
  // Sculpting's remeshing checks each operation against crossing the surface: safer hard pinches, slower frames.
  remesh.add(state, 'guardCrossings').name('no self-crossings (slower)').onChange(settingsChanged);
  remesh.add(state, 'iterations', 1, 20, 1).name('iterations');
  const remeshButton = remesh.add({ run: () => actions.remesh() }, 'run').name('remesh whole mesh');

  const brush = gui.addFolder('Grab');
  brush.add(state, 'handleRadius', 0.5, 30, 0.1).name('handle radius (%)').onChange(() => actions.radii());
  brush.add(state, 'roiRadius', 1, 80, 0.5).name('ROI radius (%)').onChange(() => actions.radii());

  // The brushes' settings (tools: the palette on the left, keys 1-8); symmetry mirrors across x/y/z = 0.
  const sculpt = gui.addFolder('Brush');
  sculpt.add(state, 'brushRadius', 0.5, 30, 0.1).name('radius (%)').onChange(() => actions.brush());
  sculpt.add(state, 'brushStrength', 0.05, 1, 0.01).name('strength').onChange(() => actions.brush());
  sculpt.add(state, 'symmetry', SYMMETRY).name('symmetry').onChange(() => actions.brush());
  // Feel: the falloff preset, stamps per radius of travel, the lazy-mouse string (0: off).
  sculpt.add(state, 'falloff', FALLOFFS).name('falloff').onChange(() => actions.feel());
  sculpt.add(state, 'spacing', 0.05, 1, 0.01).name('spacing (× radius)').onChange(() => actions.feel());
  sculpt.add(state, 'stabilizer', 0, 100, 1).name('stabilizer (px, 0 off)').onChange(() => actions.feel());

  // Detail: what edge length strokes remesh to; only the current mode's size is shown.
  const detail = gui.addFolder('Detail');
  detail.add(state, 'detailMode', DETAIL_LABELS).name('detail').onChange(() => { showDetailSize(); actions.feel(); });
  const sizes = {
    constant: detail.add(state, 'constantDetail', 0.05, 5, 0.01).name('edge length (%)'),
    brush: detail.add(state, 'brushDetail', 1, 100, 1).name('edge (% of radius)'),
    pixels: detail.add(state, 'pixelDetail', 1, 40, 1).name('edge (screen px)'),
  };
  for (const c of Object.values(sizes)) c.onChange(() => actions.feel());
  const showDetailSize = () => { for (const [mode, c] of Object.entries(sizes)) c.show(state.detailMode === mode); };
  showDetailSize();
  const floodButton = detail.add({ run: () => actions.floodFill() }, 'run').name('detail flood fill');

  // The mask (tool M: paint, Ctrl/Alt erase; radius and strength are the brush's): masked parts never move.
  const mask = gui.addFolder('Mask');
  for (const op of MASK_OPS) mask.add({ [op]: () => actions.mask(op) }, op).name(`${op} mask`);

  const view = gui.addFolder('Display');
  view.add(state, 'matcap', actions.matcaps).name('matcap').onChange(() => actions.display());
  view.add(state, 'shading', ['matcap', 'standard']).name('material').onChange(() => actions.display());
  view.add(state, 'flat').name('flat shading').onChange(() => actions.display());
  view.add(state, 'wireframe').name('wireframe overlay').onChange(() => actions.display());
  view.add({ frame: () => actions.view.frame() }, 'frame').name('frame model (F)');
  const axis = { view: 'front' };
  view.add(axis, 'view', ['front', 'back', 'left', 'right', 'top', 'bottom']).name('axis view (Shift+1–6)')
    .onChange((v) => actions.view.set(v));
  const ortho = { on: false };
  view.add(ortho, 'on').name('orthographic (O)').onChange((v) => actions.view.orthographic(v));

  const history = gui.addFolder('History');
  const undo = history.add({ undo: () => actions.undo() }, 'undo').name('undo (Ctrl+Z)');
  const redo = history.add({ redo: () => actions.redo() }, 'redo').name('redo (Ctrl+Shift+Z)');

  return {
    gui,
    refresh() {
      if (actions.view) ortho.on = actions.view.orthographic();
      for (const c of gui.controllersRecursive()) c.updateDisplay();
      showDetailSize();
    },
    // Short views: only the Brush folder stays open (lil-gui scrolls the rest).
    compact() {
      for (const f of [files, remesh, brush, detail, mask, view, history]) f.close();
      gui.domElement.classList.add('compact');
    },
    setHistory(canUndo, canRedo) {
      undo.disable(!canUndo);
      redo.disable(!canRedo);
    },
    // The model list shows an opened file's name beside the samples.
    setSample(name) {
      const names = Object.keys(SAMPLES);
      if (!names.includes(name)) names.push(name);
      if (names.length !== sampleCtl._values.length) {
        sampleCtl = sampleCtl.options(names).name('model').onChange((v) => actions.loadSample(v));
      }
      ui.sample = name;
      sampleCtl.updateDisplay();
    },
    // null: idle; {done, total}: running. which: 'remesh' (whole mesh) or 'flood' (detail flood fill).
    setProgress(p, which = 'remesh') {
      const [button, idle, busy] = which === 'flood' ? [floodButton, 'detail flood fill', 'flood filling']
        : [remeshButton, 'remesh whole mesh', 'remeshing'];
      button.name(p ? `${busy}… ${p.done}/${p.total}` : idle);
      for (const b of [remeshButton, floodButton]) b.disable(!!p);
    },
    dispose() { gui.destroy(); },
  };
}
