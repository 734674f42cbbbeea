import assert from 'node:assert/strict';
import { test } from 'node:test';
import { parsePreview, PreviewFormatError } from '../../src/core/preview';
import { readFixture } from './fixtures';

test('the CLI preview of the demo program is read move by move', () => {
  const preview = parsePreview(readFixture('demo_mill.preview.json'));
  assert.equal(preview.units, 'mm');
  assert.equal(preview.moves.length, 23);
  const first = preview.moves[0];
  assert.deepEqual(first.start, {});
  assert.deepEqual(first.end, { X: -10, Y: -10, Z: 5 });
  assert.equal(first.feed, null);
  const circle = preview.moves.find((m) => m.block === 'N170')!;
  assert.deepEqual(circle.arc, { centre: { X: 35, Y: 25 }, radius: 15, clockwise: true, sweep: 360 });
  const afterLabel = preview.moves.find((m) => m.block === 'N240')!;
  assert.deepEqual(afterLabel.uncertain, ['X', 'Y', 'Z']);
});

test('an arc may give its direction as `clockwise` or as `direction`', () => {
  const base = { line: 2, motion: 'G2', start: { X: 0, Y: 0 }, end: { X: 10, Y: 0 }, uncertain: [] };
  const a = parsePreview({ moves: [{ ...base, arc: { centre: { X: 5, Y: 0 }, radius: 5, clockwise: false, sweep: 180 } }] });
  const b = parsePreview({ moves: [{ ...base, arc: { centre: { x: 5, y: 0 }, radius: 5, direction: 'cw', sweep: 180 } }] });
  assert.equal(a.moves[0].arc!.clockwise, false);
  assert.equal(b.moves[0].arc!.clockwise, true);
  assert.deepEqual(b.moves[0].arc!.centre, { X: 5, Y: 0 }, 'axis names are upper-cased');
});

test('a malformed answer is an error that names the place', () => {
  const cases: [unknown, RegExp][] = [
    [null, /answer: expected an object/],
    [{ moves: 3 }, /no list of moves/],
    [{ moves: [{ line: 0, motion: 'G1', end: {} }] }, /moves\[0\]: line is not a positive integer/],
    [{ moves: [{ line: 1, motion: 'G1', end: { X: 'a' } }] }, /moves\[0\]\.end: axis X is not a finite number/],
    [{ moves: [{ line: 1, motion: 'G2', end: {}, arc: { centre: {}, radius: -1, sweep: 3, clockwise: true } }] }, /radius/],
    [{ moves: [{ line: 1, motion: 'G2', end: {}, arc: { centre: {}, radius: 1, sweep: 3 } }] }, /neither/],
    [{ moves: [{ line: 1, motion: 'G1', end: {}, uncertain: [1] }] }, /uncertain/],
  ];
  for (const [value, message] of cases) {
    assert.throws(() => parsePreview(value), (error: unknown) => error instanceof PreviewFormatError && message.test(error.message));
  }
});
