// IndexedDB refuses a single value over about 127 MiB (Chromium: "The serialized keys and/or value
// are too large"), and the saved state of a 2M-triangle mesh is larger. A record's `state`
// ArrayBuffer is therefore stored in pieces of at most CHUNK_BYTES under the keys `${key}\u0000${i}`,
// written in the same transaction as the record (so a reader never sees half a state), and joined
// again when read.
export const CHUNK_BYTES = 64 * 1024 * 1024;

const chunkKey = (key, i) => `${key}\u0000${i}`;
// Every chunk key of `key` (and nothing else: '\u0000' sorts before any character a key may hold).
const chunkRange = (key) => IDBKeyRange.bound(`${key}\u0000`, `${key}\u0001`, false, true);

// Puts `record` under `key` in the object store, its `state` in chunks; returns the record's request.
export function putChunked(store, key, record) {
  const { state, ...rest } = record;
  const n = Math.ceil(state.byteLength / CHUNK_BYTES);
  store.delete(chunkRange(key));
  const req = store.put({ ...rest, chunks: n }, key);  // first: a refusal (quota) stops the rest
  for (let i = 0; i < n; i++) store.put(state.slice(i * CHUNK_BYTES, (i + 1) * CHUNK_BYTES), chunkKey(key, i));
  return req;
}

// Deletes the record and its chunks; returns the last request.
export function deleteChunked(store, key) {
  store.delete(chunkRange(key));
  return store.delete(key);
}

// Reads the record under `key` with its state joined (null when there is none). Records written
// before chunking hold `state` directly and are returned as they are.
export function getChunked(store, key) {
  return new Promise((resolve, reject) => {
    const req = store.get(key);
    req.onerror = () => reject(req.error);
    req.onsuccess = () => {
      const r = req.result;
      if (!r || !('chunks' in r)) { resolve(r || null); return; }
      const parts = store.getAll(chunkRange(key));
      parts.onerror = () => reject(parts.error);
      parts.onsuccess = () => {
        // getAll returns the chunks in key order; keys compare as strings, so order by index.
        const keys = store.getAllKeys(chunkRange(key));
        keys.onerror = () => reject(keys.error);
        keys.onsuccess = () => {
          const byIndex = keys.result.map((k, j) => [Number(k.slice(key.length + 1)), parts.result[j]])
            .sort((a, b) => a[0] - b[0]);
          if (byIndex.length !== r.chunks) { reject(new Error('the autosave is incomplete')); return; }
          const total = byIndex.reduce((s, [, b]) => s + b.byteLength, 0);
          const state = new Uint8Array(total);
          let o = 0;
          for (const [, b] of byIndex) { state.set(new Uint8Array(b), o); o += b.byteLength; }
          const { chunks, ...rest } = r;
          resolve({ ...rest, state: state.buffer });
        };
      };
    };
  });
}
