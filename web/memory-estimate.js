// How much wasm memory a mesh file will need, estimated before the core reads it, so that a file
// too large for the page is refused with a message instead of killing the tab.
//
// The wasm module may grow to MAX_WASM_BYTES (CMakeLists.txt: -sMAXIMUM_MEMORY=2GB). Loading and
// then sculpting a mesh of F triangles needed at most BYTES_PER_FACE × F bytes of wasm heap
// (measured with the wasm module in node on 0.18M–3.9M-triangle grids: 230–290 bytes/face after
// the load, 470–610 after the first grab, which adds the undo snapshot, the remesher's and the
// deformer's state and the AABB tree; the heap grows in ~20 % steps, so these are upper bounds;
// re-measured with the picking tree and kept angle figures by `bash scripts/bench-memory-wasm.sh`
// on 0.2M–2M-triangle tori: 275–309 after the load, 507–539 after a grab and a stroke),
// plus the file itself, which is copied into wasm memory to be parsed. The current mesh and its
// history stay in memory until the new mesh has loaded, so they are subtracted from the limit.
export const MAX_WASM_BYTES = 2048 * 1024 * 1024;
export const BYTES_PER_FACE = 550;
const MB = 1024 * 1024;

// Triangles in a mesh file, from its header (PLY, OFF, binary STL) or, for formats without
// counts (OBJ, ASCII STL), from its size. `head` is the start of the file (64 KB is plenty),
// `size` the whole file's size in bytes.
export function estimateFaces(head, size, name = '') {
  const ext = (name.match(/\.([a-z0-9]+)$/i) || [])[1]?.toLowerCase();
  const text = new TextDecoder('latin1').decode(head.subarray(0, Math.min(head.length, 65536)));
  if (/^ply\r?\n/.test(text) || ext === 'ply') {
    const f = /element\s+face\s+(\d+)/.exec(text);
    const v = /element\s+vertex\s+(\d+)/.exec(text);
    if (f) return Number(f[1]);          // polygons: at least one triangle each
    if (v) return 2 * Number(v[1]);
  }
  if (/^\s*[A-Z]*OFF\b/.test(text) || ext === 'off') {
    // "OFF" then, after comments, "nv nf ne" (the counts may follow OFF on the same line).
    const body = text.replace(/#[^\n]*/g, '').replace(/^\s*[A-Z]*OFF/, '');
    const m = /^\s*(\d+)\s+(\d+)/.exec(body);
    if (m) return Number(m[2]);
  }
  if (head.length >= 84 && (ext === 'stl' || !/^\s*solid\b/.test(text))) {
    const n = new DataView(head.buffer, head.byteOffset, head.byteLength).getUint32(80, true);
    if (84 + 50 * n === size) return n;   // binary STL: the count matches the size exactly
  }
  if (/^\s*solid\b/.test(text) || ext === 'stl') return Math.ceil(size / 250); // ascii facet ≈ 250 bytes
  return Math.ceil(size / 40);           // OBJ: a face line plus half a vertex line ≈ 40 bytes
}

// {neededBytes, availableBytes, faces, ok, message}: whether a file of `size` bytes starting with
// `head` fits next to what the page already holds (`residentBytes`, the core's estimate).
export function checkMemory(head, size, name, residentBytes = 0) {
  const faces = estimateFaces(head, size, name);
  const neededBytes = size + faces * BYTES_PER_FACE;
  const availableBytes = Math.max(0, MAX_WASM_BYTES - residentBytes);
  const ok = neededBytes <= availableBytes;
  const message = ok ? '' :
    `${name}: needs about ${Math.ceil(neededBytes / MB)} MB (${faces.toLocaleString('en-US')} triangles), ` +
    `more than the ${Math.floor(availableBytes / MB)} MB this page can use; the current mesh is unchanged`;
  return { neededBytes, availableBytes, faces, ok, message };
}

// The message for a core that ran out of memory anyway (std::bad_alloc).
export function outOfMemoryMessage(name, residentBytes = 0) {
  return `${name}: needs more memory than the ${Math.floor(Math.max(0, MAX_WASM_BYTES - residentBytes) / MB)} MB ` +
    'this page can use (the core ran out of memory); the current mesh is unchanged';
}

export function isOutOfMemory(e) {
  return /bad_alloc|out of memory|Cannot enlarge memory/i.test(String(e && e.message));
}
