import assert from 'node:assert/strict';
import { test } from 'node:test';
import {
  blockNumberProblem,
  commandOutcome,
  DEFAULT_RENUMBER_CHOICE,
  failureOutcome,
  formatRequest,
  MAX_BLOCK_NUMBER,
  modesInPickOrder,
  parseBlockNumber,
  rememberedChoice,
  renumberRequest,
} from '../../src/core/programCommands';

test('block numbers typed for renumbering are whole numbers within what a block number holds', () => {
  for (const text of ['0', '10', ' 25 ', String(MAX_BLOCK_NUMBER)]) assert.equal(blockNumberProblem(text, 'start'), undefined, text);
  assert.equal(parseBlockNumber(' 25 '), 25);
  for (const text of ['', 'ten', '-5', '1.5', '1e3', '10 20', '+3', '0x10']) {
    assert.match(blockNumberProblem(text, 'start') ?? '', /start must be a whole number/, `start "${text}"`);
  }
  assert.match(blockNumberProblem(String(MAX_BLOCK_NUMBER + 1), 'start') ?? '', /at most 2147483647/);
  assert.equal(blockNumberProblem('1', 'step'), undefined);
  assert.match(blockNumberProblem('0', 'step') ?? '', /step must be at least 1/);
  assert.match(blockNumberProblem('-1', 'step') ?? '', /step must be a whole number/);
  assert.match(blockNumberProblem('99999999999', 'step') ?? '', /step must be at most/);
});

test('the remembered renumbering choice is used where it is valid, the defaults elsewhere', () => {
  assert.deepEqual(DEFAULT_RENUMBER_CHOICE, { start: 10, step: 10, mode: 'keep' });
  assert.deepEqual(rememberedChoice(undefined), DEFAULT_RENUMBER_CHOICE);
  assert.deepEqual(rememberedChoice({ start: 100, step: 5, mode: 'drop' }), { start: 100, step: 5, mode: 'drop' });
  assert.deepEqual(rememberedChoice({ start: 0, step: 1, mode: 'all' }), { start: 0, step: 1, mode: 'all' });
  assert.deepEqual(rememberedChoice({ start: -1, step: 0, mode: 'some' }), DEFAULT_RENUMBER_CHOICE);
  assert.deepEqual(rememberedChoice({ start: 2.5, step: '5', mode: 3 }), DEFAULT_RENUMBER_CHOICE);
  assert.deepEqual(rememberedChoice('keep'), DEFAULT_RENUMBER_CHOICE);
});

test('the quick pick offers the remembered mode first and every mode once', () => {
  assert.deepEqual(modesInPickOrder('keep').map((item) => item.mode), ['keep', 'all', 'drop']);
  assert.deepEqual(modesInPickOrder('drop').map((item) => item.mode), ['drop', 'keep', 'all']);
  assert.deepEqual(modesInPickOrder('all').map((item) => item.mode), ['all', 'keep', 'drop']);
});

test('the requests carry the server command and its one argument object', () => {
  assert.deepEqual(renumberRequest('file:///p/a.mpf', { start: 100, step: 5, mode: 'all' }), {
    command: 'sinumerik.renumber',
    arguments: [{ uri: 'file:///p/a.mpf', start: 100, step: 5, mode: 'all' }],
  });
  assert.deepEqual(formatRequest('file:///p/a.mpf'), { command: 'sinumerik.format', arguments: [{ uri: 'file:///p/a.mpf' }] });
});

test('the answer of the server becomes a message: changes, nothing to do, not applied, not understood, refused', () => {
  assert.deepEqual(commandOutcome('Formatting', { applied: true, edits: 3 }), { kind: 'info', message: 'Formatting: 3 changes applied.' });
  assert.deepEqual(commandOutcome('Formatting', { applied: true, edits: 1 }), { kind: 'info', message: 'Formatting: 1 change applied.' });
  assert.deepEqual(commandOutcome('Renumbering', { applied: false, edits: 0 }), { kind: 'info', message: 'Renumbering: nothing to change.' });
  const refused = commandOutcome('Renumbering', { applied: false, edits: 4 });
  assert.equal(refused.kind, 'error');
  assert.match(refused.message, /did not apply/);
  assert.equal(commandOutcome('Formatting', null).kind, 'error');
  assert.equal(commandOutcome('Formatting', { applied: 'yes', edits: 2 }).kind, 'error');
  const failure = failureOutcome('Renumbering', { code: -32602, message: 'line 4: the jump to N30 has no target now' });
  assert.deepEqual(failure, { kind: 'error', message: 'Renumbering failed: line 4: the jump to N30 has no target now' });
  assert.equal(failureOutcome('Formatting', 'broken pipe').message, 'Formatting failed: broken pipe');
});
