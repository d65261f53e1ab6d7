// Files in and out: a hidden file input, drag-and-drop onto the viewer, downloads, and the toast
// that reports what went wrong.
export const MESH_EXTENSIONS = ['obj', 'stl', 'ply', 'off'];

// onFile(File) is called for a chosen or dropped file. Returns {open(), dispose()}.
export function createFileInput(root, onFile) {
  const input = document.createElement('input');
  input.type = 'file';
  input.accept = MESH_EXTENSIONS.map((e) => '.' + e).join(',');
  input.className = 'adasculpt-file';
  root.appendChild(input);
  const hint = document.createElement('div');
  hint.className = 'adasculpt-drop';
  hint.textContent = 'Drop an OBJ, STL, PLY or OFF file';
  root.appendChild(hint);

  let depth = 0;
  const listeners = [
    [input, 'change', () => {
      const f = input.files && input.files[0];
      input.value = '';
      if (f) onFile(f);
    }],
    [root, 'dragenter', (e) => { if (hasFiles(e)) { e.preventDefault(); depth++; hint.classList.add('show'); } }],
    [root, 'dragover', (e) => { if (hasFiles(e)) { e.preventDefault(); e.dataTransfer.dropEffect = 'copy'; } }],
    [root, 'dragleave', () => { if (--depth <= 0) { depth = 0; hint.classList.remove('show'); } }],
    [root, 'drop', (e) => {
      if (!hasFiles(e)) return;
      e.preventDefault();
      depth = 0;
      hint.classList.remove('show');
      const f = e.dataTransfer.files[0];
      if (f) onFile(f);
    }],
  ];
  for (const [t, type, fn] of listeners) t.addEventListener(type, fn);
  return {
    input,
    open() { input.click(); },
    dispose() {
      for (const [t, type, fn] of listeners) t.removeEventListener(type, fn);
      input.remove();
      hint.remove();
    },
  };
}

function hasFiles(e) {
  return e.dataTransfer && Array.from(e.dataTransfer.types || []).includes('Files');
}

export function download(bytes, filename) {
  const url = URL.createObjectURL(new Blob([bytes], { type: 'application/octet-stream' }));
  const a = document.createElement('a');
  a.href = url;
  a.download = filename;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

// Short messages at the bottom of the viewer; errors stay a little longer.
export function createToaster(root) {
  const box = document.createElement('div');
  box.className = 'adasculpt-toasts';
  box.setAttribute('role', 'status');
  root.appendChild(box);
  const timers = new Set();
  return {
    show(message, kind = 'info') {
      const t = document.createElement('div');
      t.className = `adasculpt-toast ${kind}`;
      if (kind === 'error') t.setAttribute('role', 'alert');
      t.textContent = message;
      box.appendChild(t);
      while (box.children.length > 3) box.firstChild.remove(); // the newest three
      const timer = setTimeout(() => { t.remove(); timers.delete(timer); }, kind === 'error' ? 8000 : 3000);
      timers.add(timer);
    },
    dispose() {
      for (const t of timers) clearTimeout(t);
      box.remove();
    },
  };
}
