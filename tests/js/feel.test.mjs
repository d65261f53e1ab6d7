// web/lazy-pointer.js (the stroke stabiliser) and web/brush-feel.js (falloff, spacing, detail modes).
import test from 'node:test';
import assert from 'node:assert';
import { LazyPointer } from '../../web/lazy-pointer.js';
import { FEEL_DEFAULTS, checkFeel, detailLength } from '../../web/brush-feel.js';
import { lengthToPercent } from '../../web/settings.js';

test('the lazy pointer stays put within the string and then trails the pointer by its length', () => {
  const p = new LazyPointer(0, 0);
  assert.strictEqual(p.follow(3, 4, 10), false); // 5 px away: within reach
  assert.deepStrictEqual([p.x, p.y], [0, 0]);
  assert.strictEqual(p.follow(30, 40, 10), true); // 50 px away: pulled 40 px along the line
  assert.ok(Math.abs(p.x - 24) < 1e-12 && Math.abs(p.y - 32) < 1e-12);
  assert.ok(Math.abs(Math.hypot(30 - p.x, 40 - p.y) - 10) < 1e-12);
  // A zig-zag of +-8 px around y = 0 under a 20 px string: the brush never leaves the line by more than the first pull.
  const q = new LazyPointer(0, 0);
  let worst = 0;
  for (let i = 1; i <= 40; i++) {
    if (q.follow(6 * i, i % 2 ? 8 : -8, 20)) worst = Math.max(worst, Math.abs(q.y));
  }
  assert.ok(worst < 4, `lateral deviation ${worst}`);
});

test('feel parameters are checked with messages that name them', () => {
  assert.strictEqual(checkFeel('falloff', 'sharp', 2, lengthToPercent), 'sharp');
  assert.throws(() => checkFeel('falloff', 'soft', 2, lengthToPercent), /falloff must be one of smooth, sphere, sharp, linear, constant/);
  assert.throws(() => checkFeel('detailMode', 'auto', 2, lengthToPercent), /detailMode must be one of relative, constant, brush, pixels/);
  assert.throws(() => checkFeel('spacing', 0.01, 2, lengthToPercent), /spacing must be a number between 0.05 and 4/);
  assert.throws(() => checkFeel('stabilizer', -1, 2, lengthToPercent), /stabilizer must be a number between 0 and 200/);
  assert.strictEqual(checkFeel('constantDetail', 0.02, 2, lengthToPercent), 1); // absolute 0.02 of a diagonal 2: 1 %
  assert.strictEqual(checkFeel('constantDetail', '0.5%', 2, lengthToPercent), 0.5);
});

test('the detail length of each mode', () => {
  const feel = { ...FEEL_DEFAULTS, constantDetail: 0.5, brushDetail: 20, pixelDetail: 8 };
  const at = { diagonal: 4, radius: 0.3, pixelSize: () => 0.001 };
  assert.strictEqual(detailLength({ ...feel, detailMode: 'relative' }, at), 0);
  assert.strictEqual(detailLength({ ...feel, detailMode: 'constant' }, at), 0.02);
  assert.ok(Math.abs(detailLength({ ...feel, detailMode: 'brush' }, at) - 0.06) < 1e-15);
  assert.strictEqual(detailLength({ ...feel, detailMode: 'pixels' }, at), 0.008);
});

test('the touch gate: a finger on the model is the tool\'s once it moves or taps, never when a second finger comes', async () => {
  const { TouchGate, TOUCH_SLOP_PX } = await import('../../web/touch-gate.js');
  const held = [];
  const gate = new TouchGate((h) => held.push(h));
  const ev = (type, pointerId, x, isPrimary = pointerId === 1) => ({ type, pointerId, clientX: x, clientY: 0, isPrimary, target: null });
  // One finger: waits, then the press at the landing point once it moved past the slop.
  assert.strictEqual(gate.down(ev('pointerdown', 1, 100)), false);
  gate.wait(ev('pointerdown', 1, 100), 'hit');
  assert.strictEqual(gate.moved(ev('pointermove', 1, 100 + TOUCH_SLOP_PX - 1)), null);
  const press = gate.moved(ev('pointermove', 1, 100 + TOUCH_SLOP_PX + 1));
  assert.deepStrictEqual([press.down.clientX, press.down.pointerId, press.hit], [100, 1, 'hit']);
  assert.strictEqual(gate.up(ev('pointerup', 1, 120)), null);
  assert.deepStrictEqual(held, [true, false]);
  // Two fingers: the second cancels the wait; nothing is the tool's.
  gate.down(ev('pointerdown', 1, 100));
  gate.wait(ev('pointerdown', 1, 100), 'hit');
  assert.strictEqual(gate.down(ev('pointerdown', 2, 140)), true);
  assert.strictEqual(gate.moved(ev('pointermove', 1, 60)), null);
  assert.strictEqual(gate.up(ev('pointerup', 1, 60)), null);
  assert.strictEqual(gate.up(ev('pointerup', 2, 180)), null);
  // A tap is the tool's; a cancel is not.
  gate.down(ev('pointerdown', 1, 100));
  gate.wait(ev('pointerdown', 1, 100), 'hit');
  assert.strictEqual(gate.up(ev('pointerup', 1, 100)).hit, 'hit');
  gate.down(ev('pointerdown', 1, 100));
  gate.wait(ev('pointerdown', 1, 100), 'hit');
  assert.strictEqual(gate.up(ev('pointercancel', 1, 100)), null);
  // A finger lifted outside the canvas is forgotten when a new touch starts.
  gate.down(ev('pointerdown', 5, 0, false));
  assert.strictEqual(gate.down(ev('pointerdown', 1, 100)), false);
});
