import assert from 'node:assert/strict';
import { test } from 'node:test';
import { ToolpathLoader } from '../../src/core/loader';
import { describeProgramTime, formatDuration, formatProgramTime, parseProgramTime } from '../../src/core/machiningTime';
import type { ToPage } from '../../src/core/messages';
import { formatModalState, parseModalState } from '../../src/core/modalState';
import { parsePreview } from '../../src/core/preview';

const TIME = { total_s: 123.4, feed_s: 100, rapid_s: 20.9, dwell_s: 2.5, unknown_moves: 0 };

test('a program time is read from the server and rejected when malformed', () => {
  assert.deepEqual(parseProgramTime(TIME), { totalS: 123.4, feedS: 100, rapidS: 20.9, dwellS: 2.5, unknownMoves: 0 });
  assert.equal(parseProgramTime(null), null);
  assert.equal(parseProgramTime({ ...TIME, total_s: -1 }), null);
  assert.equal(parseProgramTime({ ...TIME, unknown_moves: 1.5 }), null);
  assert.equal(parseProgramTime({ ...TIME, feed_s: 'x' }), null);
});

test('durations read as seconds, minutes and hours; unknown moves make the total a lower bound', () => {
  assert.equal(formatDuration(9.4248), '9.4 s');
  assert.equal(formatDuration(123.4), '2 min 3 s');
  assert.equal(formatDuration(3723), '1 h 2 min 3 s');
  assert.equal(formatDuration(Number.NaN), '?');
  const time = parseProgramTime(TIME)!;
  assert.equal(formatProgramTime(time), '⏱ 2 min 3 s');
  assert.equal(formatProgramTime({ ...time, unknownMoves: 2 }), '⏱ ≥ 2 min 3 s');
  assert.equal(describeProgramTime(time), 'machining time 2 min 3 s, feed 1 min 40 s, rapid 20.9 s, dwell 2.5 s');
  assert.match(describeProgramTime({ ...time, unknownMoves: 3 }), /^machining time at least 2 min 3 s, .* \(3 moves of unknown time/);
});

test('the status bar text ends with the program time when the server gives one', () => {
  const state = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null, time: TIME })!;
  const status = formatModalState(state, 0);
  assert.equal(status.text, 'G90 G71 G17 G1 · ⏱ 2 min 3 s');
  assert.match(status.tooltip, /Program: machining time 2 min 3 s/);
  const older = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null })!;
  assert.equal(older.time, null);
  assert.equal(formatModalState(older, 0).text, 'G90 G71 G17 G1');
});

test('the preview gives the whole program time: program_time first, else time', () => {
  const whole = { total_s: 50, feed_s: 50, rapid_s: 0, dwell_s: 0, unknown_moves: 1 };
  const range = { ...whole, total_s: 10 };
  assert.equal(parsePreview({ moves: [], time: range, program_time: whole }).time?.totalS, 50);
  assert.equal(parsePreview({ moves: [], time: range }).time?.totalS, 10);
  assert.equal(parsePreview({ moves: [] }).time, null);
});

test('the loader hands the program time to the page when the load is complete', async () => {
  const messages: ToPage[] = [];
  const program_time = { total_s: 75, feed_s: 70, rapid_s: 5, dwell_s: 0, unknown_moves: 0 };
  const loader = new ToolpathLoader({
    executePreview: async () => ({ file: 'a.mpf', units: 'mm', moves: [], time: { ...program_time, total_s: 1 }, program_time }),
    post: (message) => messages.push(message),
    chunkLines: 2,
  });
  await loader.load({ uri: 'file:///a.mpf', title: 'a.mpf', lineCount: 5, plane: null });
  const done = messages[messages.length - 1];
  assert.equal(done.type, 'done');
  assert.equal(done.type === 'done' && done.time?.totalS, 75);
  const without: ToPage[] = [];
  await new ToolpathLoader({
    executePreview: async () => ({ file: 'a.mpf', units: 'mm', moves: [] }),
    post: (message) => without.push(message),
  }).load({ uri: 'file:///a.mpf', title: 'a.mpf', lineCount: 5, plane: null });
  assert.deepEqual(without[without.length - 1], { type: 'done', generation: 1 });
});
