// The program-rewriting commands: renumbering blocks and formatting, sent to the server as
// `workspace/executeCommand` `sinumerik.renumber` / `sinumerik.format`. The server edits the document
// with `workspace/applyEdit` and answers `{"applied": bool, "edits": number}`. This module decides
// what is asked (validation of the numbers, the remembered choice) and what the user is told.

export const RENUMBER_COMMAND = 'sinumerik.renumber';
export const FORMAT_COMMAND = 'sinumerik.format';

/** The largest block number the server writes (a signed 32-bit integer, like other NC integers). */
export const MAX_BLOCK_NUMBER = 2_147_483_647;

export type NumberingMode = 'keep' | 'all' | 'drop';

export const NUMBERING_MODES: readonly { mode: NumberingMode; label: string; detail: string }[] = [
  { mode: 'keep', label: 'Keep', detail: 'The blocks that have a number get the new numbers; the others stay without.' },
  { mode: 'all', label: 'All', detail: 'Every block with a statement or label gets a number.' },
  { mode: 'drop', label: 'Drop', detail: 'Numbers are removed, except on blocks that a jump targets, which are renumbered.' },
];

export interface RenumberChoice {
  start: number;
  step: number;
  mode: NumberingMode;
}

export const DEFAULT_RENUMBER_CHOICE: RenumberChoice = { start: 10, step: 10, mode: 'keep' };

/** The key under which the last choice is kept in the extension's global state. */
export const RENUMBER_CHOICE_KEY = 'sinumerik.renumber.lastChoice';

/**
 * Reads a block number typed by the user: `undefined` when it is valid, else the message to show
 * under the input box. The start may be 0; the step must be at least 1.
 */
export function blockNumberProblem(text: string, what: 'start' | 'step'): string | undefined {
  const trimmed = text.trim();
  if (!/^\d+$/.test(trimmed)) return `The ${what} must be a whole number, like 10.`;
  const value = Number(trimmed);
  if (what === 'step' && value < 1) return 'The step must be at least 1.';
  if (value > MAX_BLOCK_NUMBER) return `The ${what} must be at most ${MAX_BLOCK_NUMBER}.`;
  return undefined;
}

/** The number in a text that `blockNumberProblem` accepted. */
export function parseBlockNumber(text: string): number {
  return Number(text.trim());
}

function isNumber(value: unknown, what: 'start' | 'step'): value is number {
  return typeof value === 'number' && Number.isInteger(value) && blockNumberProblem(String(value), what) === undefined;
}

/** The remembered choice from the global state, or the defaults where a stored value is not usable. */
export function rememberedChoice(stored: unknown): RenumberChoice {
  const record = typeof stored === 'object' && stored !== null ? (stored as Record<string, unknown>) : {};
  const mode = NUMBERING_MODES.find((item) => item.mode === record.mode)?.mode;
  return {
    start: isNumber(record.start, 'start') ? record.start : DEFAULT_RENUMBER_CHOICE.start,
    step: isNumber(record.step, 'step') ? record.step : DEFAULT_RENUMBER_CHOICE.step,
    mode: mode ?? DEFAULT_RENUMBER_CHOICE.mode,
  };
}

/** The modes in the order the quick pick shows them: the remembered one first. */
export function modesInPickOrder(last: NumberingMode): typeof NUMBERING_MODES {
  return [...NUMBERING_MODES].sort((a, b) => Number(b.mode === last) - Number(a.mode === last));
}

export interface ExecuteCommandParams {
  command: string;
  arguments: unknown[];
}

export function renumberRequest(uri: string, choice: RenumberChoice): ExecuteCommandParams {
  return { command: RENUMBER_COMMAND, arguments: [{ uri, start: choice.start, step: choice.step, mode: choice.mode }] };
}

export function formatRequest(uri: string): ExecuteCommandParams {
  return { command: FORMAT_COMMAND, arguments: [{ uri }] };
}

/** What the user is told after the server answered: an information or an error message. */
export type Outcome = { kind: 'info' | 'error'; message: string };

/** The outcome of the server's answer `{"applied", "edits"}` to `what` ("Renumbering", "Formatting"). */
export function commandOutcome(what: string, answer: unknown): Outcome {
  const record = typeof answer === 'object' && answer !== null ? (answer as Record<string, unknown>) : {};
  const edits = record.edits;
  if (typeof record.applied !== 'boolean' || typeof edits !== 'number') {
    return { kind: 'error', message: `${what}: the language server gave an answer the extension does not understand: ${JSON.stringify(answer)}` };
  }
  if (edits === 0) return { kind: 'info', message: `${what}: nothing to change.` };
  if (!record.applied) return { kind: 'error', message: `${what}: the editor did not apply the changes (was the program edited meanwhile?).` };
  return { kind: 'info', message: `${what}: ${edits} ${edits === 1 ? 'change' : 'changes'} applied.` };
}

/** The message of a failed request (the server explains InvalidParams errors in their message). */
export function failureOutcome(what: string, error: unknown): Outcome {
  const message = typeof error === 'object' && error !== null && typeof (error as { message?: unknown }).message === 'string'
    ? (error as { message: string }).message
    : String(error);
  return { kind: 'error', message: `${what} failed: ${message}` };
}
