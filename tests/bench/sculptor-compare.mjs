// Brushes side by side: adasculpt (wasm module, Session.replay of brush steps) against three.js's
// Sculptor addon (three/addons/misc/Sculptor.js, SculptGL's dynamic topology), in one node process.
//
//   node tests/bench/sculptor-compare.mjs [--repeats N] [--detail D] [--quick]
//   npm run bench:sculptor              (the same; also a stage of `npm run bench`)
//
// For every mesh: the same strokes (rays of an orthographic view, see brush-compare-lib.mjs) go to
// Sculptor as strokeFromRay() stamps and to adasculpt as the stroke path (the rays' hits on the
// initial surface, one stamp per point). Equal resolution: Sculptor refines the brushed region
// towards edge lengths between radius * sqrt(0.2 (1.1 - detail)) / 2.05 and that; adasculpt gets
// a uniform target length (min_length = max_length = L) calibrated on the draw stroke so that the
// mean edge length in the brushed region matches Sculptor's (both are printed).
// Timing: wall time of the whole stroke per stamp (Sculptor: the strokeFromRay calls + endStroke;
// adasculpt: the replay call minus an empty replay's), and the median single stamp (Sculptor: one
// strokeFromRay call; adasculpt: the core's frame_ms_median), each the median over the repeats.
import fs from 'node:fs';
import path from 'node:path';
import os from 'node:os';
import { execFileSync } from 'node:child_process';
import * as L from './brush-compare-lib.mjs';

const args = process.argv.slice(2);
const opt = (name, dflt) => {
  const i = args.indexOf(name);
  return i >= 0 ? Number(args[i + 1]) : dflt;
};
const quick = args.includes('--quick');
const REPEATS = opt('--repeats', quick ? 1 : 5);
const DETAIL = opt('--detail', 0.75);

const M = await L.loadAdasculpt();
if (!M) {
  console.log('sculptor-compare: no wasm module in public/wasm (scripts/build.sh wasm); skipped');
  process.exit(0);
}
await L.loadSculptor();

const shared = process.env.ADASCULPT_SHARED_MESHES_DIR || path.join(L.ROOT, '..', 'shared', 'meshes');
const MESHES = [
  { name: 'icosphere', file: path.join(L.ROOT, 'public', 'models', 'sphere.obj'), view: [0, 0, -1], across: [1, 0, 0] },
  { name: 'hemisphere', file: path.join(L.ROOT, 'public', 'models', 'hemisphere.off'), view: [0, 0, -1], across: [1, 0, 0] },
  { name: 'fandisk', file: path.join(L.ROOT, 'public', 'models', 'fandisk.off'), view: [0, 0, -1], across: [0, 1, 0] },
  { name: 'bunny', file: path.join(shared, 'bunny.off'), view: [0, 0, -1], across: [1, 0, 0], optional: true },
];
const TOOL_ORDER = ['draw', 'inflate', 'smooth', 'flatten', 'pinch', 'crease'];
// The "session" row: every tool in turn along the same stroke on one mesh.
const SESSION_ORDER = ['draw', 'inflate', 'crease', 'pinch', 'flatten', 'smooth'];
const RADIUS = 0.07;  // brush radius, fraction of the bounding-box diagonal
const native = path.join(L.ROOT, 'build', 'native', 'adasculpt');
const haveNative = fs.existsSync(native);

const f = (x, d = 2) => (Number.isFinite(x) ? x.toFixed(d) : '–');
const rows = [];
const notes = [];

