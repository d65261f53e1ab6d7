// Issue #7 quality targets for our brushes, in the brushed region (the same strokes and the same
// region definition as the Sculptor comparison, tests/bench/sculptor-compare.mjs): at least 90 % of
// the triangles above 30° and at least 90 % of the interior vertices of valence 5-7, after each
// tool's stroke and after all six in turn. Runs the wasm module (public/wasm, or
// ADASCULPT_WASM_DIR) through Session.replay. No timing assertions.
import test from 'node:test';
import assert from 'node:assert';
import path from 'node:path';
import * as L from '../bench/brush-compare-lib.mjs';

const M = await L.loadAdasculpt();
const skip = !M && 'no wasm module (scripts/build.sh wasm)';

const MESHES = [
  { name: 'icosphere', file: path.join(L.ROOT, 'public', 'models', 'sphere.obj'), view: [0, 0, -1], across: [1, 0, 0] },
  { name: 'hemisphere', file: path.join(L.ROOT, 'public', 'models', 'hemisphere.off'), view: [0, 0, -1], across: [1, 0, 0] },
];
const CASES = [
  ...Object.keys(L.TOOLS).map((t) => [t]),
  ['draw', 'inflate', 'crease', 'pinch', 'flatten', 'smooth'],
];

for (const spec of MESHES) {
  test(`brushed region quality on ${spec.name}`, { skip }, async (t) => {
    const mesh = L.readMesh(M, spec.file);
    const radius = 0.07 * L.boundingBox(mesh.positions).diagonal;
    const stroke = L.makeStroke(mesh, { view: spec.view, across: spec.across, span: 0.4, wiggle: 0.05, radius });
    const before = L.brushedRegionMetrics(mesh, stroke);
    // About the resolution Sculptor's default detail (0.75) gives: finer than both input meshes,
    // so every stroke refines its region.
    const length = 0.2 * radius;
    assert.ok(length < 0.9 * before.meanEdge, 'the stroke must refine the region');
    for (const tools of CASES) {
      await t.test(tools.join(' + '), () => {
        const ours = L.runOurs(M, mesh, tools.map((tool) => ({ tool, stroke })), { length });
        const m = L.brushedRegionMetrics(ours.mesh, stroke);
        const what = `${spec.name} ${tools.join('+')}: ${JSON.stringify(m)}`;
        assert.ok(m.faces > before.faces, `${what}: the region was refined`);
        assert.ok(m.meanEdge < 1.25 * length && m.meanEdge > 0.75 * length, `${what}: edge length near ${length}`);
        assert.ok(m.pctUnder30 <= 10, `${what}: at most 10 % of the triangles under 30°`);
        assert.ok(m.pctValence5to7 >= 90, `${what}: at least 90 % of interior vertices of valence 5-7`);
        assert.ok(m.minAngle > 10, `${what}: no sliver`);
      });
    }
  });
}
