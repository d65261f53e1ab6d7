// node:test of the wasm brush bindings: Session.brushBegin / brushStamp / brushEnd (the browser's
// frame path: one brushStamp per animation frame with all its pointer samples as x, y, z, pressure).
// Loads public/wasm (or ADASCULPT_WASM_DIR) like session.test.cjs.
const test = require('node:test');
const assert = require('node:assert');

const { skip, loadModule, withSphere: withSphereOf } = require('./wasm-module.cjs');

let M;
test.before(async () => {
  M = await loadModule();
});

const withSphere = (fn) => withSphereOf(M, fn);

const exported = (s) => Buffer.from(s.exportMesh('off'));
const quality = (s) => s.stats();

// An arc over the front of the unit sphere, right of the x = 0 plane.
const PATH = Array.from({ length: 9 }, (_, i) => {
  const a = -0.4 + 0.1 * i;
  return [0.35, Math.sin(a) * Math.sqrt(1 - 0.35 * 0.35), Math.cos(a) * Math.sqrt(1 - 0.35 * 0.35)];
});
const SETTINGS = { tool: 'draw', radius: 0.2, strength: 0.8, symmetry: 'x' };
const samples = (pts, pressure = 1) => Float64Array.from(pts.flatMap((p) => [...p, pressure]));
const radiusOf = (pos, v) => Math.hypot(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);

test('a draw stroke in one brushStamp call: raised on both sides (symmetry x), one undo step', { skip }, () => {
  withSphere((s) => {
    const before = exported(s);
    s.brushBegin(SETTINGS);
    assert.strictEqual(s.brushing(), true);
    const ch = s.brushStamp(samples(PATH));
    assert.ok(ch.timings.stamps >= PATH.length, `stamps ${ch.timings.stamps}`);
    assert.ok(ch.timings.total > 0);
    assert.ok(ch.vertexEnd > ch.vertexBegin, 'dirty vertices reported');
    assert.strictEqual(ch.vertexCount, s.positions().length / 3);
    s.brushEnd();
    assert.strictEqual(s.brushing(), false);
    const pos = s.positions();
    let right = 0, left = 0;
    for (let v = 0; v < pos.length / 3; v++) {
      if (radiusOf(pos, v) < 1.02) continue;
      if (pos[3 * v] > 0) right++; else left++;
    }
    assert.ok(right > 5 && left > 5, `raised vertices right ${right}, left ${left}`);
    assert.notStrictEqual(quality(s).vertices, 2562, 'dynamic topology changed the vertex count');
    assert.strictEqual(s.undo(), true);
    assert.deepStrictEqual(exported(s), before, 'one undo restores the sphere exactly');
    assert.strictEqual(s.canUndo(), false);
  });
});

test('one call with N samples = N calls with one sample = the session file replay', { skip }, () => {
  const oneCall = withSphere((s) => {
    s.brushBegin({ ...SETTINGS });
    s.brushStamp(samples(PATH, 0.7));
    s.brushEnd();
    return exported(s);
  });
  const perSample = withSphere((s) => {
    s.brushBegin(SETTINGS);
    for (const p of PATH) s.brushStamp([...p, 0.7]); // a plain array works too
    s.brushEnd();
    return exported(s);
  });
  const replayed = withSphere((s) => {
    s.replay(JSON.stringify({ version: 1, steps: [{ brush: { ...SETTINGS, path: PATH, pressure: PATH.map(() => 0.7) } }] }));
    return exported(s);
  });
  assert.deepStrictEqual(perSample, oneCall);
  assert.deepStrictEqual(replayed, oneCall);
});

test('invert, pressure and symmetry none do what they say', { skip }, () => {
  const extreme = (settings, pressure = 1) => withSphere((s) => {
    s.brushBegin({ ...SETTINGS, ...settings });
    s.brushStamp(samples(PATH, pressure));
    s.brushEnd();
    const pos = s.positions();
    let min = Infinity, max = 0, leftMoved = 0;
    for (let v = 0; v < pos.length / 3; v++) {
      const r = radiusOf(pos, v);
      min = Math.min(min, r);
      max = Math.max(max, r);
      if (pos[3 * v] < -0.05 && Math.abs(r - 1) > 0.01) leftMoved++;
    }
    return { min, max, leftMoved };
  });
  const full = extreme({});
  const light = extreme({}, 0.2);
  const inward = extreme({ invert: true });
  const oneSide = extreme({ symmetry: 'none' });
  assert.ok(full.max > 1.05, `draw raises (max radius ${full.max})`);
  assert.ok(light.max - 1 < (full.max - 1) * 0.6, `pressure 0.2 raises less (${light.max} vs ${full.max})`);
  assert.ok(inward.min < 0.95 && inward.max < 1.01, `inverted draw digs in (min ${inward.min}, max ${inward.max})`);
  assert.strictEqual(oneSide.leftMoved, 0, 'without symmetry the left side stays');
  assert.ok(full.leftMoved > 0, 'with symmetry x the left side moves too');
});

test('every tool strokes; bad settings and calls are Errors with the message', { skip }, () => {
  withSphere((s) => {
    for (const tool of ['draw', 'inflate', 'smooth', 'flatten', 'pinch', 'crease', 'snakeHook']) {
      s.brushBegin({ tool, radius: 0.15 });
      // The grab brush takes pointer positions in space: lift the path off the surface.
      s.brushStamp(samples(tool === 'snakeHook' ? PATH.map(([x, y, z]) => [x, y, z * 1.2]) : PATH));
      s.brushEnd();
    }
    const q = quality(s);
    assert.ok(q.minAngleDeg > 5, `min angle after all tools ${q.minAngleDeg}`);
    assert.throws(() => s.brushBegin({ tool: 'hammer', radius: 0.1 }), /'tool' must be one of draw, inflate/);
    assert.throws(() => s.brushBegin({ tool: 'draw', radius: -1 }), /'radius' must be a positive number/);
    assert.throws(() => s.brushBegin({ tool: 'draw', radius: 0.1, strenght: 1 }), /unknown field 'strenght'/);
    assert.throws(() => s.brushBegin(42), /expected a plain object/);
    assert.throws(() => s.brushBegin(JSON.stringify(SETTINGS)), /expected a plain object/); // no JSON strings
    assert.throws(() => s.brushStamp(samples(PATH)), /no stroke in progress/);
    s.brushBegin(SETTINGS);
    assert.throws(() => s.brushStamp(new Float64Array(5)), /x, y, z, pressure/);
    s.brushEnd();
    assert.strictEqual(s.brushing(), false);
  });
});

test('quickStats (kept from the changes) equals the whole stats() after strokes, undo and redo', { skip }, () => {
  withSphere((s) => {
    const same = (where) => {
      const q = s.quickStats(), full = s.stats();
      for (const k of ['vertices', 'faces', 'edges', 'minAngleDeg', 'maxAngleDeg', 'pctMinAngleLt30', 'pctMinAngleLt10'])
        assert.strictEqual(q[k], full[k], `${where}: ${k}`);
      assert.ok(Math.abs(q.meanMinAngleDeg - full.meanMinAngleDeg) < 1e-9, `${where}: meanMinAngleDeg`);
      assert.strictEqual(q.canUndo, full.canUndo);
    };
    same('loaded');
    for (const tool of ['draw', 'crease', 'pinch']) {
      s.brushBegin({ ...SETTINGS, tool });
      s.brushStamp(samples(PATH));
      s.brushEnd();
      same(tool);
    }
    for (const step of ['undo', 'undo', 'redo', 'undo']) {
      s[step]();
      same(step);
    }
  });
});
