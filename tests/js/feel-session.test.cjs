// node:test of the wasm Session's brush falloff and detail flood fill (bindings: brushBegin's falloff,
// remeshDetail), the calls web/AdaptiveSculptor.js makes.
const test = require('node:test');
const assert = require('node:assert');
const { skip, loadModule, withSphere: withSphereOf } = require('./wasm-module.cjs');

let Module = null;
test.before(async () => { Module = await loadModule(); });

const withSphere = (fn) => withSphereOf(Module, fn);

// The highest point after one full-strength draw dab at the front pole, and the raise at half the radius.
function dab(s, falloff) {
  s.brushBegin({ tool: 'draw', radius: 0.4, strength: 1, symmetry: 'none', falloff });
  s.brushStamp(new Float64Array([0, 0, 1, 1]));
  s.brushEnd();
  const p = s.positions();
  let centre = 0, half = 0, n = 0;
  for (let i = 0; i < p.length; i += 3) {
    const r = Math.hypot(p[i], p[i + 1]);
    const raise = Math.hypot(p[i], p[i + 1], p[i + 2]) - 1;
    if (p[i + 2] <= 0) continue;
    if (r < 0.03) centre = Math.max(centre, raise);
    if (r > 0.18 && r < 0.22) { half += raise; n++; }
  }
  return half / n / centre;
}

test('brushBegin takes a falloff preset; constant and sharp dabs differ; a bad name is refused', { skip }, () => {
  const constant = withSphere((s) => dab(s, 'constant'));
  const sharp = withSphere((s) => dab(s, 'sharp'));
  assert.ok(constant > 0.85, `constant ${constant}`);
  assert.ok(sharp < 0.45, `sharp ${sharp}`);
  withSphere((s) => assert.throws(() => s.brushBegin({ tool: 'draw', radius: 0.3, falloff: 'soft' }),
    /'falloff' must be one of smooth, sphere, sharp, linear, constant/));
});

test('remeshDetail remeshes the whole mesh towards the edge length in one undo step', { skip }, () => {
  withSphere((s) => {
    const before = s.stats().vertices;
    s.remeshDetail(5, 0.05);
    const q = s.stats();
    assert.ok(Math.abs(q.edgeLengthMean - 0.05) < 0.0075, `mean edge ${q.edgeLengthMean}`);
    assert.strictEqual(s.undo(), true);
    assert.strictEqual(s.stats().vertices, before);
    assert.strictEqual(s.canUndo(), false);
    assert.throws(() => s.remeshDetail(1, -1), /'detail' must be a non-negative length/);
  });
});
