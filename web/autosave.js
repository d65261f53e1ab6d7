// Autosave: after each completed change (grab, stroke, whole remesh, undo, redo, load, settings)
// and one second without another, the app writes its whole state to IndexedDB: the mesh (double
// positions), the settings and the newest undo/redo steps within HISTORY_BYTES, as one lossless
// blob from the core (Session.saveState, sculpt::Session::save_state). Never during a drag or a
// remesh: the timer waits until the app is idle. On the next visit the app offers to restore it.
//
// One record per key (the app's `autosave` option; the standalone page uses 'main'), in the
// database 'adasculpt', store 'autosave', its state in pieces beside it (web/idb-chunks.js). Two tabs
// with the same key share one record: the last write wins.
import { deleteChunked, getChunked, putChunked } from './idb-chunks.js';

export const DEBOUNCE_MS = 1000;
export const HISTORY_BYTES = 96 * 1024 * 1024;
const DB_NAME = 'adasculpt';
const STORE = 'autosave';
const MB = 1024 * 1024;

function openDb() {
  return new Promise((resolve, reject) => {
    if (typeof indexedDB === 'undefined') { reject(new Error('IndexedDB is not available')); return; }
    const req = indexedDB.open(DB_NAME, 1);
    req.onupgradeneeded = () => req.result.createObjectStore(STORE);
    req.onsuccess = () => resolve(req.result);
    req.onerror = () => reject(req.error);
    req.onblocked = () => reject(new Error('IndexedDB is blocked by another tab'));
  });
}

function run(db, mode, fn) {
  return new Promise((resolve, reject) => {
    const tx = db.transaction(STORE, mode);
    const req = fn(tx.objectStore(STORE));
    let result;
    req.onsuccess = () => { result = req.result; };
    tx.oncomplete = () => resolve(result);
    tx.onerror = () => reject(tx.error || req.error);
    tx.onabort = () => reject(tx.error || new Error('IndexedDB transaction aborted'));
  });
}

function isQuotaError(e) {
  return !!e && (e.name === 'QuotaExceededError' || /quota/i.test(String(e.message)));
}