for (const spec of MESHES) {
  if (!fs.existsSync(spec.file)) {
    console.log(`sculptor-compare: ${spec.file} not found; ${spec.name} skipped`);
    continue;
  }
  if (quick && spec.optional) continue;
  const mesh = L.readMesh(M, spec.file);
  const bb = L.boundingBox(mesh.positions);
  const radius = RADIUS * bb.diagonal;
  const stroke = L.makeStroke(mesh, { view: spec.view, across: spec.across, span: 0.4, wiggle: 0.05, radius });
  const base = L.brushedRegionMetrics(mesh, stroke);

  // Equal resolution: our uniform length such that the brushed region's mean edge matches
  // Sculptor's after the same strokes. L0 = Sculptor's mean, then one correction. Each single-tool
  // row is calibrated on its own stroke: Sculptor's smooth neither refines nor coarsens the input
  // (its region keeps the input's edges, 1.6x longer than after its draw on the sphere, 2.5x
  // shorter on the bunny), so a length calibrated on the draw made us remesh the smooth row to a
  // different resolution than Sculptor's. Grab and the session row keep the draw's length.
  const calibrate = (strokes) => {
    const last = strokes[strokes.length - 1].stroke;
    const target = L.brushedRegionMetrics(L.runSculptor(mesh, strokes, { detail: DETAIL }).mesh, last).meanEdge;
    const first = L.brushedRegionMetrics(L.runOurs(M, mesh, strokes, { length: target }).mesh, last).meanEdge;
    return target * (target / first);
  };
  const length = calibrate([{ tool: 'draw', stroke }]);
  notes.push(
    `${spec.name}: ${mesh.positions.length / 3} vertices, ${mesh.indices.length / 3} faces, diagonal ${f(bb.diagonal, 3)}, ` +
      `brush radius ${f(radius, 4)}, ${stroke.path.length} stamps per stroke, mean edge in the region before ${f(base.meanEdge, 4)}; ` +
      `Sculptor detail ${DETAIL} (split > ${f(radius * Math.sqrt(0.2 * (1.1 - DETAIL)), 4)}, collapse < ${f((radius * Math.sqrt(0.2 * (1.1 - DETAIL))) / 2.05, 4)}); ` +
      `adasculpt min_length = max_length = ${f(length, 4)} (calibrated on the draw stroke)`,
  );

  const cases = TOOL_ORDER.map((t) => {
    const strokes = [{ tool: t, stroke }];
    return { label: t, strokes, length: t === 'draw' ? length : calibrate(strokes) };
  });
  notes.push(`${spec.name}: adasculpt length per single-tool row: ` +
    cases.map((c) => `${c.label} ${f(c.length, 4)}`).join(', '));
  const grab = L.makeGrab(mesh, { view: spec.view, across: spec.across, start: 0.25, pull: 3, radius });
  cases.push({ label: 'grab (snake hook, 3 radii)', strokes: [{ tool: 'grab', stroke: grab }], length });
  cases.push({ label: 'all six in turn', strokes: SESSION_ORDER.map((t) => ({ tool: t, stroke })), length });
  for (const c of cases) {
    const length = c.length;
    // One untimed warm-up run of each (JIT, wasm tier-up), then REPEATS timed runs.
    L.runSculptor(mesh, c.strokes, { detail: DETAIL });
    L.runOurs(M, mesh, c.strokes, { length });
    const S = [], O = [];
    for (let r = 0; r < REPEATS; ++r) {
      S.push(L.runSculptor(mesh, c.strokes, { detail: DETAIL }));
      O.push(L.runOurs(M, mesh, c.strokes, { length }));
    }
    let nativeMedian = NaN;
    if (haveNative) {
      const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'sculptcmp-'));
      try {
        const steps = c.strokes.map(({ tool, stroke: s }) => ({
          brush: { tool, path: s.path, radius: s.radius, strength: L.TOOLS[tool].ours, spacing: s.spacing },
        }));
        fs.writeFileSync(path.join(tmp, 's.json'),
          JSON.stringify({ version: 1, settings: { min_length: length, max_length: length }, steps }));
        const med = [];
        for (let r = 0; r < Math.max(1, REPEATS); ++r) {
          const out = execFileSync(native, ['replay', spec.file, path.join(tmp, 's.json'), path.join(tmp, 'o.off'), '--json']);
          med.push(JSON.parse(out).frame_ms_median);
        }
        nativeMedian = L.median(med);
      } finally {
        fs.rmSync(tmp, { recursive: true, force: true });
      }
    }
    const last = c.strokes[c.strokes.length - 1].stroke;
    const sm = L.brushedRegionMetrics(S[S.length - 1].mesh, last);
    const om = L.brushedRegionMetrics(O[O.length - 1].mesh, last);
    const stamps = S[0].stamps;
    if (c.strokes[0].tool === 'grab')
      notes.push(`${spec.name} grab: the hook reached ${f(100 * L.grabReach(S[S.length - 1].mesh, grab), 0)} % (Sculptor) and ` +
        `${f(100 * L.grabReach(O[O.length - 1].mesh, grab), 0)} % (adasculpt) of the pointer's 3-radii travel`);
    if (S.some((x) => x.missed)) notes.push(`${spec.name} ${c.label}: Sculptor missed ${S[0].missed} rays`);
    const row = (who, m, runs, extra) =>
      rows.push(
        `| ${spec.name} | ${c.label} | ${who} | ${stamps} | ${f(m.meanEdge, 4)} | ${m.faces} | ${f(m.minAngle, 1)} | ` +
          `${f(m.pctUnder30, 1)} | ${f(m.pctValence5to7, 1)} | ${f(m.pctUnder30Rim, 1)} | ${f(L.median(runs.map((x) => x.msPerStamp)), 2)} | ` +
          `${f(L.median(runs.map((x) => x.stampMedian)), 2)} | ${extra} |`,
      );
    row('Sculptor', sm, S, '');
    row('**adasculpt**', om, O, f(nativeMedian, 2));
    process.stderr.write(`  ${spec.name} ${c.label} done\n`);
  }
}

console.log(`\nBrushes vs three.js Sculptor (three ${(await import('three')).REVISION}), node ${process.version}, ` +
  `${REPEATS} timed run(s) after a warm-up, medians; region = faces whose centroid is within the brush radius of the ` +
  `stroke (its rays cast again on the final surface; grab: of the dragged path), rim = faces between 1 and 1.5 radii from it\n`);
console.log('| mesh | stroke | who | stamps | mean edge in region | faces in region | min angle | % < 30° | % interior valence 5–7 | rim: % < 30° | ms/stamp (stroke wall) | ms/stamp (median stamp) | native ms/stamp (median) |');
console.log('|---|---|---|---|---|---|---|---|---|---|---|---|---|');
for (const r of rows) console.log(r);
console.log('');
for (const n of notes) console.log(`- ${n}`);
console.log(`- load average while measuring: ${os.loadavg().map((x) => x.toFixed(1)).join(' ')} (${os.cpus().length} cores)`);
