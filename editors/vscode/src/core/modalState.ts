// The status-bar item: the modal state at the cursor from the server's `sinumerik/modalState`
// request, `{uri, line}` -> `{motion, plane, units, distance, diameter}` (each may be null: unknown),
// `diameterAxis` (whether the machine has a transverse axis, so that the diameter mode means anything),
// and `passes` when the state is that of the block's first execution in the program's run, and the
// whole program's machining time `time` (null from an older server).

import { describeProgramTime, formatProgramTime, parseProgramTime, type ProgramTime } from './machiningTime';

export interface ModalState {
  motion: string | null;
  plane: string | null;
  units: string | null;
  distance: string | null;
  diameter: string | null;
  /**
   * Whether the diameter mode belongs in the status bar: the machine has a transverse axis (a lathe).
   * A server older than `diameterAxis` says nothing, and then a diameter mode it reports is shown.
   */
  diameterAxis: boolean;
  /** How often the block runs when the state is its first pass's; null: the state in program order. */
  passes: number | null;
  /** The machining time of the whole program; null when the server does not say. */
  time: ProgramTime | null;
}

export const MODAL_STATE_REQUEST = 'sinumerik/modalState';

const FIELDS = ['distance', 'units', 'plane', 'motion', 'diameter'] as const;

export function parseModalState(value: unknown): ModalState | null {
  if (typeof value !== 'object' || value === null) return null;
  const record = value as Record<string, unknown>;
  const field = (name: string) => (typeof record[name] === 'string' && record[name] !== '' ? (record[name] as string) : null);
  return {
    motion: field('motion'),
    plane: field('plane'),
    units: field('units'),
    distance: field('distance'),
    diameter: field('diameter'),
    diameterAxis: typeof record.diameterAxis === 'boolean' ? record.diameterAxis : field('diameter') !== null,
    passes: typeof record.passes === 'number' && Number.isInteger(record.passes) && record.passes >= 0 ? record.passes : null,
    time: parseProgramTime(record.time),
  };
}

export interface StatusText {
  text: string;
  tooltip: string;
}

const NAMES: Record<(typeof FIELDS)[number], string> = {
  distance: 'dimensions (G90 absolute / G91 incremental)',
  units: 'units (G70/G700 inch, G71/G710 metric)',
  plane: 'working plane',
  motion: 'motion',
  diameter: 'diameter programming',
};

/**
 * `G90 G71 G17 G1` in the order a programmer reads a safety block; unknown fields show `?`. The
 * diameter mode follows on a lathe only: DIAMOF is the reset state of a mill too, where it means nothing.
 */
export function formatModalState(state: ModalState, line: number): StatusText {
  const shown = FIELDS.filter((name) => name !== 'diameter' || state.diameterAxis);
  const parts = shown.map((name) => state[name] ?? '?');
  const unknown = shown.filter((name) => state[name] === null);
  const lines = [`Modal state at line ${line + 1} (from the language server):`];
  for (const name of shown) lines.push(`${NAMES[name]}: ${state[name] ?? 'unknown'}`);
  if (unknown.length) lines.push('? = unknown here (inherited from a caller, or after a call or a jump)');
  let pass = '';
  if (state.passes === 0) {
    pass = ' · not run';
    lines.push('The program\'s run never reaches this block.');
  } else if (state.passes !== null && state.passes > 1) {
    pass = ` · pass 1 of ${state.passes}`;
    lines.push(`The block runs ${state.passes} times: this is the state of its first pass.`);
  }
  let time = '';
  if (state.time) {
    time = ` · ${formatProgramTime(state.time)}`;
    lines.push(`Program: ${describeProgramTime(state.time)}.`);
  }
  return { text: parts.join(' ') + pass + time, tooltip: lines.join('\n') };
}
