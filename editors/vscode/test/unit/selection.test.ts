import assert from 'node:assert/strict';
import { test } from 'node:test';
import { fileLabel, fileUri } from '../../src/core/files';
import { concatPacked, packMoves } from '../../src/core/packed';
import { parsePreview } from '../../src/core/preview';
import { assumedEntryState, callPath, moveNotes, moveOrigin } from '../../src/webview/describe';
import { project } from '../../src/webview/geometry';
import { fileIndexOf, movesCausedBy, passesOf, segmentsCausedBy } from '../../src/webview/selection';
import { move, readFixture } from './fixtures';

const CALLS_URI = 'file:///work/calls_mill.mpf';
const SLOT_URI = 'file:///work/SLOT.SPF';
const calls = () =>
  packMoves(parsePreview(readFixture('calls_mill.preview.json')).moves, {
    previewed: CALLS_URI, aliases: ['calls_mill.mpf'], key: (name) => fileUri(name, CALLS_URI),
  });

/** The moves a line causes, as "file line pass" for readable failures. */
function caused(file: string | undefined, line: number, packed = calls()): string[] {
  return movesCausedBy(packed, fileIndexOf(packed, file), line).map((m) => `${fileLabel(packed.files[packed.file[m]])} ${packed.line[m]} ${packed.pass[m]}`);
}

test('a call line causes every move of the program it calls, in every run of the call', () => {
  assert.deepEqual(caused(undefined, 6), ['SLOT.SPF 3 1', 'SLOT.SPF 4 1', 'SLOT.SPF 5 1'], 'N50 SLOT');
  assert.deepEqual(caused(undefined, 8), [
    'SLOT.SPF 3 2', 'SLOT.SPF 4 2', 'SLOT.SPF 5 2', 'SLOT.SPF 3 3', 'SLOT.SPF 4 3', 'SLOT.SPF 5 3',
  ], 'N70 SLOT P2: both runs, not the run of N50');
  assert.deepEqual(caused(undefined, 7), ['calls_mill.mpf 7 0'], 'a line without a call: its own move');
  assert.deepEqual(caused(undefined, 11), ['calls_mill.mpf 11 1', 'calls_mill.mpf 11 2', 'calls_mill.mpf 11 3'], 'every pass of a loop');
  assert.deepEqual(caused(undefined, 10), [], 'FOR itself moves nothing');
});

test('a line of a called program causes its moves in every run, in that file only', () => {
  assert.deepEqual(caused(SLOT_URI, 4), ['SLOT.SPF 4 1', 'SLOT.SPF 4 2', 'SLOT.SPF 4 3']);
  assert.deepEqual(caused(SLOT_URI, 7), [], 'line 7 of SLOT.SPF is not line 7 of the program');
  assert.equal(fileIndexOf(calls(), 'file:///work/OTHER.SPF'), -1);
  assert.deepEqual(caused('file:///work/OTHER.SPF', 4), [], 'a file the toolpath does not run through');
  assert.deepEqual(caused(CALLS_URI, 6).length, 3, 'the previewed file named by its URI');
});

test('a call in a called program causes the moves of the program it calls, at any depth', () => {
  const packed = packMoves([
    move(3, 'G1', {}, { X: 1 }, { file: 'B.SPF', stack: [{ file: null, line: 5 }] }),
    move(7, 'G1', {}, { X: 2 }, { file: 'C.SPF', stack: [{ file: null, line: 5 }, { file: 'B.SPF', line: 4 }] }),
    move(7, 'G1', {}, { X: 3 }, { file: 'C.SPF', stack: [{ file: null, line: 6 }, { file: 'B.SPF', line: 4 }] }),
    move(4, 'G1', {}, { X: 4 }, { file: 'D.SPF', stack: [{ file: null, line: 6 }, { file: 'B.SPF', line: 8 }] }),
  ], { previewed: 'file:///A.MPF' });
  assert.deepEqual(caused(undefined, 5, packed), ['B.SPF 3 0', 'C.SPF 7 0']);
  assert.deepEqual(caused('B.SPF', 4, packed), ['C.SPF 7 0', 'C.SPF 7 0'], 'the call in B.SPF, whichever line called B');
  assert.deepEqual(caused('C.SPF', 7, packed), ['C.SPF 7 0', 'C.SPF 7 0']);
  assert.deepEqual(caused(undefined, 6, packed), ['C.SPF 7 0', 'D.SPF 4 0']);
});

test('the selection holds across parts loaded range by range, and on drawn segments', () => {
  const part = (from: number, to: number) => {
    const moves = parsePreview(readFixture('calls_mill.preview.json')).moves.filter((m) => {
      const outer = m.stack.length ? m.stack[0].line : m.line;
      return outer >= from && outer <= to;
    });
    return packMoves(moves, { previewed: CALLS_URI, key: (name) => fileUri(name, CALLS_URI) });
  };
  const joined = concatPacked([part(1, 7), part(8, 8), part(9, 19)]);
  assert.deepEqual(caused(SLOT_URI, 4, joined), ['SLOT.SPF 4 1', 'SLOT.SPF 4 2', 'SLOT.SPF 4 3']);
  assert.equal(caused(undefined, 8, joined).length, 6);
  // In X/Y the Z moves of the slot are points: the first move (no start) and nothing else is hidden,
  // and line 8 draws its two cuts along X.
  const p = project(joined, 'G17');
  const segments = [...segmentsCausedBy(p, joined, 0, 8)];
  assert.equal(segments.length, 6);
  assert.deepEqual(segments.map((s) => [p.x0[s], p.x1[s]]).filter(([a, b]) => a !== b), [[10, 30], [30, 50]]);
});

