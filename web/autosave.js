// Autosave: after each completed change (grab, stroke, whole remesh, undo, redo, load, settings)
// and one second without another, the app writes to IndexedDB. The first write is the whole state:
// the mesh (double positions), the settings and the newest undo/redo steps within HISTORY_BYTES, as
// one lossless blob from the core (Session.saveState). Later writes are only what changed since
// (Session.saveChanges: the new undo steps, each the size of its brushed region, undo/redo marks
// and the settings), one small record each, so that autosaving a stroke does not cost the mesh. A
// fresh whole state replaces them when the core says a record cannot express the change (a load, a
// whole remesh, an undo past the saved history), after MAX_RECORDS records, or when the records add
// up to half the whole state. Never during a drag or a remesh: the timer waits until the app is
// idle. On the next visit the app offers to restore it (the whole state, then the records in order).
//
// Per key (the app's `autosave` option; the standalone page uses 'main'), in the database
// 'adasculpt', store 'autosave': the whole state under the key (its bytes in pieces beside it,
// web/idb-chunks.js), the records under [key, 1],
// [key, 2], ... Each record names the whole state it follows (`chain`), so records of another tab
// (two tabs with the same key: the last whole state wins) or of an older state are never applied.
import { deleteChunked, getChunked, putChunked } from './idb-chunks.js';

export const DEBOUNCE_MS = 1000;
export const HISTORY_BYTES = 96 * 1024 * 1024;
// Restoring replays and checks every recorded step: past this many records a whole state is due.
export const MAX_RECORDS = 50;
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

// The records of `key` (array keys sort after every string key, and by their number).
const recordRange = (key) => IDBKeyRange.bound([key, 0], [key, Infinity]);

// The whole state and the records that continue it: same chain, numbered 1, 2, ... without a gap.
function readSaved(db, key) {
  const store = db.transaction(STORE, 'readonly').objectStore(STORE);
  // Asked first: requests complete in order, so the records are there when the state is.
  const all = store.getAll(recordRange(key));
  return getChunked(store, key).then((b) => {
    if (!b) return null;
    const records = [];
    for (const r of all.result || []) {
      if (!b.chain || r.chain !== b.chain || r.seq !== records.length + 1) break;
      records.push(r);
    }
    return { base: b, records };
  });
}

// What the prompt and saved() show: the newest record's figures, the size of all of it.
function summary(saved) {
  const { base, records } = saved;
  const last = records.length ? records[records.length - 1] : base;
  return {
    key: base.key, name: last.name, vertices: last.vertices, faces: last.faces, savedAt: last.savedAt,
    bytes: records.reduce((n, r) => n + r.bytes, base.bytes), changes: records.length, lastBytes: last.bytes,
  };
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
  // The chain written last: its id (null: the next write is a whole state), records so far, sizes.
  let chain = null, seq = 0, baseBytes = 0, recordBytes = 0;
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

  // A record: the core's bytes plus what the prompt shows. A change record when the core can give
  // one and the chain is not due for a whole state; otherwise the whole state (dropping the old
  // records in the same transaction). Quota errors retry with a whole state with less history,
  // then with none; the last resort is a message (the page keeps working).
  async function write() {
    if (writing) await writing.catch(() => {});
    if (disposed || !dirty || offer || !host.session.hasMesh()) return false;
    if (host.busy()) { schedule(); return false; }
    dirty = false;
    const counts = host.counts(); // the app's cached figures (stats() would measure the whole mesh)
    const settings = host.session.settings();
    const meta = () => ({ version: 1, key, name: host.sourceName(), savedAt: Date.now(),
      vertices: counts.vertices, faces: counts.faces, settings });
    const attempt = async (budget) => {
      chain = null;  // until this whole state is stored, no record may follow it
      const state = host.session.saveState(budget);
      const id = `${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;
      const record = { ...meta(), chain: id, bytes: state.byteLength, state: state.buffer };
      await run(await db(), 'readwrite', (s) => { s.delete(recordRange(key)); return putChunked(s, key, record); });
      chain = id;
      seq = 0;
      baseBytes = state.byteLength;
      recordBytes = 0;
      return record;
    };
    // False when a whole state is due (the core then has nothing to give as a record).
    const attemptChanges = async () => {
      if (!chain || seq >= MAX_RECORDS || recordBytes > baseBytes / 2) return false;
      const bytes = host.session.saveChanges();
      if (!bytes) return false;
      const id = chain;
      chain = null;  // a record that is not stored breaks the chain: the next write is a whole state
      const record = { ...meta(), chain: id, seq: seq + 1, bytes: bytes.byteLength, state: bytes.buffer };
      await run(await db(), 'readwrite', (s) => s.put(record, [key, seq + 1]));
      chain = id;
      seq += 1;
      recordBytes += bytes.byteLength;
      return true;
    };
    writing = (async () => {
      try {
        if (await attemptChanges()) {
          lastError = null;
          return true;
        }
      } catch (e) {
        lastError = e;  // a whole state follows
      }
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

  const read = async () => readSaved(await db(), key);

  function describe(r) {  // r: a summary()
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
    // changes: records after the whole state; lastBytes: the newest one's size (or the whole state's).
    async saved() {
      const r = await read();
      return r && summary(r);
    },
    // Loads the saved mesh, settings and history (Ctrl+Z continues where it was). Null if none.
    async restore() {
      const saved = await read();
      hidePrompt();
      if (!saved) return null;
      // Throws on a damaged state or record; the mesh stays.
      host.session.restoreSaved(new Uint8Array(saved.base.state), saved.records.map((x) => new Uint8Array(x.state)));
      const r = summary(saved);
      host.restored(r);
      // The session is what was saved: later changes continue the same chain (the core's too).
      chain = saved.base.chain || null;
      seq = saved.records.length;
      baseBytes = saved.base.bytes;
      recordBytes = r.bytes - baseBytes;
      if (saved.records.length < (await run(await db(), 'readonly', (s) => s.count(recordRange(key))))) chain = null;
      dirty = false;
      return { name: r.name, vertices: r.vertices, faces: r.faces, savedAt: r.savedAt };
    },
    // Deletes the saved record (and the prompt); the next change writes a new one.
    async clear() {
      hidePrompt();
      clearTimeout(timer);
      chain = null;
      await run(await db(), 'readwrite', (s) => { s.delete(recordRange(key)); return deleteChunked(s, key); });
      if (dirty) schedule(); // changes made while the offer was up
    },
    // Offers the saved session, if any (called once at start-up). Until it is answered nothing
    // is written, so working on the start-up model cannot overwrite the saved session.
    async offer() {
      let r = null;
      try {
        const saved = await read();
        r = saved && summary(saved);
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
