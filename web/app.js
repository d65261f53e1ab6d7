// createSculptApp(container, options): the whole sculpting app inside one element (renderer,
// camera, OrbitControls, tool palette, panel, stats, keyboard, files, autosave), a thin app on top of
// AdaptiveSculptor (web/AdaptiveSculptor.js), which does the sculpting. Returns the page API
// (window.app on the main page), declared and documented in web/adasculpt.d.ts.
import { instantiateCore } from './wasm-module.js';
import { createViewer } from './viewer.js';
import { AdaptiveSculptor } from './AdaptiveSculptor.js';
import { ToolPalette } from './tool-palette.js';
import { createPanel, SAMPLES } from './panel.js';
import { createStatsOverlay } from './stats-overlay.js';
import { createFileInput, createToaster, download } from './file-io.js';
import { STYLE } from './style.js';
import { createAutosave, noAutosave } from './autosave.js';
import { createViewControls } from './view-controls.js';
import { createCameraGestures } from './camera-gestures.js';
import { FEEL_KEYS } from './brush-feel.js';
import { helpText } from './help-text.js';
import { checkMemory, isOutOfMemory, outOfMemoryMessage } from './memory-estimate.js';
import { TOOL_DEFAULTS, lengthToPercent } from './settings.js';
import * as THREE from 'three';

// The app's own preferences on top of the shared defaults (web/settings.js, the core's).
const APP_STATE = { iterations: 5, shading: 'matcap', matcap: 'clay', flat: false, wireframe: false };
// setParams keys of the app that are the sculptor's under another name (kept for scripts).
const ALIASES = { brushRadius: 'radius', brushStrength: 'strength' };

