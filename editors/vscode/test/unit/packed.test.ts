import assert from 'node:assert/strict';
import { test } from 'node:test';
import { concatPacked, FLAG_CLOCKWISE, FLAG_RAPID, FLAG_UNCERTAIN_X, MOTIONS, packMoves, revivePacked } from '../../src/core/packed';
import { move } from './fixtures';

test('moves are packed with unknown axes as NaN and flags for rapid, direction and uncertainty', () => {
  const packed = packMoves([
    move(3, 'G0', {}, { X: 1, Z: 2 }),
    move(4, 'g02', { X: 1, Z: 2 }, { X: 3, Z: 2 }, { arc: { centre: { X: 2, Z: 2 }, radius: 1, clockwise: true, sweep: 180 }, uncertain: ['Z'] }),
  ]);
  assert.equal(packed.count, 2);
  assert.deepEqual([...packed.line], [3, 4]);
  assert.equal(MOTIONS[packed.motion[1]], 'G2');
  assert.equal(packed.flags[0], FLAG_RAPID);
  assert.equal(packed.flags[1], FLAG_CLOCKWISE | (FLAG_UNCERTAIN_X << 2));
  assert.ok(Number.isNaN(packed.start[0]) && Number.isNaN(packed.end[1]), 'no start and no Y are unknown');
  assert.deepEqual([...packed.end.slice(0, 3)].map((v) => (Number.isNaN(v) ? null : v)), [1, null, 2]);
  assert.deepEqual([...packed.arcOf], [-1, 0]);
  assert.equal(packed.arcRadius[0], 1);
});

test('joined parts keep each move and re-number the arcs', () => {
  const arc = { centre: { X: 0, Y: 0 }, radius: 1, clockwise: false, sweep: 90 };
  const a = packMoves([move(1, 'G2', { X: 1, Y: 0 }, { X: 0, Y: 1 }, { arc })]);
  const b = packMoves([move(2, 'G1', { X: 0, Y: 1 }, { X: 0, Y: 2 }), move(3, 'G3', { X: 1, Y: 0 }, { X: 0, Y: 1 }, { arc: { ...arc, radius: 7 } })]);
  const joined = concatPacked([a, b]);
  assert.equal(joined.count, 3);
  assert.deepEqual([...joined.line], [1, 2, 3]);
  assert.deepEqual([...joined.arcOf], [0, -1, 1]);
  assert.deepEqual([...joined.arcRadius], [1, 7]);
  assert.deepEqual([...joined.end.slice(3, 6)].map((v) => (Number.isNaN(v) ? null : v)), [0, 2, null]);
});

test('a toolpath that lost its typed arrays on the way is revived', () => {
  const arc = { centre: { X: 0, Y: 0 }, radius: 1, clockwise: false, sweep: 90 };
  const packed = packMoves([move(1, 'G0', {}, { X: 1 }), move(2, 'G3', { X: 1, Y: 0 }, { X: 0, Y: 1 }, { arc })]);
  const asJson = JSON.parse(JSON.stringify(packed)); // typed arrays become {"0": .., "1": ..}
  const revived = revivePacked(asJson);
  assert.ok(revived.line instanceof Uint32Array && revived.arcOf instanceof Int32Array);
  assert.deepEqual([...revived.line], [1, 2]);
  assert.deepEqual([...revived.arcOf], [-1, 0]);
  assert.deepEqual([...revived.end.slice(0, 3)].map((v) => (v === null || Number.isNaN(v) ? null : v)), [1, null, null]);
  assert.equal(revivePacked(packed).line, packed.line, 'typed arrays are kept, not copied');
  const plain = revivePacked({ ...packed, line: [...packed.line] });
  assert.deepEqual([...plain.line], [1, 2]);
});
