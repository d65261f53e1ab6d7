// createSculptApp(container, options): the whole sculpting app inside one element, as an ES module
// entry for host pages. Returns the page API (also window.app on the main page):
//   load(source, format?)  URL | File/Blob | ArrayBuffer | typed array  -> Promise<{vertices, faces}>
//   setParams({epsilon, minLength, maxLength, features})  numbers are absolute, "0.1%" strings relative
//   grab.begin({center, handleRadius?, roiRadius?}), grab.drag({translate, rotate: {axis, degrees}, scale}),
//   grab.end()   (drag takes the total transform since begin)
//   brush.stroke({tool, path, radius, strength, symmetry, pressure}), brush.begin/stamp/end;
//   setTool('pull' | 'draw' | ... | 'grab'), tool   (web/brush-tool.js)
//   remesh({iterations})  -> Promise (one iteration per animation frame; each iteration is one undo step)
//   undo(), redo()  -> boolean;  replay(sessionJson) -> Promise<report>;  stats();  export(format) -> Promise<ArrayBuffer>
//   dispose()  frees the wasm instance, GPU resources, DOM and every listener.
// options: model (URL of the first model, null for none), wasmUrl (adasculpt.js), ui (panel and
// overlays, default true), keyboard ('global': shortcuts on window; default: when the app has focus),
// autosave (a key: save to IndexedDB after each change and offer to restore on start-up, see
// web/autosave.js; default false; the standalone page uses 'main').
import { instantiateCore } from './wasm-module.js';
import { createViewer } from './viewer.js';
import { MeshBuffers } from './mesh-buffers.js';
import { GrabTool } from './grab-tool.js';
import { BrushTool, BRUSH_STATE, BRUSH_PARAMS, createBrushApi } from './brush-tool.js';
import { ToolPalette } from './tool-palette.js';
import { createPanel, SAMPLES } from './panel.js';
import { createStatsOverlay } from './stats-overlay.js';
import { createFileInput, createToaster, download } from './file-io.js';
import { STYLE } from './style.js';
import { createAutosave, noAutosave } from './autosave.js';
import { checkMemory, isOutOfMemory, outOfMemoryMessage } from './memory-estimate.js';
import * as THREE from 'three';