export async function createSculptApp(container, options = {}) {
  const opts = { model: SAMPLES.sphere, ui: true, keyboard: 'focus', ...options };
  const root = document.createElement('div');
  root.className = 'adasculpt-root';
  root.tabIndex = 0;
  const style = document.createElement('style');
  style.textContent = STYLE;
  root.appendChild(style);
  container.appendChild(root);

  // The first model downloads while the wasm module compiles.
  const firstModel = opts.model ? readSource(opts.model).catch((e) => e) : null;
  const Module = await instantiateCore(opts.wasmUrl);
  const wasmReadyMs = performance.now();
  const viewer = createViewer(root);
  const keyTarget = opts.keyboard === 'global' ? window : root;
  const sculptor = await AdaptiveSculptor.create(viewer.surface, viewer.camera, {
    module: Module, keyTarget, controls: viewer.controls, wireframe: true, tool: 'pull',
    grabPreview: (g) => viewer.setBrush(g),
  });
  const session = sculptor.session;
  viewer.setWireGeometry(sculptor.buffers.lines);
  const toaster = createToaster(root);
  const core = Module.defaultSettings();
  const pctOf = (v) => lengthToPercent(v, 1, 'default');
  const state = {
    ...APP_STATE,
    epsilon: pctOf(core.epsilon), minLength: pctOf(core.minLength), maxLength: pctOf(core.maxLength), features: core.features, guardCrossings: false,
    tool: sculptor.tool, brushRadius: 0, brushStrength: 0, symmetry: TOOL_DEFAULTS.symmetry, handleRadius: 0, roiRadius: 0,
    sample: Object.keys(SAMPLES).find((k) => SAMPLES[k] === opts.model) || 'sphere',
  };
  let disposed = false;
  let firstRenderMs = null;
  // The stats box's figures (Session.quickStats: kept up to date by the core from each change, so
  // reading them after every stroke costs the stroke, not the mesh); the whole report (a pass over
  // the mesh, ~0.9 s at 1.1M triangles) only when app.stats().quality is read.
  let quality = {};
  const frame = { core: null, copyMs: 0, renderMs: 0, vertices: 0, faces: 0, dragged: false };
  const frameLog = []; // per stroke frame: core phases, buffer update, copy, render (for benchmarks)
  let sourceName = opts.model ? String(opts.model).split(/[?#]/)[0].split('/').pop() : 'mesh';
  const autosave = opts.autosave ? createAutosave(String(opts.autosave), {
    session, toaster, root: opts.ui ? root : null,
    busy: () => sculptor.busy || session.grabbing() || session.brushing() || session.masking(),
    sourceName: () => sourceName,
    counts: () => ({ vertices: quality.vertices ?? 0, faces: quality.faces ?? 0 }),
    restored: (record) => {
      sourceName = record.name;
      showSource();
      sculptor.resync();
      readSettings();
      viewer.fitView(sculptor.buffers.boundingBox());
      refreshQuality();
    },
  }) : noAutosave();

  // ---- the sculptor's events: redraw, frame figures, the whole-mesh report after a stroke
  sculptor.addEventListener('change', (e) => {
    viewer.requestRender();
    if (e.timings) {
      frame.core = e.timings;
      frame.copyMs = e.copyMs;
      frame.vertices = e.vertices;
      frame.faces = e.faces;
      if (sculptor._stroke) frame.dragged = true;
    }
  });
  sculptor.addEventListener('end', () => {
    refreshQuality();
    autosave.changed();
  });
  sculptor.addEventListener('params', () => { readToolParams(); if (panel) panel.refresh(); });
  sculptor.addEventListener('tool', (e) => { state.tool = e.tool; if (panel) panel.refresh(); });
  sculptor.addEventListener('error', (e) => toaster.show(e.error.message, 'error'));
  sculptor.addEventListener('notice', (e) => toaster.show(e.message));

  function refreshQuality() {
    quality = session.quickStats();
    if (stats) {
      stats.update({
        vertices: quality.vertices ?? 0, faces: quality.faces ?? 0,
        minAngle: quality.minAngleDeg, meanMinAngle: quality.meanMinAngleDeg,
      });
    }
    if (panel) panel.setHistory(session.canUndo(), session.canRedo());
  }

  // The panel shows lengths in percent of the diagonal; the core answers in absolute lengths.
  function readSettings() {
    const s = session.settings();
    const diagonal = s.diagonal || 1;
    const pct = (x) => Math.round((x / diagonal) * 100 * 1e4) / 1e4;
    state.epsilon = pct(s.epsilon);
    state.minLength = pct(s.minLength);
    state.maxLength = pct(s.maxLength);
    state.features = s.features;
    state.guardCrossings = s.guardCrossings;
    readToolParams();
    if (panel) panel.refresh();
    return s;
  }
  function readToolParams() {
    const p = sculptor.params;
    state.brushRadius = p.percent.radius;
    state.handleRadius = p.percent.handleRadius;
    state.roiRadius = p.percent.roiRadius;
    state.brushStrength = p.strength;
    state.symmetry = p.symmetry;
    state.tool = p.tool;
    for (const k of FEEL_KEYS) state[k] = k === 'constantDetail' ? p.percent.constantDetail : p[k];
  }
  readToolParams();

  function loadBytes({ bytes, name }) {
    if (disposed) throw new Error('app disposed');
    try {
      sculptor.loadBytes(bytes, name); // throws with the reader's message; the old mesh stays
    } catch (e) {
      throw isOutOfMemory(e) ? new Error(outOfMemoryMessage(name, session.memoryBytes())) : e;
    }
    sourceName = name;
    showSource();
    readSettings();
    refreshQuality(); // the stats box gets its size before the model is framed beside it
    leftInset();
    viewer.fitView(sculptor.buffers.boundingBox());
    showToolState();
    return { vertices: quality.vertices, faces: quality.faces, warnings: session.loadWarnings() };
  }

  // The panel's model list and the export names follow the last opened file or sample.
  function showSource() {
    const sample = Object.keys(SAMPLES).find((k) => SAMPLES[k].split('/').pop() === sourceName);
    state.sample = sample || sourceName;
    if (panel) panel.setSample(state.sample);
  }
  function exportName(fmt) {
    const base = String(sourceName).replace(/\.[^.]*$/, '') || 'mesh';
    return `adasculpt-${base}.${fmt}`;
  }

  function afterWholeMeshChange() {
    refreshQuality();
    autosave.changed();
  }

  // Refuses a file the page has no memory for before the core reads it (web/memory-estimate.js).
  function checkFits(head, size, name) {
    const c = checkMemory(head, size, name, session.memoryBytes());
    if (!c.ok) throw new Error(c.message);
  }

  // ---- the page API (an EventDispatcher: start, change, end as the sculptor's)
  const api = Object.defineProperties(new THREE.EventDispatcher(), Object.getOwnPropertyDescriptors({
    get module() { return Module; },
    get session() { return session; },
    get sculptor() { return sculptor; },

    async load(source, format) {
      const isBlob = typeof Blob !== 'undefined' && source instanceof Blob;
      if (isBlob) {  // only the header is read before deciding
        const name = format ? `x.${String(format).replace(/^\./, '')}` : (source.name || 'mesh');
        const c = checkMemory(new Uint8Array(await source.slice(0, 65536).arrayBuffer()), source.size, name,
          session.memoryBytes());
        if (!c.ok) throw new Error(c.message.replace(/^[^:]*:/, `${source.name || 'mesh'}:`));
      }
      const src = await readSource(source, format);
      if (!isBlob) checkFits(src.bytes, src.bytes.length, src.name);
      const result = loadBytes(src);
      autosave.changed();
      return result;
    },
    // IndexedDB autosave (web/autosave.js): flush(), restore(), clear(), saved(), pending, enabled.
    get autosave() { return autosave; },

    // The sculptor's parameters (brushRadius/brushStrength: old names of radius/strength).
    setParams(p = {}) {
      const q = {};
      for (const [k, v] of Object.entries(p)) q[ALIASES[k] || k] = v;
      if ('tool' in q) throw new Error("setParams: unknown parameter 'tool' (use setTool)");
      sculptor.setParams(q);
      autosave.changed();
      return readSettings();
    },

    get grab() { return grab; },
    get brush() { return brush; },
    // The mask (tool 'mask', key M): clear(), fill(), invert(), blur(), sharpen(), stroke({path, erase}),
    // begin/stamp/end, values(); each operation one undo step.
    get mask() { return sculptor.mask; },
    get tool() { return sculptor.tool; },
    // frame(), set('front'|'back'|'left'|'right'|'top'|'bottom'), orthographic(bool), state()
    get view() { return views.view; },
    // Looks: {matcap, shading: 'matcap'|'standard', flat, wireframe}; returns the current ones.
    display(d = {}) {
      for (const k of ['matcap', 'shading', 'flat', 'wireframe']) if (k in d) state[k] = d[k];
      applyDisplay();
      if (panel) panel.refresh();
      return { matcap: state.matcap, shading: state.shading, flat: state.flat, wireframe: state.wireframe };
    },
    setTool(name) { return sculptor.setTool(name); },

    remesh({ iterations = state.iterations } = {}) {
      return wholeMesh('remesh', (onProgress) => sculptor.remesh({ iterations, onProgress }));
    },
    // The detail flood fill: the whole mesh at the current detail mode's edge length (one call, one undo step).
    floodFill({ iterations = state.iterations } = {}) {
      return wholeMesh('flood', (onProgress) => sculptor.floodFill({ iterations, onProgress }));
    },

    undo() {
      const ok = sculptor.undo();
      afterWholeMeshChange();
      return ok;
    },
    redo() {
      const ok = sculptor.redo();
      afterWholeMeshChange();
      return ok;
    },

    async replay(sessionJson) {
      const report = sculptor.replay(sessionJson);
      afterWholeMeshChange();
      return report;
    },

    stats() {
      const t = frame.core || {};
      return {
        vertices: quality.vertices ?? 0,
        faces: quality.faces ?? 0,
        minAngle: quality.minAngleDeg ?? null,
        meanMinAngle: quality.meanMinAngleDeg ?? null,
        lastFrameMs: (t.total ?? 0) + (t.buffers ?? 0) + frame.copyMs + frame.renderMs,
        coreMs: t.total ?? 0,
        buffersMs: t.buffers ?? 0,
        phasesMs: { ...t },
        uploadMs: frame.copyMs,
        renderMs: frame.renderMs,
        firstRenderMs,
        wasmReadyMs,
        canUndo: session.canUndo(),
        canRedo: session.canRedo(),
        settings: session.settings(),
        get quality() { return session.stats(); }, // the whole report, when read
      };
    },

    async export(format = 'obj') {
      const bytes = session.exportMesh(format);
      return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    },

    // The stroke frames since the last call (core, buffers, copy, render ms each), for benchmarks.
    takeFrameLog() {
      return frameLog.splice(0, frameLog.length);
    },

    // Axis-aligned bounds of the drawn mesh: {min: [x,y,z], max: [x,y,z]}.
    bounds() {
      const b = sculptor.buffers.boundingBox();
      return { min: b.min.toArray(), max: b.max.toArray() };
    },

    dispose,
  }));
  for (const type of ['start', 'change', 'end']) {
    sculptor.addEventListener(type, (e) => api.dispatchEvent({ ...e, target: undefined }));
  }
  // The programmatic strokes are the sculptor's; the whole-mesh report follows each stroke.
  const grab = {
    begin: (args) => sculptor.grab.begin(args),
    drag: (t) => sculptor.grab.drag(t),
    end: () => sculptor.grab.end(),
  };
  const brush = sculptor.brush;

  // A whole-mesh remesh (`which`: the panel button showing its progress).
  async function wholeMesh(which, run) {
    // The panel's button is disabled while it runs, which drops the focus: the keys stay with the app.
    const hadFocus = root.contains(document.activeElement);
    try {
      await run((p) => { if (panel) panel.setProgress(p, which); });
    } finally {
      if (!disposed) {
        if (panel) panel.setProgress(null, which);
        if (hadFocus && !root.contains(document.activeElement)) root.focus({ preventScroll: true });
        refreshQuality();
        autosave.changed();
      }
    }
    return api.stats();
  }

  const onKey = (e) => {
    if (!(e.ctrlKey || e.metaKey) || e.altKey) return;
    const k = e.key.toLowerCase();
    if (k === 'z' || k === 'y') {
      e.preventDefault();
      guard(() => ((k === 'z' && !e.shiftKey) ? api.undo() : api.redo()));
    }
  };
  keyTarget.addEventListener('keydown', onKey);
  function guard(fn) {
    try {
      return fn();
    } catch (e) {
      toaster.show(e.message, 'error');
      return undefined;
    }
  }

  // ---- UI: file input / drop, panel, stats
  const openFile = async (file) => {
    try {
      const { warnings } = await api.load(file);
      // The reader's repairs (each "name: what it did"): said once, so that a changed file is no surprise.
      const repairs = warnings.map((w) => w.replace(/^.*?: (?=[a-z])/, '')).join('; ');
      toaster.show(repairs ? `Opened ${file.name}, repaired: ${repairs}` : `Opened ${file.name}`);
    } catch (e) {
      // Reader messages already start with the file name.
      toaster.show(e.message.startsWith(file.name) ? `Could not open ${e.message}` : `Could not open ${file.name}: ${e.message}`, 'error');
    }
  };
  const fileInput = createFileInput(root, openFile);
  let panel = null;
  let views = null;
  let stats = null;
  let help = null;
  if (opts.ui) {
    stats = createStatsOverlay(root);
    panel = createPanel(root, state, {
      matcaps: viewer.matcaps,
      get view() { return views?.view; },
      loadSample: (name) => {
        if (!SAMPLES[name]) return; // the opened file's entry: nothing to reload
        state.sample = name;
        api.load(SAMPLES[name]).catch((e) => toaster.show(`Could not load ${name}: ${e.message}`, 'error'));
      },
      open: () => fileInput.open(),
      exportMesh: (fmt) => guard(() => download(session.exportMesh(fmt), exportName(fmt))),
      settings: () => guard(() => api.setParams({
        epsilon: `${state.epsilon}%`, minLength: `${state.minLength}%`, maxLength: `${state.maxLength}%`, features: state.features,
        guardCrossings: state.guardCrossings,
      })),
      remesh: () => api.remesh({ iterations: state.iterations }).catch((e) => toaster.show(e.message, 'error')),
      floodFill: () => api.floodFill({ iterations: state.iterations }).catch((e) => toaster.show(e.message, 'error')),
      feel: () => guard(() => sculptor.setParams(Object.fromEntries(FEEL_KEYS.map((k) =>
        [k, k === 'constantDetail' ? `${state[k]}%` : state[k]])))),
      radii: () => {
        if (state.handleRadius > state.roiRadius) state.handleRadius = state.roiRadius * 0.9;
        guard(() => sculptor.setParams({ handleRadius: `${state.handleRadius}%`, roiRadius: `${state.roiRadius}%` }));
      },
      brush: () => guard(() => sculptor.setParams({
        radius: `${state.brushRadius}%`, strength: state.brushStrength, symmetry: state.symmetry,
      })),
      display: () => applyDisplay(),
      mask: (op) => guard(() => sculptor.mask[op]()),
      undo: () => guard(() => api.undo()),
      redo: () => guard(() => api.redo()),
    });
    // Small views: the panel starts as a title bar; short ones open only the Brush folder.
    if (root.clientWidth < 720) panel.gui.close();
    if (root.clientHeight < 560) panel.compact();
    const inset = () => {
      const px = panel.gui._closed ? 0 : panel.gui.domElement.offsetWidth + 10;
      viewer.setInsetRight(px);
      root.style.setProperty('--adasculpt-inset', `${px + 10}px`);
    };
    panel.gui.onOpenClose(inset);
    inset();
    help = document.createElement('div');
    help.className = 'adasculpt-help';
    root.appendChild(help);
  }
  const palette = new ToolPalette(opts.ui ? root : null, keyTarget, sculptor);
  const gestures = createCameraGestures({ viewer, pick: (x, y) => sculptor.surfacePoint(x, y) });
  views = createViewControls({
    viewer, keyTarget, parent: palette.el, bounds: () => sculptor.buffers.boundingBox(), pivot: () => gestures.pivot,
    onCamera: (camera) => { sculptor.camera = camera; },
  });
  // The model is framed in the canvas right of the tool buttons and below the stats (viewer insets).
  const leftInset = () => {
    const r = root.getBoundingClientRect();
    const right = palette.el ? palette.el.getBoundingClientRect().right - r.left : 0;
    viewer.setInsetLeft(right > 0 ? right + 6 : 0);
    const bottom = stats ? stats.element.getBoundingClientRect().bottom - r.top : 0;
    viewer.setInsetTop(bottom > 0 ? bottom + 4 : 0);
  };
  leftInset();
  function showToolState() {
    if (help) help.textContent = helpText(sculptor.tool);
    const p = sculptor.params;
    const brushTool = sculptor.tool !== 'pull' && sculptor.tool !== 'mask'; // (the mask brush has no symmetry)
    viewer.setMirror(brushTool && p.symmetry && p.symmetry !== 'off' ? p.symmetry : null, sculptor.buffers.boundingBox());
  }
  sculptor.addEventListener('tool', showToolState);
  sculptor.addEventListener('params', showToolState);
  sculptor.addEventListener('end', showToolState);
  showToolState();
  function applyDisplay() {
    viewer.setMatcap(state.matcap);
    viewer.setShading({ mode: state.shading, flat: state.flat });
    viewer.setWireframe(state.wireframe);
  }
  applyDisplay();
  sculptor.connect(viewer.renderer.domElement);

  // ---- the frame loop: at most one wasm call (the grab's or the stroke's) and one render per frame
  let raf = 0;
  let statsShownAt = 0;
  function loop(now) {
    raf = requestAnimationFrame(loop);
    const active = sculptor.grabTool.active || sculptor.brushTool.active;
    sculptor.update();
    if (viewer.needsRender) {
      const r0 = performance.now();
      viewer.render();
      frame.renderMs = performance.now() - r0;
      if (firstRenderMs === null && session.hasMesh()) firstRenderMs = performance.now();
      if (stats && active) stats.tick(now);
    }
    if (frame.dragged) {
      frame.dragged = false;
      const t = frame.core || {};
      if (frameLog.length >= 2000) frameLog.shift();
      frameLog.push({ coreMs: t.total, buffersMs: t.buffers, copyMs: frame.copyMs, renderMs: frame.renderMs,
        totalMs: t.total + t.buffers + frame.copyMs + frame.renderMs, phases: { ...t }, vertices: frame.vertices });
    }
    if (stats && active && now - statsShownAt > 100) {
      statsShownAt = now;
      stats.update({ timings: frame.core, uploadMs: (frame.core?.buffers ?? 0) + frame.copyMs + frame.renderMs,
        vertices: frame.vertices, faces: frame.faces });
    }
  }
  raf = requestAnimationFrame(loop);

  function dispose() {
    if (disposed) return;
    disposed = true;
    cancelAnimationFrame(raf);
    autosave.dispose();
    keyTarget.removeEventListener('keydown', onKey);
    views.dispose();
    gestures.dispose();
    palette.dispose();
    sculptor.dispose();
    fileInput.dispose();
    toaster.dispose();
    if (panel) panel.dispose();
    if (stats) stats.dispose();
    if (help) help.remove();
    viewer.dispose();
    root.remove();
  }

  viewer.precompile(); // shaders compile while the model is parsed
  if (firstModel) {
    try {
      const source = await firstModel;
      if (source instanceof Error) throw source;
      loadBytes(source);
    } catch (e) {
      toaster.show(`Could not load ${opts.model}: ${e.message}`, 'error');
    }
  }
  autosave.offer(); // the prompt appears when IndexedDB answers; the app does not wait for it
  return api;
}

async function readSource(source, format) {
  let buffer;
  let name = 'mesh';
  if (typeof source === 'string' || source instanceof URL) {
    const res = await fetch(source);
    if (!res.ok) throw new Error(`${source}: HTTP ${res.status}`);
    buffer = await res.arrayBuffer();
    name = String(source).split(/[?#]/)[0].split('/').pop() || 'mesh';
  } else if (typeof Blob !== 'undefined' && source instanceof Blob) {
    buffer = await source.arrayBuffer();
    name = source.name || 'mesh';
  } else if (source instanceof ArrayBuffer) {
    buffer = source;
  } else if (ArrayBuffer.isView(source)) {
    buffer = source.buffer.slice(source.byteOffset, source.byteOffset + source.byteLength);
  } else {
    throw new Error('load: expected a URL, a File/Blob or an ArrayBuffer');
  }
  if (format) name = `${name.replace(/\.[^.]*$/, '')}.${String(format).replace(/^\./, '')}`;
  return { bytes: new Uint8Array(buffer), name };
}

