import assert from 'node:assert/strict';
import { test } from 'node:test';
import { chunkRanges, movesInRange } from '../../src/core/chunks';
import { ToolpathLoader } from '../../src/core/loader';
import type { ToPage } from '../../src/core/messages';
import { concatPacked } from '../../src/core/packed';
import { move, readFixture } from './fixtures';

test('ranges cover every line once', () => {
  assert.deepEqual(chunkRanges(10, 4), [{ start: 0, end: 4 }, { start: 4, end: 8 }, { start: 8, end: 10 }]);
  assert.deepEqual(chunkRanges(0, 4), [{ start: 0, end: 1 }]);
  assert.equal(chunkRanges(1_000_000).length, 40);
});

test('an inclusive end line does not give a move twice; a server that ignores ranges is noticed', () => {
  const moves = [move(4, 'G1', {}, {}), move(5, 'G1', {}, {}), move(9, 'G1', {}, {})];
  // Range [3, 4): line 4 (0-based 3) is inside, line 5 (0-based 4) is the inclusive end's extra.
  assert.deepEqual(movesInRange(moves.slice(0, 2), { start: 3, end: 4 }), { moves: [moves[0]], wholeProgram: false });
  assert.equal(movesInRange(moves, { start: 3, end: 4 }).wholeProgram, true);
});

/** A fake server: 1-based moves on every line from 2 to `lines`, answering ranges with an inclusive end. */
function fakeServer(lines: number, calls: unknown[]) {
  return async (args: unknown[]) => {
    calls.push(args[0]);
    const { startLine, endLine } = args[0] as { startLine: number; endLine: number };
    const moves = [];
    for (let line = Math.max(startLine + 1, 2); line <= Math.min(endLine + 1, lines); line++) {
      moves.push(move(line, 'G1', { X: line - 1 }, { X: line }));
    }
    return { file: 'a.mpf', units: 'inch', moves };
  };
}

test('a program is loaded range by range, each move once, in order', async () => {
  const calls: unknown[] = [];
  const messages: ToPage[] = [];
  const loader = new ToolpathLoader({ executePreview: fakeServer(10, calls), post: (m) => messages.push(m), chunkLines: 4 });
  await loader.load({ uri: 'file:///a.mpf', title: 'a.mpf', lineCount: 10, plane: null });
  assert.deepEqual(calls, [
    { uri: 'file:///a.mpf', startLine: 0, endLine: 4 },
    { uri: 'file:///a.mpf', startLine: 4, endLine: 8 },
    { uri: 'file:///a.mpf', startLine: 8, endLine: 10 },
  ]);
  const lines = messages.flatMap((m) => (m.type === 'append' ? [...m.packed.line] : []));
  assert.deepEqual(lines, [2, 3, 4, 5, 6, 7, 8, 9, 10]);
  assert.deepEqual(messages.map((m) => m.type), ['reset', 'reset', 'append', 'append', 'append', 'done']);
  const resets = messages.filter((m) => m.type === 'reset');
  assert.equal(resets[1].type === 'reset' && resets[1].units, 'inch', 'the units come with the first answer');
});

test('an edit during a load makes the older load stop; an error is shown with its reason', async () => {
  const messages: ToPage[] = [];
  let release: () => void = () => undefined;
  const slow = new Promise<void>((resolve) => (release = resolve));
  let first = true;
  const loader = new ToolpathLoader({
    executePreview: async (args) => {
      if (first) {
        first = false;
        await slow;
      }
      return fakeServer(3, [])(args);
    },
    post: (m) => messages.push(m),
  });
  const older = loader.load({ uri: 'u', title: 't', lineCount: 3, plane: null });
  const newer = loader.load({ uri: 'u', title: 't', lineCount: 3, plane: null });
  await newer;
  release();
  await older;
  const generations = new Set(messages.filter((m) => m.type === 'append').map((m) => (m as { generation: number }).generation));
  assert.deepEqual([...generations], [2], 'only the newer load appends');

  const failing = new ToolpathLoader({ executePreview: async () => ({ moves: 'no' }), post: (m) => messages.push(m) });
  await failing.load({ uri: 'u', title: 't', lineCount: 3, plane: null });
  const error = messages[messages.length - 1];
  assert.equal(error.type, 'error');
  assert.match((error as { message: string }).message, /toolpath could not be read: endpoint preview: answer: has no list of moves/);
});

