// web/settings.js: the one place lengths are read ("x%" or absolute) and the tools' defaults live.
import test from 'node:test';
import assert from 'node:assert';
import { TOOL_DEFAULTS, lengthToPercent, lengthFromText, checkStrength, checkSymmetry } from '../../web/settings.js';

test('lengths: "x%" stays a percentage, numbers are converted with the diagonal', () => {
  assert.strictEqual(lengthToPercent('5%', 2, 'radius'), 5);
  assert.strictEqual(lengthToPercent(' 0.25% ', 2, 'radius'), 0.25);
  assert.strictEqual(lengthToPercent(0.1, 2, 'radius'), 5);
  for (const bad of ['%', 'abc%', '-1%', '0%', 0, -2, NaN, Infinity, '5', null, undefined, {}]) {
    assert.throws(() => lengthToPercent(bad, 2, 'radius'), /radius must be a positive number or "x%"/, String(bad));
  }
  assert.strictEqual(lengthFromText(' 0.1% '), '0.1%');
  assert.strictEqual(lengthFromText('0.002'), 0.002);
});

test('strength and symmetry are checked; none/false/null read as off', () => {
  assert.strictEqual(checkStrength(0.3), 0.3);
  assert.throws(() => checkStrength(1.5), /strength must be a number between 0 and 1/);
  assert.throws(() => checkStrength('0.5'), /strength/);
  for (const v of ['none', false, null, 'off']) assert.strictEqual(checkSymmetry(v), 'off');
  assert.strictEqual(checkSymmetry('z'), 'z');
  assert.throws(() => checkSymmetry('w'), /symmetry must be one of x, y, z, off/);
});

test('the defaults read back through the same parser', () => {
  for (const k of ['radius', 'handleRadius', 'roiRadius']) assert.ok(lengthToPercent(TOOL_DEFAULTS[k], 1, k) > 0, k);
  assert.strictEqual(checkStrength(TOOL_DEFAULTS.strength), TOOL_DEFAULTS.strength);
  assert.strictEqual(checkSymmetry(TOOL_DEFAULTS.symmetry), TOOL_DEFAULTS.symmetry);
});
