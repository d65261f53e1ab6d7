// node:test of the wasm Session's autosave calls (saveState, saveChanges, restoreState, restoreSaved,
// memoryBytes) that web/autosave.js uses: a restored session exports the same bytes, keeps its settings and its
// undo/redo history, a damaged state is refused with the mesh kept, and the history budget holds.
const test = require('node:test');
const assert = require('node:assert');

const { skip, sphereObj, loadModule } = require('./wasm-module.cjs');

let M;
test.before(async () => {
  M = await loadModule();
});

const ply = (s) => Buffer.from(s.exportMesh('ply'));
function pull(s, c, t) {
  s.grabBegin(c[0], c[1], c[2], 0.1, 0.6);
  for (let i = 1; i <= 4; i++) s.grabDrag((t[0] * i) / 4, (t[1] * i) / 4, (t[2] * i) / 4, 0, 0, 1, 0, 1);
  s.grabEnd();
}

test('saveState / restoreState: same mesh, settings and history in a new Session', { skip }, () => {
  const a = new M.Session(), b = new M.Session();
  try {
    a.loadBytes(new Uint8Array(sphereObj), 'sphere.obj');
    const m0 = ply(a);
    pull(a, [0, 0, 1], [0, 0, 0.4]);
    const m1 = ply(a);
    a.setSettings({ epsilon: '0.1%' });
    pull(a, [1, 0, 0], [0.3, 0, 0]);
    const m2 = ply(a);
    assert.ok(a.memoryBytes() > 3 * 5120 * 8, 'mesh and two snapshots');
    const state = a.saveState(96 * 2 ** 20);
    assert.ok(state instanceof Uint8Array);

    b.restoreState(state);
    assert.ok(ply(b).equals(m2));
    assert.deepStrictEqual(b.settings(), a.settings());
    assert.ok(b.canUndo() && !b.canRedo());
    assert.ok(b.undo());
    assert.ok(ply(b).equals(m1));
    assert.ok(b.undo());
    assert.ok(ply(b).equals(m0));
    assert.strictEqual(b.undo(), false);
    assert.ok(b.redo() && b.redo());
    assert.ok(ply(b).equals(m2));
    // The render buffers follow the restored mesh: they draw its live triangles (a deleted slot,
    // which undo and redo keep, is an empty triangle) and hold every vertex slot.
    const ch = b.changes();
    const ix = b.indices();
    let drawn = 0;
    for (let i = 0; i < ix.length; i += 3) if (ix[i] | ix[i + 1] | ix[i + 2]) drawn++;
    assert.strictEqual(drawn, b.stats().faces);
    assert.ok(ch.vertexCount >= b.stats().vertices);

    // Budget 0: the mesh without history.
    b.restoreState(a.saveState(0));
    assert.ok(ply(b).equals(m2));
    assert.strictEqual(b.canUndo(), false);

    // A damaged state is refused and changes nothing; ArrayBuffers are accepted too.
    const cut = state.slice(0, state.length - 7);
    assert.throws(() => b.restoreState(cut), /saved state: truncated/);
    assert.ok(ply(b).equals(m2));
    assert.throws(() => b.restoreState(new Uint8Array([1, 2, 3])), /saved state: not an adasculpt state/);
    b.restoreState(state.buffer.slice(state.byteOffset, state.byteOffset + state.byteLength));
    assert.ok(b.canUndo());
    // Mid-grab: refused (the autosave waits for the grab to end).
    b.grabBegin(0, 0, 1, 0.1, 0.5);
    assert.throws(() => b.saveState(1e6), /a grab or a stroke is in progress/);
    b.grabEnd();
  } finally {
    a.delete();
    b.delete();
  }
});

// Incremental autosave: a full state once, then saveChanges() records (a pull, an undo, a redo, a
// new pull that drops the redo step, a settings change); restoreSaved(state, records) in a new
// Session gives the same mesh, settings and history. Records are small; a damaged one is refused.
test('saveChanges: a full state plus small records restores the session exactly', { skip }, () => {
  const a = new M.Session(), b = new M.Session();
  try {
    a.loadBytes(new Uint8Array(sphereObj), 'sphere.obj');
    assert.strictEqual(a.saveChanges(), null, 'no full state yet');
    const state = a.saveState(96 * 2 ** 20);
    const records = [];
    const save = () => {
      const r = a.saveChanges();
      assert.ok(r instanceof Uint8Array);
      records.push(r);
    };
    const m0 = ply(a);
    pull(a, [0, 0, 1], [0, 0, 0.2]);
    save();
    const m1 = ply(a);
    pull(a, [1, 0, 0], [0.2, 0, 0]);
    assert.ok(a.undo());
    save();
    assert.ok(a.redo() && a.undo());
    pull(a, [0, 1, 0], [0, 0.2, 0]);  // drops the redo step
    a.setSettings({ epsilon: '0.1%' });
    save();
    const m2 = ply(a);
    for (const r of records) assert.ok(r.byteLength < state.byteLength / 4, `${r.byteLength} of ${state.byteLength}`);

    b.restoreSaved(state, records);
    assert.ok(ply(b).equals(m2));
    assert.deepStrictEqual(b.settings(), a.settings());
    assert.ok(b.canUndo() && !b.canRedo());
    assert.ok(b.undo() && ply(b).equals(m1));
    assert.ok(b.undo() && ply(b).equals(m0));
    assert.strictEqual(b.undo(), false);

    // Damaged, missing or out-of-order records: refused, and the session stays as it was.
    const cut = records[1].slice(0, records[1].length - 3);
    assert.throws(() => b.restoreSaved(state, [records[0], cut, records[2]]), /saved state: a change record is damaged/);
    assert.ok(ply(b).equals(m0));
    assert.throws(() => b.restoreSaved(state, [records[0], records[2]]), /saved state: change record 3 where 2 belongs/);
    assert.ok(ply(b).equals(m0));
    // A whole remesh cannot be a record: a full state is due.
    a.remesh(1);
    assert.strictEqual(a.saveChanges(), null);
  } finally {
    a.delete();
    b.delete();
  }
});