test('the drawn segments of a line are the drawn moves it causes, for every line of every file', () => {
  const packed = packMoves([
    ...parsePreview(readFixture('calls_mill.preview.json')).moves,
    move(7, 'G1', { X: 0, Y: 0 }, { X: 2, Y: 0 }, { file: 'C.SPF', stack: [{ file: null, line: 8 }, { file: 'SLOT.SPF', line: 6 }] }),
  ], { previewed: CALLS_URI, key: (name) => fileUri(name, CALLS_URI) });
  const p = project(packed, 'G17');
  let selections = 0;
  packed.files.forEach((_, file) => {
    for (let line = 1; line <= 20; line++) {
      const drawn = [...segmentsCausedBy(p, packed, file, line)].map((s) => p.moveIndex[s]);
      const expected = movesCausedBy(packed, file, line).filter((m) => p.moveIndex.subarray(0, p.count).includes(m));
      assert.deepEqual(drawn, expected, `${packed.files[file]} line ${line}`);
      if (expected.length) selections++;
    }
  });
  assert.equal(selections, 14, 'lines with drawn moves: 5 to 9, 11 to 13 and 17; SLOT.SPF 3 to 6 (6 calls C.SPF); C.SPF 7');
  assert.equal(segmentsCausedBy(p, packed, 0, 8).length, 7, 'line 8: two runs of SLOT.SPF and the move of C.SPF it calls');
});

test('a move is described by its block, its pass of all passes, its file and line, and its calls', () => {
  const packed = calls();
  const third = 10; // SLOT.SPF line 4 (N20) in its third run, called on line 8
  assert.equal(passesOf(packed, third), 3);
  assert.equal(moveOrigin(packed, third, 3), 'N20, pass 3 of 3, SLOT.SPF line 4');
  assert.equal(callPath(packed, third), 'called at calls_mill.mpf line 8');
  assert.equal(moveOrigin(packed, 1, passesOf(packed, 1)), 'N40, line 5', 'a block of the previewed file that runs once');
  assert.equal(callPath(packed, 1), '');
  const loop = packed.line.findIndex((line, m) => line === 12 && packed.pass[m] === 2);
  assert.equal(moveOrigin(packed, loop, passesOf(packed, loop)), 'N110, pass 2 of 3, line 12');
  assert.deepEqual(moveNotes(packed, 22), ['conditional: on a way whose condition the analysis could not decide']);
  assert.deepEqual(moveNotes(packed, 21), []);
  // Line 3 runs twice in the program and three times in SLOT.SPF: each counts its own passes.
  const twice = packMoves([1, 2, 3].map((pass) => move(3, 'G1', {}, {}, { pass, file: 'SLOT.SPF', stack: [{ file: null, line: 9 }] }))
    .concat([1, 2].map((pass) => move(3, 'G1', {}, {}, { pass }))));
  assert.deepEqual([0, 3].map((m) => passesOf(twice, m)), [3, 2]);
  const assumed = packMoves([move(3, 'G1', {}, { X: 1 }, { assumed: ['X', 'Z'] })]);
  assert.deepEqual(moveNotes(assumed, 0), ['assumed: X Z rest on the assumed entry state']);
  assert.equal(assumedEntryState({ units: 'G71', distance: 'G90', plane: 'G17' }), 'entry state assumed: G71 G90 G17');
  assert.equal(assumedEntryState({}), '');
});

test('file names become URIs relative to the previewed file, and are shown by their last part', () => {
  assert.equal(fileUri('SLOT.SPF', CALLS_URI), SLOT_URI);
  assert.equal(fileUri('../cycles/CYC 1.SPF', 'file:///work/parts/a.mpf'), 'file:///work/cycles/CYC%201.SPF');
  assert.equal(fileUri('/work/SLOT.SPF', 'anything'), SLOT_URI);
  assert.equal(fileUri('C:\\work\\SLOT.SPF', 'file:///c%3A/work/a.mpf'), 'file:///C:/work/SLOT.SPF');
  assert.equal(fileUri('file:///work/SLOT.SPF', 'x'), SLOT_URI, 'a URI stays');
  assert.equal(fileUri('SLOT.SPF', 'untitled:Untitled-1'), 'SLOT.SPF', 'no folder to start from: the name stays');
  assert.equal(fileLabel('file:///work/a%20b/SLOT.SPF'), 'SLOT.SPF');
  assert.equal(fileLabel('C:\\work\\SUB.SPF'), 'SUB.SPF');
});
