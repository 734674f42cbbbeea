import assert from 'node:assert/strict';
import { test } from 'node:test';
import {
  blockText, concatPacked, FLAG_ASSUMED_X, FLAG_CLOCKWISE, FLAG_CONDITIONAL, FLAG_MAIN_BLOCK, FLAG_RAPID, FLAG_UNCERTAIN_X, MOTIONS,
  packMoves, revivePacked, type PackedToolpath,
} from '../../src/core/packed';
import { parsePreview } from '../../src/core/preview';
import { move, readFixture } from './fixtures';

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

/** The call path of a move as [file, line] pairs, outermost first, read back from the site table. */
function callsOf(packed: PackedToolpath, index: number): [string, number][] {
  const calls: [string, number][] = [];
  for (let site = packed.stack[index]; site !== 0; site = packed.siteCaller[site]) {
    calls.unshift([packed.files[packed.siteFile[site]], packed.siteLine[site]]);
  }
  return calls;
}

const CALLS_URI = 'file:///work/calls_mill.mpf';
const callsPart = (lines?: [number, number]) => {
  const moves = parsePreview(readFixture('calls_mill.preview.json')).moves;
  const outer = (m: (typeof moves)[number]) => (m.stack.length ? m.stack[0].line : m.line);
  const part = lines ? moves.filter((m) => outer(m) >= lines[0] && outer(m) <= lines[1]) : moves;
  return packMoves(part, { previewed: CALLS_URI, aliases: ['calls_mill.mpf'], key: (name) => `file:///work/${name}` });
};

test('moves of a called program are packed with their file, pass, outermost line and call path', () => {
  const packed = callsPart();
  assert.equal(packed.count, 23);
  assert.deepEqual(packed.files, [CALLS_URI, 'file:///work/SLOT.SPF'], 'the previewed file first, then each called file once');
  // Moves 2..4 are SLOT.SPF lines 3..5 called from line 6; 6..11 are its second and third run from line 8.
  assert.deepEqual([...packed.file.slice(0, 12)], [0, 0, 1, 1, 1, 0, 1, 1, 1, 1, 1, 1]);
  assert.deepEqual([...packed.line.slice(2, 12)], [3, 4, 5, 7, 3, 4, 5, 3, 4, 5]);
  assert.deepEqual([...packed.outerLine.slice(2, 12)], [6, 6, 6, 7, 8, 8, 8, 8, 8, 8]);
  assert.deepEqual([...packed.pass.slice(0, 12)], [0, 0, 1, 1, 1, 0, 2, 2, 2, 3, 3, 3]);
  assert.deepEqual(callsOf(packed, 3), [[CALLS_URI, 6]]);
  assert.deepEqual(callsOf(packed, 10), [[CALLS_URI, 8]]);
  assert.deepEqual(callsOf(packed, 0), []);
  assert.equal(packed.siteLine.length, 3, 'no call, line 6 and line 8: each call site once');
  assert.equal(blockText(packed, 3), 'N20');
  assert.equal(packed.flags[22], FLAG_CONDITIONAL, 'N160 under the undecided IF is conditional');
  assert.equal(packed.flags[21] & FLAG_CONDITIONAL, 0);
});

test('an older answer packs as blocks of the previewed file, each run once', () => {
  const packed = packMoves(parsePreview(readFixture('demo_mill.preview.json')).moves, { previewed: 'file:///demo_mill.mpf' });
  assert.deepEqual(packed.files, ['file:///demo_mill.mpf']);
  assert.ok(packed.file.every((file) => file === 0) && packed.pass.every((pass) => pass === 0) && packed.stack.every((site) => site === 0));
  assert.deepEqual([...packed.outerLine], [...packed.line]);
  assert.equal(blockText(packed, 0), 'N30');
});