const DEFAULT_STATE = {
  epsilon: 0.05, minLength: 0.2, maxLength: 5, features: 0, iterations: 5,
  handleRadius: 4, roiRadius: 15, shading: 'matcap', flat: false, wireframe: false, ...BRUSH_STATE,
};

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
  const session = new Module.Session();
  const viewer = createViewer(root);
  const buffers = new MeshBuffers(Module);
  buffers.onGeometry = (g, lines) => viewer.setGeometry(g, lines);
  const toaster = createToaster(root);
  const state = { ...DEFAULT_STATE, sample: Object.keys(SAMPLES).find((k) => SAMPLES[k] === opts.model) || 'sphere' };
  let diagonal = 1;
  let remeshing = null;   // {done, total} while a whole-mesh remesh runs
  let disposed = false;
  let firstRenderMs = null;
  let quality = {};
  let qualityStale = false;  // a stroke ended since `quality` was read (refreshQualityWhenIdle)
  let qualityTimer = null;
  const frame = { core: null, copyMs: 0, renderMs: 0, vertices: 0, faces: 0, dragged: false };
  const frameLog = []; // per grab frame: core phases, buffer update, copy, render (for benchmarks)
  let sourceName = opts.model ? String(opts.model).split(/[?#]/)[0].split('/').pop() : 'mesh';
  const autosave = opts.autosave ? createAutosave(String(opts.autosave), {
    session, toaster, root: opts.ui ? root : null,
    busy: () => !!remeshing || tool.active || session.grabbing() || (!!session.brushing && session.brushing()),
    sourceName: () => sourceName,
    counts: () => {
      if (qualityStale) refreshQuality();
      return { vertices: quality.vertices ?? 0, faces: quality.faces ?? 0 };
    },
    restored: (record) => {
      sourceName = record.name;
      sync();
      readSettings();
      viewer.fitView(buffers.boundingBox());
      refreshQuality();
    },
  }) : noAutosave();

  // ---- keeping three.js in step with the core
  function sync(changes) {
    const t0 = performance.now();
    const ch = changes || session.changes();
    if (buffers.apply(ch)) viewer.requestRender();
    frame.copyMs = performance.now() - t0;
    frame.vertices = ch.vertices;
    frame.faces = ch.faces;
    frame.core = ch.timings;
  }

  function refreshQuality() {
    qualityStale = false;
    clearTimeout(qualityTimer);
    quality = JSON.parse(session.stats());
    if (stats) {
      stats.update({
        vertices: quality.vertices ?? 0, faces: quality.faces ?? 0,
        minAngle: quality.min_angle_deg, meanMinAngle: quality.mean_min_angle_deg,
      });
    }
    if (panel) panel.setHistory(session.canUndo(), session.canRedo());
  }

  // Settings in the panel are percent of the diagonal; the core answers in absolute lengths.
  function readSettings() {
    const s = JSON.parse(session.settings());
    diagonal = s.diagonal || 1;
    const pct = (x) => Math.round((x / diagonal) * 100 * 1e4) / 1e4;
    state.epsilon = pct(s.epsilon);
    state.minLength = pct(s.min_length);
    state.maxLength = pct(s.max_length);
    state.features = s.features;
    if (panel) panel.refresh();
    return s;
  }

  function radii() {
    return { handle: (state.handleRadius / 100) * diagonal, roi: (state.roiRadius / 100) * diagonal };
  }

  function loadBytes({ bytes, name }) {
    if (disposed) throw new Error('app disposed');
    try {
      session.loadBytes(bytes, name); // throws with the reader's message; the old mesh stays
    } catch (e) {
      throw isOutOfMemory(e) ? new Error(outOfMemoryMessage(name, session.memoryBytes())) : e;
    }
    sourceName = name;
    sync();
    readSettings();
    viewer.fitView(buffers.boundingBox());
    refreshQuality();
    return { vertices: quality.vertices, faces: quality.faces };
  }

  // After a brush stroke the whole-mesh quality report (22 ms of WebAssembly on the 35k-vertex
  // bunny, more than the stroke's stamps together) waits until no stroke or grab runs for a
  // moment, so that it does not stall the next stroke's first frames; stats() refreshes at once.
  function refreshQualityWhenIdle() {
    qualityStale = true;
    if (panel) panel.setHistory(session.canUndo(), session.canRedo());
    clearTimeout(qualityTimer);
    qualityTimer = setTimeout(function settle() {
      if (disposed || !qualityStale) return;
      if (session.grabbing() || (session.brushing && session.brushing())) {
        qualityTimer = setTimeout(settle, 250);
        return;
      }
      refreshQuality();
    }, 250);
  }

  function afterWholeMeshChange() {
    sync();
    refreshQuality();
    autosave.changed();
  }

  // Refuses a file the page has no memory for before the core reads it (web/memory-estimate.js).
  function checkFits(head, size, name) {
    const c = checkMemory(head, size, name, session.memoryBytes());
    if (!c.ok) throw new Error(c.message);
  }

  // ---- the page API
  const api = {
    get module() { return Module; },
    get session() { return session; },

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

    setParams(p = {}) {
      const keys = { epsilon: 'epsilon', minLength: 'min_length', maxLength: 'max_length', features: 'features' };
      const s = {};
      const radius = {}; // handleRadius, roiRadius, brushRadius: the tools' defaults, kept in percent like the panel
      const brush = {}; // brushStrength, symmetry
      for (const [k, v] of Object.entries(p)) {
        if (['handleRadius', 'roiRadius', 'brushRadius'].includes(k)) radius[k] = percentOfDiagonal(v, k, diagonal);
        else if (k in BRUSH_PARAMS) brush[k] = BRUSH_PARAMS[k](v);
        else if (!(k in keys)) throw new Error(`setParams: unknown parameter '${k}'`);
        else s[keys[k]] = v;
      }
      session.setSettings(JSON.stringify(s));
      autosave.changed();
      Object.assign(state, radius, brush);
      if (radius.handleRadius !== undefined || radius.roiRadius !== undefined) tool.updateBrush();
      brushTool.updateCursor();
      return readSettings();
    },

    grab: {
      begin({ center, handleRadius, roiRadius } = {}) {
        const r = radii();
        const c = toVec3(center, 'center');
        session.grabBegin(c.x, c.y, c.z, handleRadius ?? r.handle, roiRadius ?? r.roi);
        sync();
      },
      drag({ translate = [0, 0, 0], rotate = { axis: [0, 0, 1], degrees: 0 }, scale = 1 } = {}) {
        const t = toVec3(translate, 'translate');
        const a = toVec3(rotate.axis || [0, 0, 1], 'rotate.axis');
        sync(session.grabDrag(t.x, t.y, t.z, a.x, a.y, a.z, rotate.degrees || 0, scale));
        frame.dragged = true;
        return { vertices: frame.vertices, faces: frame.faces, timings: frame.core };
      },
      end() {
        session.grabEnd();
        afterWholeMeshChange();
      },
    },

    // Brush strokes (web/brush-tool.js): brush.stroke({tool, path, radius, strength, symmetry, pressure}),
    // or brush.begin/stamp/end; radius absolute, defaults from the panel.
    brush: createBrushApi({
      session,
      applyChanges: (ch) => { sync(ch); frame.dragged = true; },
      afterStroke: () => {
        sync();
        refreshQualityWhenIdle();
        autosave.changed();
      },
      defaults: () => ({ tool: state.tool === 'pull' ? 'draw' : state.tool, radius: (state.brushRadius / 100) * diagonal,
        strength: state.brushStrength, symmetry: state.symmetry, detailPixels: state.detailPixels }),
    }),
    get tool() { return palette.tool; },
    setTool(name) { return palette.setTool(name); },

    async remesh({ iterations = state.iterations } = {}) {
      if (remeshing) throw new Error('a remesh is already running');
      remeshing = { done: 0, total: iterations };
      try {
        for (let i = 0; i < iterations && !disposed; i++) {
          if (panel) panel.setProgress(remeshing);
          await nextFrame();
          if (disposed) break;
          session.remesh(1);
          sync();
          remeshing.done = i + 1;
        }
      } finally {
        remeshing = null;
        if (!disposed) {
          if (panel) panel.setProgress(null);
          refreshQuality();
          autosave.changed();
        }
      }
      return api.stats();
    },

    undo() {
      if ((tool && tool.active) || (brushTool && brushTool.active)) return false;
      const ok = session.undo();
      afterWholeMeshChange();
      return ok;
    },
    redo() {
      if ((tool && tool.active) || (brushTool && brushTool.active)) return false;
      const ok = session.redo();
      afterWholeMeshChange();
      return ok;
    },

    async replay(sessionJson) {
      const text = typeof sessionJson === 'string' ? sessionJson : JSON.stringify(sessionJson);
      const report = JSON.parse(session.replay(text));
      afterWholeMeshChange();
      return report;
    },

    stats() {
      if (qualityStale) refreshQuality();
      const t = frame.core || {};
      return {
        vertices: quality.vertices ?? 0,
        faces: quality.faces ?? 0,
        minAngle: quality.min_angle_deg ?? null,
        meanMinAngle: quality.mean_min_angle_deg ?? null,
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
        settings: JSON.parse(session.settings()),
        quality,
      };
    },

    async export(format = 'obj') {
      const bytes = session.exportMesh(format);
      return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    },

    // The grab frames since the last call (core, buffers, copy, render ms each), for benchmarks.
    takeFrameLog() {
      return frameLog.splice(0, frameLog.length);
    },

    // Axis-aligned bounds of the drawn mesh: {min: [x,y,z], max: [x,y,z]}.
    bounds() {
      const b = buffers.boundingBox();
      return { min: b.min.toArray(), max: b.max.toArray() };
    },

    dispose,
  };

  // ---- interaction: the grab tool talks to the core through this adapter
  const keyTarget = opts.keyboard === 'global' ? window : root;
  const core = {
    pick(ray) {
      if (!session.hasMesh()) return null;
      const o = ray.origin, d = ray.direction;
      const h = session.pick(o.x, o.y, o.z, d.x, d.y, d.z);
      return h && h.hit ? new THREE.Vector3(h.x, h.y, h.z) : null;
    },
    begin(center) { guard(() => api.grab.begin({ center: center.toArray() })); },
    drag(t) { return guard(() => api.grab.drag(t)); },
    notify: (message) => toaster.show(message),
    end() { guard(() => api.grab.end()); },
    radii,
    scaleRadii(fh, fr) {
      state.roiRadius = clamp(state.roiRadius * fr, 1, 80);
      state.handleRadius = clamp(state.handleRadius * fh, 0.5, Math.min(30, state.roiRadius * 0.9));
      if (panel) panel.refresh();
    },
    busy: () => !!remeshing || !session.hasMesh(),
  };
  const tool = new GrabTool(viewer, core, keyTarget);
  const brushTool = new BrushTool(viewer, {
    begin: (s) => guard(() => { api.brush.begin(s); return true; }) === true,
    stamp: (samples) => guard(() => api.brush.stamp(samples)),
    end: () => guard(() => api.brush.end()),
    busy: () => !!remeshing, // no wasm call: without a mesh there is no geometry to hit
    radius: () => (state.brushRadius / 100) * diagonal,
    geometry: () => buffers.geometry,
    changed: () => { if (panel) panel.refresh(); },
  }, keyTarget, state);

  function guard(fn) {
    try {
      return fn();
    } catch (e) {
      toaster.show(e.message, 'error');
      return undefined;
    }
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

  // ---- UI: file input / drop, panel, stats
  const openFile = async (file) => {
    try {
      await api.load(file);
      toaster.show(`Opened ${file.name}`);
    } catch (e) {
      // Reader messages already start with the file name.
      toaster.show(e.message.startsWith(file.name) ? `Could not open ${e.message}` : `Could not open ${file.name}: ${e.message}`, 'error');
    }
  };
  const fileInput = createFileInput(root, openFile);
  let panel = null;
  let stats = null;
  let help = null;
  if (opts.ui) {
    stats = createStatsOverlay(root);
    panel = createPanel(root, state, {
      loadSample: (name) => {
        state.sample = name;
        api.load(SAMPLES[name]).catch((e) => toaster.show(`Could not load ${name}: ${e.message}`, 'error'));
      },
      open: () => fileInput.open(),
      exportMesh: (fmt) => guard(() => download(session.exportMesh(fmt), `adasculpt-${state.sample}.${fmt}`)),
      settings: () => guard(() => api.setParams({
        epsilon: `${state.epsilon}%`, minLength: `${state.minLength}%`, maxLength: `${state.maxLength}%`, features: state.features,
      })),
      remesh: () => api.remesh({ iterations: state.iterations }).catch((e) => toaster.show(e.message, 'error')),
      radii: () => { if (state.handleRadius > state.roiRadius) state.handleRadius = state.roiRadius * 0.9; tool.updateBrush(); },
      brush: () => brushTool.updateCursor(),
      display: () => applyDisplay(),
      undo: () => guard(() => api.undo()),
      redo: () => guard(() => api.redo()),
    });
    if (root.clientWidth < 720) panel.gui.close(); // small embeds: the panel starts as a title bar
    const inset = () => {
      const px = panel.gui._closed ? 0 : panel.gui.domElement.offsetWidth + 10;
      viewer.setInsetRight(px);
      root.style.setProperty('--adasculpt-inset', `${px + 10}px`);
    };
    panel.gui.onOpenClose(inset);
    inset();
    help = document.createElement('div');
    help.className = 'adasculpt-help';
    help.textContent = '1 pull: drag on the model, R rotate · S scale · wheel: scale · [ ] ROI · { } handle · ' +
      '2–8 brushes: stroke on the model, Ctrl/Alt invert · [ ] radius · - = strength · ' +
      'drag elsewhere: orbit · Ctrl+Z / Ctrl+Shift+Z';
    root.appendChild(help);
  }
  const palette = new ToolPalette(opts.ui ? root : null, keyTarget, {
    grabTool: tool, brushTool, state, onChange: () => { if (panel) panel.refresh(); },
  });
  function applyDisplay() {
    viewer.setShading({ mode: state.shading, flat: state.flat });
    viewer.setWireframe(state.wireframe);
  }
  applyDisplay();

  // ---- the frame loop: at most one wasm call (the grab's or the stroke's) and one render per frame
  let raf = 0;
  let statsShownAt = 0;
  function loop(now) {
    raf = requestAnimationFrame(loop);
    const grabbing = tool.active || brushTool.active;
    tool.frame();
    brushTool.frame();
    if (viewer.needsRender) {
      const r0 = performance.now();
      viewer.render();
      frame.renderMs = performance.now() - r0;
      if (firstRenderMs === null && session.hasMesh()) firstRenderMs = performance.now();
      if (stats && grabbing) stats.tick(now);
    }
    if (frame.dragged) {
      frame.dragged = false;
      const t = frame.core || {};
      if (frameLog.length >= 2000) frameLog.shift();
      frameLog.push({ coreMs: t.total, buffersMs: t.buffers, copyMs: frame.copyMs, renderMs: frame.renderMs,
        totalMs: t.total + t.buffers + frame.copyMs + frame.renderMs, phases: { ...t }, vertices: frame.vertices });
    }
    if (stats && grabbing && now - statsShownAt > 100) {
      statsShownAt = now;
      stats.update({ timings: frame.core, uploadMs: (frame.core?.buffers ?? 0) + frame.copyMs + frame.renderMs,
        vertices: frame.vertices, faces: frame.faces });
    }
  }
  raf = requestAnimationFrame(loop);

  function dispose() {
    if (disposed) return;
    disposed = true;
    clearTimeout(qualityTimer);
    cancelAnimationFrame(raf);
    autosave.dispose();
    keyTarget.removeEventListener('keydown', onKey);
    tool.dispose();
    brushTool.dispose();
    palette.dispose();
    fileInput.dispose();
    toaster.dispose();
    if (panel) panel.dispose();
    if (stats) stats.dispose();
    if (help) help.remove();
    buffers.dispose();
    viewer.dispose();
    session.delete();
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

function toVec3(v, what) {
  if (v && v.isVector3) return v;
  if (Array.isArray(v) && v.length === 3 && v.every(Number.isFinite)) return new THREE.Vector3(v[0], v[1], v[2]);
  if (v && [v.x, v.y, v.z].every(Number.isFinite)) return new THREE.Vector3(v.x, v.y, v.z);
  throw new Error(`${what}: expected [x, y, z]`);
}

// A length given as a number (absolute) or "x%" (of the diagonal), in percent of the diagonal.
function percentOfDiagonal(v, what, diagonal) {
  const pct = typeof v === 'string' && v.trim().endsWith('%');
  const x = pct ? Number(v.trim().slice(0, -1)) : Number(v);
  if (!Number.isFinite(x) || x <= 0) throw new Error(`setParams: ${what} must be a positive number or "x%"`);
  return pct ? x : (x / diagonal) * 100;
}

function clamp(x, lo, hi) { return Math.min(hi, Math.max(lo, x)); }
function nextFrame() { return new Promise((resolve) => requestAnimationFrame(() => resolve())); }
