import assert from 'node:assert/strict';
import { test } from 'node:test';
import { outermostLine, parsePreview, PreviewFormatError } from '../../src/core/preview';
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

test('an older answer without passes, files or calls reads as moves of the previewed file, each run once', () => {
  const preview = parsePreview(readFixture('demo_mill.preview.json'));
  assert.deepEqual(preview.assumed, {});
  for (const move of preview.moves) {
    assert.deepEqual([move.pass, move.file, move.stack, move.assumed, move.conditional], [null, null, [], [], false]);
    assert.equal(outermostLine(move), move.line);
  }
});

test('moves in execution order carry their pass, their file, their calls and whether they are conditional', () => {
  const preview = parsePreview(readFixture('calls_mill.preview.json'));
  assert.equal(preview.moves.length, 23);
  assert.deepEqual(preview.assumed, {}, 'an empty object: nothing assumed');
  // The third run of SLOT.SPF line 4 (N20), called by N70 SLOT P2 on line 8.
  const slot = preview.moves.filter((m) => m.file === 'SLOT.SPF' && m.line === 4);
  assert.deepEqual(slot.map((m) => m.pass), [1, 2, 3]);
  assert.deepEqual(slot[2].stack, [{ file: 'calls_mill.mpf', line: 8 }]);
  assert.equal(outermostLine(slot[2]), 8);
  assert.deepEqual(preview.moves.filter((m) => m.line === 11 && m.file === null).map((m) => m.pass), [1, 2, 3], 'the loop runs three times');
  const conditional = preview.moves.filter((m) => m.conditional);
  assert.deepEqual(conditional.map((m) => m.block), ['N160']);
});

test('the assumed entry state of a subprogram and the axes that rest on it are read', () => {
  const preview = parsePreview({
    file: 'SLOT.SPF',
    assumed: { units: 'G71', distance: 'G90', plane: 'G17' },
    moves: [{ line: 3, motion: 'G1', end: { X: 20 }, assumed: ['x', 'Y'], stack: [{ line: 2 }], pass: 2 }],
  });
  assert.deepEqual(preview.assumed, { units: 'G71', distance: 'G90', plane: 'G17' });
  assert.deepEqual(preview.moves[0].assumed, ['X', 'Y']);
  assert.deepEqual(preview.moves[0].stack, [{ file: null, line: 2 }], 'a call site without a file is in the previewed file');
  assert.equal(parsePreview({ assumed: null, moves: [] }).assumed.units, undefined);
});

test('a malformed pass, file, stack, assumed or conditional is an error that names the place', () => {
  const base = { line: 1, motion: 'G1', end: {} };
  const cases: [unknown, RegExp][] = [
    [{ moves: [{ ...base, pass: 0 }] }, /moves\[0\]: pass is not a positive integer/],
    [{ moves: [{ ...base, pass: 1.5 }] }, /pass is not a positive integer/],
    [{ moves: [{ ...base, file: 3 }] }, /moves\[0\]: file is not a string/],
    [{ moves: [{ ...base, stack: {} }] }, /moves\[0\]: stack is not a list of call sites/],
    [{ moves: [base, { ...base, stack: [{ file: 'A.MPF', line: 2 }, { file: 'B.SPF' }] }] }, /moves\[1\]\.stack\[1\]: line is not a positive integer/],
    [{ moves: [{ ...base, stack: [{ file: 7, line: 2 }] }] }, /moves\[0\]\.stack\[0\]: file is not a string/],
    [{ moves: [{ ...base, assumed: 'X' }] }, /assumed is not a list of axis names/],
    [{ moves: [{ ...base, conditional: 'yes' }] }, /conditional is not true or false/],
    [{ moves: [], assumed: ['G71'] }, /answer: assumed is not an object/],
    [{ moves: [], assumed: { units: 71 } }, /assumed units is not a string/],
  ];
  for (const [value, message] of cases) {
    assert.throws(() => parsePreview(value), (error: unknown) => error instanceof PreviewFormatError && message.test(error.message), String(message));
  }
});