test('nested calls, assumed axes and main blocks are packed', () => {
  const packed = packMoves(
    [
      move(7, 'G1', {}, { X: 1 }, { file: 'C.SPF', stack: [{ file: 'A.MPF', line: 5 }, { file: 'B.SPF', line: 3 }], assumed: ['Y', 'Z'], block: ':40' }),
      move(8, 'G1', {}, { X: 2 }, { file: 'C.SPF', stack: [{ file: 'A.MPF', line: 5 }, { file: 'B.SPF', line: 4 }] }),
      move(9, 'G1', {}, { X: 3 }, { file: 'A.MPF', stack: [{ file: null, line: 6 }] }),
      move(2, 'G1', {}, { X: 4 }, { file: 'B.SPF', stack: [{ file: '/parts/A.MPF', line: 7 }] }),
    ],
    { previewed: 'file:///A.MPF', aliases: ['A.MPF'] },
  );
  assert.deepEqual(packed.files, ['file:///A.MPF', 'C.SPF', 'B.SPF']);
  assert.deepEqual(callsOf(packed, 0), [['file:///A.MPF', 5], ['B.SPF', 3]]);
  assert.deepEqual(callsOf(packed, 1), [['file:///A.MPF', 5], ['B.SPF', 4]]);
  assert.equal(packed.siteCaller[packed.stack[0]], packed.siteCaller[packed.stack[1]], 'one site for the shared outer call');
  assert.equal(packed.file[2], 0, 'the previewed file under its own name is file 0');
  assert.deepEqual([...packed.outerLine], [5, 5, 6, 7]);
  assert.deepEqual(callsOf(packed, 3), [['file:///A.MPF', 7]], 'the outermost call is in the previewed file, however it is spelt');
  assert.equal(packed.flags[0], (FLAG_ASSUMED_X << 1) | (FLAG_ASSUMED_X << 2) | FLAG_MAIN_BLOCK);
  assert.equal(blockText(packed, 0), ':40');
  assert.equal(blockText(packed, 1), '');
});

test('parts joined keep one file table and one table of call sites', () => {
  const whole = callsPart();
  // Three ranges: the first call (line 6), the second (line 8), the rest.
  const joined = concatPacked([callsPart([1, 6]), callsPart([7, 8]), callsPart([9, 19])]);
  assert.deepEqual(joined.files, whole.files);
  for (const name of ['line', 'file', 'outerLine', 'pass', 'block', 'flags'] as const) {
    assert.deepEqual([...joined[name]], [...whole[name]], name);
  }
  for (let i = 0; i < whole.count; i++) assert.deepEqual(callsOf(joined, i), callsOf(whole, i));
  assert.equal(joined.siteLine.length, 3);
  // A part that met a second called file first: its indices are translated.
  const other = packMoves([move(2, 'G1', {}, {}, { file: 'OTHER.SPF', stack: [{ file: null, line: 20 }] }),
    move(5, 'G1', {}, {}, { file: 'SLOT.SPF', stack: [{ file: null, line: 21 }] })],
  { previewed: CALLS_URI, key: (name) => `file:///work/${name}` });
  const three = concatPacked([whole, other]);
  assert.deepEqual(three.files, [CALLS_URI, 'file:///work/SLOT.SPF', 'file:///work/OTHER.SPF']);
  assert.deepEqual([...three.file.slice(23)], [2, 1]);
  assert.deepEqual(callsOf(three, 24), [[CALLS_URI, 21]]);
});

test('the file table and the call sites survive the way to the page', () => {
  const packed = callsPart();
  const revived = revivePacked(JSON.parse(JSON.stringify(packed)));
  assert.deepEqual(revived.files, packed.files);
  assert.ok(revived.flags instanceof Uint16Array && revived.siteCaller instanceof Uint32Array);
  assert.deepEqual([...revived.stack], [...packed.stack]);
  assert.deepEqual(callsOf(revived, 10), callsOf(packed, 10));
  assert.equal(revived.flags[22], FLAG_CONDITIONAL);
});
