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
  ...Object.keys(L.TOOLS).map((t) => [t]),  // draw, inflate, smooth, flatten, pinch, crease, grab
  ['draw', 'inflate', 'crease', 'pinch', 'flatten', 'smooth'],
];

// `length`: the edge length the region should reach (within 25 %), or null to skip that check.
function checkTargets(what, m, length) {
  assert.ok(m.faces > 0 && m.interior > 0, `${what}: a region`);
  if (length) assert.ok(m.meanEdge < 1.25 * length && m.meanEdge > 0.75 * length, `${what}: edge length near ${length}`);
  assert.ok(m.pctUnder30 <= 10, `${what}: at most 10 % of the triangles under 30°`);
  assert.ok(m.pctValence5to7 >= 90, `${what}: at least 90 % of interior vertices of valence 5-7`);
  assert.ok(m.minAngle > 10, `${what}: no sliver`);
}

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
    const grab = L.makeGrab(mesh, { view: spec.view, across: spec.across, start: 0.25, pull: 3, radius });
    for (const tools of CASES) {
      await t.test(tools.join(' + '), () => {
        const s = tools[0] === 'grab' ? grab : stroke;
        const ours = L.runOurs(M, mesh, tools.map((tool) => ({ tool, stroke: s })), { length });
        const m = L.brushedRegionMetrics(ours.mesh, s);
        checkTargets(`${spec.name} ${tools.join('+')}: ${JSON.stringify(m)}`, m, length);
      });
    }
  });
}

// The same strokes where the brush must COARSEN the surface 2.5x (a hemisphere first remeshed
// finely; three.js's Sculptor meets the bunny at that ratio with its default detail). The region
// grades up from the fine mesh around it (Remesher::iterate_region: its held border keeps its own
// edge length, graded by the 0.2 gradient limit, and the border's edges are not split); before,
// 7-13 % of the triangles there were under 30°, all in the outer third of the brush.
test('brushed region quality when the brush coarsens 2.5x (hemisphere)', { skip }, async (t) => {
  const mesh0 = L.readMesh(M, MESHES[1].file);
  const radius = 0.07 * L.boundingBox(mesh0.positions).diagonal;
  const length = 0.2 * radius;
  const fine = length / 2.5;
  const s = new M.Session();
  let mesh;
  try {
    s.loadArrays(mesh0.positions, mesh0.indices);
    s.replay(JSON.stringify({ version: 1, settings: { min_length: fine, max_length: fine }, steps: [{ remesh: { iterations: 5 } }] }));
    mesh = { positions: Float64Array.from(s.positions()), indices: Uint32Array.from(s.indices()) };
  } finally {
    s.delete();
  }
  const { view, across } = MESHES[1];
  const stroke = L.makeStroke(mesh, { view, across, span: 0.4, wiggle: 0.05, radius });
  const grab = L.makeGrab(mesh, { view, across, start: 0.25, pull: 3, radius });
  const before = L.brushedRegionMetrics(mesh, stroke);
  for (const tool of ['draw', 'smooth', 'grab']) {
    await t.test(tool, () => {
      const st = tool === 'grab' ? grab : stroke;
      const m = L.brushedRegionMetrics(L.runOurs(M, mesh, [{ tool, stroke: st }], { length }).mesh, st);
      const what = `coarsening ${tool}: ${JSON.stringify(m)}`;
      // A graded transition from the fine surroundings may keep the region finer than `length`.
      assert.ok(m.meanEdge > 1.2 * before.meanEdge, `${what}: the region was coarsened`);
      checkTargets(what, m, null);
    });
  }
});