test('a range keeps the moves whose outermost line is in it, wherever the lines of the called program are', () => {
  const call = [{ file: null, line: 8 }];
  const moves = [move(7, 'G1', {}, {}), move(3, 'G1', {}, {}, { file: 'SLOT.SPF', stack: call }), move(40, 'G1', {}, {}, { file: 'SLOT.SPF', stack: call })];
  assert.deepEqual(movesInRange(moves, { start: 7, end: 8 }), { moves: moves.slice(1), wholeProgram: false }, 'lines 3 and 40 of SLOT.SPF come from line 8');
  assert.deepEqual(movesInRange(moves, { start: 0, end: 7 }), { moves: [moves[0]], wholeProgram: false });
});

/** A server of the calls fixture: the moves whose outermost line is in the range (end inclusive). */
function callsServer(answer: Record<string, unknown> = {}) {
  const whole = readFixture('calls_mill.preview.json') as { moves: { line: number; stack?: { line: number }[] }[] };
  return async (args: unknown[]) => {
    const { startLine, endLine } = args[0] as { startLine: number; endLine: number };
    const outer = (m: (typeof whole.moves)[number]) => (m.stack?.length ? m.stack[0].line : m.line) - 1;
    return { ...whole, ...answer, moves: whole.moves.filter((m) => outer(m) >= startLine && outer(m) <= endLine) };
  };
}

test('a program with calls is loaded range by range; the loader knows the called files', async () => {
  const messages: ToPage[] = [];
  const loader = new ToolpathLoader({ executePreview: callsServer(), post: (m) => messages.push(m), chunkLines: 4 });
  const uri = 'file:///work/calls_mill.mpf';
  assert.equal(loader.isCalledFile('file:///work/SLOT.SPF'), false);
  await loader.load({ uri, title: 'calls_mill.mpf', lineCount: 19, plane: null });
  const parts = messages.flatMap((m) => (m.type === 'append' ? [m.packed] : []));
  assert.equal(parts.length, 5);
  const joined = concatPacked(parts);
  assert.equal(joined.count, 23, 'every move once');
  assert.deepEqual(joined.files, [uri, 'file:///work/SLOT.SPF'], 'SLOT.SPF, named relative to the program, becomes a URI');
  assert.deepEqual([...joined.outerLine.slice(0, 12)], [4, 5, 6, 6, 6, 7, 8, 8, 8, 8, 8, 8]);
  assert.deepEqual(messages.filter((m) => m.type === 'reset').length, 1, 'millimetres and nothing assumed: one reset');
  assert.equal(loader.isCalledFile('file:///work/SLOT.SPF'), true);
  assert.equal(loader.isCalledFile(uri), false, 'the previewed file is not a called one');
  assert.equal(loader.isCalledFile('file:///work/OTHER.SPF'), false);
  await loader.load({ uri: 'file:///work/other.mpf', title: 'other.mpf', lineCount: 1, plane: null });
  assert.equal(loader.isCalledFile('file:///work/SLOT.SPF'), false, 'another program: SLOT.SPF is not in its toolpath');
});

test('the entry state assumed for a subprogram reaches the page with the first answer', async () => {
  const messages: ToPage[] = [];
  const assumed = { units: 'G71', distance: 'G90', plane: 'G17' };
  const loader = new ToolpathLoader({ executePreview: callsServer({ assumed }), post: (m) => messages.push(m), chunkLines: 4 });
  await loader.load({ uri: 'file:///work/calls_mill.mpf', title: 'calls_mill.mpf', lineCount: 19, plane: 'G17' });
  const resets = messages.filter((m) => m.type === 'reset');
  assert.equal(resets.length, 2);
  assert.deepEqual(resets[1], { type: 'reset', generation: 1, title: 'calls_mill.mpf', units: 'mm', plane: 'G17', assumed });
});
