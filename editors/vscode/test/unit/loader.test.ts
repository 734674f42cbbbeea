import assert from 'node:assert/strict';
import { test } from 'node:test';
import { chunkRanges, movesInRange } from '../../src/core/chunks';
import { ToolpathLoader } from '../../src/core/loader';
import type { ToPage } from '../../src/core/messages';
import { move } from './fixtures';

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
