// node:test of the WebAssembly module's mask API: mask(), the stroke calls, maskValues() in the
// render buffers' slots, undo/redo and the saved state, errors naming the field.
const test = require('node:test');
const assert = require('node:assert');

const wasm = require('./wasm-module.cjs');

const { skip, loadModule } = wasm;
let M;
test.before(async () => {
  M = await loadModule();
});
const withSphere = (fn) => wasm.withSphere(M, fn);

const values = (s) => Array.from(s.maskValues());

test('whole-mask operations: each one undo step, the values in the render buffers follow undo and redo', { skip }, () => {
  withSphere((s) => {
    assert.ok(values(s).every((v) => v === 0));
    const ch = s.mask({ op: 'fill' });
    assert.ok(ch.vertexEnd > ch.vertexBegin, 'the changed vertices are a dirty range');
    assert.ok(values(s).every((v) => v === 1));
    s.mask({ op: 'clear' });
    assert.ok(values(s).every((v) => v === 0));
    assert.strictEqual(s.undo(), true);
    assert.ok(values(s).every((v) => v === 1), 'undo of clear');
    assert.strictEqual(s.redo(), true);
    assert.ok(values(s).every((v) => v === 0), 'redo of clear');
  });
});

test('a paint stroke point by point equals mask() with the same path; erase lowers; saved state keeps it', { skip }, () => {
  const path = [[0, 0, 1], [0.3, 0, 0.95], [0.6, 0, 0.8]];
  const byCall = withSphere((s) => {
    s.mask({ op: 'paint', path, radius: 0.3, strength: 0.9 });
    return values(s);
  });
  withSphere((s) => {
    s.maskBegin({ op: 'paint', radius: 0.3, strength: 0.9 });
    assert.strictEqual(s.masking(), true);
    for (const p of path) s.maskStamp(Float64Array.from(p));
    s.maskEnd();
    assert.deepStrictEqual(values(s), byCall);
    assert.ok(byCall.filter((v) => v > 0.89).length > 5);
    s.mask({ op: 'erase', path: [path[0]], radius: 0.3 });
    const erased = values(s);
    assert.ok(erased.every((v, i) => v <= byCall[i]) && erased.some((v, i) => v < byCall[i]));
    const blob = s.saveState(1e8);
    const t = new M.Session();
    try {
      t.restoreState(blob);
      assert.deepStrictEqual(values(t), erased);
      t.undo();
      assert.deepStrictEqual(values(t), byCall);
    } finally {
      t.delete();
    }
  });
});

test('bad mask operations throw naming the field; replay runs mask steps', { skip }, () => {
  withSphere((s) => {
    assert.throws(() => s.mask({ op: 'smudge' }), /'op' must be one of paint, erase, clear, fill, invert, blur, sharpen/);
    assert.throws(() => s.mask({ op: 'paint', radius: 1 }), /'path' is missing/);
    assert.throws(() => s.maskBegin({ op: 'invert' }), /paint or erase/);
    assert.throws(() => s.maskStamp(Float64Array.from([0, 0, 1])), /no mask stroke in progress/);
    s.replay({ version: 1, steps: [{ mask: { op: 'fill' } }, { mask: { op: 'invert' } }, { undo: 1 }] });
    assert.ok(values(s).every((v) => v === 1));
  });
});