// host: {session, busy(), sourceName(), counts() -> {vertices, faces}, restored(record), toaster,
//        root (for the prompt; null = no prompt)}
export function createAutosave(key, host) {
  let dbPromise = null;
  let timer = 0;
  let dirty = false;
  let writing = null;     // the write in flight
  let offer = null;       // the record offered for restore, while the prompt is up
  let prompt = null;
  let disposed = false;
  let lastError = null;
  const db = () => (dbPromise ||= openDb());

  function schedule(ms = DEBOUNCE_MS) {
    clearTimeout(timer);
    timer = setTimeout(tick, ms);
  }
  function tick() {
    timer = 0;
    if (disposed || !dirty) return;
    if (host.busy()) { schedule(); return; }  // never during a drag or a remesh
    write().catch(() => {});
  }

  // The record: the core's blob plus what the prompt shows. Quota errors retry with less
  // history, then with none; the last resort is a message (the page keeps working).
  async function write() {
    if (writing) await writing.catch(() => {});
    if (disposed || !dirty || offer || !host.session.hasMesh()) return false;
    if (host.busy()) { schedule(); return false; }
    dirty = false;
    const counts = host.counts(); // the app's cached figures (stats() would measure the whole mesh)
    const settings = host.session.settings();
    const attempt = async (budget) => {
      const state = host.session.saveState(budget);
      const record = {
        version: 1, key, name: host.sourceName(), savedAt: Date.now(),
        vertices: counts.vertices, faces: counts.faces, settings, bytes: state.byteLength, state: state.buffer,
      };
      await run(await db(), 'readwrite', (s) => putChunked(s, key, record));
      return record;
    };
    writing = (async () => {
      for (const budget of [HISTORY_BYTES, HISTORY_BYTES / 8, 0]) {
        if (budget !== HISTORY_BYTES && host.busy()) { dirty = true; schedule(); return false; } // a drag began
        try {
          await attempt(budget);
          lastError = null;
          return true;
        } catch (e) {
          lastError = e;
          if (!isQuotaError(e)) break;
        }
      }
      const e = lastError;
      dirty = true; // a later flush (or the next change) tries again
      host.toaster.show(isQuotaError(e)
        ? 'Autosave failed: the browser\'s storage is full. Export the mesh to keep it.'
        : `Autosave failed: ${e.message}`, 'error');
      return false;
    })();
    try {
      return await writing;
    } finally {
      writing = null;
    }
  }

  async function read() {
    const d = await db();
    return getChunked(d.transaction(STORE, 'readonly').objectStore(STORE), key);
  }

  function describe(r) {
    const t = new Date(r.savedAt);
    const when = t.toDateString() === new Date().toDateString() ? t.toLocaleTimeString() : t.toLocaleString();
    return `${r.name} · ${Number(r.vertices).toLocaleString('en-US')} vertices · saved ${when}`;
  }

  function hidePrompt() {
    if (prompt) prompt.remove();
    prompt = null;
    offer = null;
  }

  function showPrompt(r) {
    if (!host.root) return;
    prompt = document.createElement('div');
    prompt.className = 'adasculpt-restore';
    // Top centre, above the canvas; styled here so that style.js stays the app's shared sheet.
    // Centred in the area left of the panel, below the stats corner.
    prompt.style.cssText = 'position:absolute;left:calc((100% - var(--adasculpt-inset, 10px) + 10px) / 2);top:76px;' +
      'transform:translateX(-50%);display:flex;gap:8px;align-items:center;' +
      'width:max-content;max-width:calc(100% - var(--adasculpt-inset, 10px) - 30px);padding:8px 12px;border-radius:6px;z-index:5;' +
      'background:rgba(30,33,40,0.96);box-shadow:0 2px 12px rgba(0,0,0,0.45);user-select:text';
    prompt.setAttribute('role', 'dialog');
    prompt.setAttribute('aria-label', 'Restore the autosaved session');
    const text = document.createElement('span');
    text.textContent = `Unsaved session: ${describe(r)} (${(r.bytes / MB).toFixed(1)} MB)`;
    const restoreButton = document.createElement('button');
    restoreButton.textContent = 'Restore';
    restoreButton.onclick = () => api.restore().catch((e) => host.toaster.show(`Could not restore: ${e.message}`, 'error'));
    const discardButton = document.createElement('button');
    discardButton.textContent = 'Discard';
    discardButton.onclick = () => api.clear().catch((e) => host.toaster.show(e.message, 'error'));
    for (const b of [restoreButton, discardButton]) {
      b.style.cssText = 'font:inherit;padding:3px 10px;border-radius:4px;border:1px solid rgba(255,255,255,0.2);' +
        'background:#2d3240;color:#fff;cursor:pointer';
    }
    restoreButton.style.background = '#2f6fd0';
    prompt.append(text, restoreButton, discardButton);
    host.root.appendChild(prompt);
  }

  const onHide = () => { if (document.visibilityState === 'hidden' && dirty) write().catch(() => {}); };
  document.addEventListener('visibilitychange', onHide);

  const api = {
    enabled: true,
    key,
    // Something changed: write after DEBOUNCE_MS of quiet.
    changed() {
      if (disposed) return;
      dirty = true;
      schedule();
    },
    // Writes now (when something changed since the last write); resolves to true when written.
    async flush() {
      clearTimeout(timer);
      return write();
    },
    // What is saved: {name, vertices, faces, savedAt, bytes, key} or null.
    async saved() {
      const r = await read();
      return r && { key: r.key, name: r.name, vertices: r.vertices, faces: r.faces, savedAt: r.savedAt, bytes: r.bytes };
    },
    // Loads the saved mesh, settings and history (Ctrl+Z continues where it was). Null if none.
    async restore() {
      const r = await read();
      hidePrompt();
      if (!r) return null;
      host.session.restoreState(new Uint8Array(r.state)); // throws on a damaged record; the mesh stays
      host.restored(r);
      dirty = false;
      return { name: r.name, vertices: r.vertices, faces: r.faces, savedAt: r.savedAt };
    },
    // Deletes the saved record (and the prompt); the next change writes a new one.
    async clear() {
      hidePrompt();
      clearTimeout(timer);
      await run(await db(), 'readwrite', (s) => deleteChunked(s, key));
      if (dirty) schedule(); // changes made while the offer was up
    },
    // Offers the saved session, if any (called once at start-up). Until it is answered nothing
    // is written, so working on the start-up model cannot overwrite the saved session.
    async offer() {
      let r = null;
      try {
        r = await read();
      } catch (e) {
        host.toaster.show(`Autosave is off: ${e.message}`, 'error');
        return null;
      }
      if (!r || disposed) return null;
      offer = r;
      showPrompt(r);
      return { name: r.name, vertices: r.vertices, faces: r.faces, savedAt: r.savedAt };
    },
    get pending() { return !!offer; },
    get lastError() { return lastError ? lastError.message : null; },
    dispose() {
      disposed = true;
      clearTimeout(timer);
      document.removeEventListener('visibilitychange', onHide);
      hidePrompt();
      if (dbPromise) dbPromise.then((d) => d.close(), () => {});
    },
  };
  return api;
}

// The same shape when the app does not autosave (option `autosave: false`).
export function noAutosave() {
  return {
    enabled: false, key: null, pending: false, lastError: null,
    changed() {}, dispose() {},
    async flush() { return false; },
    async saved() { return null; },
    async restore() { return null; },
    async clear() {},
    async offer() { return null; },
  };
}
