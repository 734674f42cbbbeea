// The answer of the server's `sinumerik.endpointPreview` command (the same JSON as
// `sinumerik-lsp preview`), read defensively: a malformed answer is an error with a clear message,
// never a picture with invented numbers. The moves come in the order the control executes them;
// the fields that say where a move comes from (pass, file, stack, assumed, conditional) are
// optional, so that the answer of an older server that lists each block once reads the same; so are
// those that say what made a move (inserted, cycle) and its time.

import { parseProgramTime, type ProgramTime } from './machiningTime';

/** Axis name to value; an axis that is missing is unknown. */
export type AxisValues = Record<string, number>;

export interface PreviewArc {
  centre: AxisValues;
  radius: number;
  clockwise: boolean;
  /** Opening angle in degrees, 0 to 360. */
  sweep: number;
}

/** A call that led to a move: the calling block's 1-based line in `file`. */
export interface PreviewCallSite {
  /** The calling program's file (path or URI); null when the server left it out (the previewed file). */
  file: string | null;
  line: number;
}

export interface PreviewMove {
  /** 1-based line of the block in `file` (in the previewed file when `file` is null). */
  line: number;
  block: string | null;
  motion: string;
  start: AxisValues;
  end: AxisValues;
  mcs: AxisValues | null;
  arc: PreviewArc | null;
  feed: number | null;
  /** Axes whose value is unknown or may not be the control's (after labels, jumps, loops). */
  uncertain: string[];
  /** The pass (1, 2, 3, ...) of a block that runs more than once; null when it runs once. */
  pass: number | null;
  /** The file of the called program that made the move; null for the previewed file. */
  file: string | null;
  /** The calls that led to the move, outermost first; empty for the previewed file's own blocks. */
  stack: PreviewCallSite[];
  /** Axes whose value rests on an assumed entry state. */
  assumed: string[];
  /** The move is on a way whose condition the analysis could not decide. */
  conditional: boolean;
  /** A rounding or chamfer the control inserts at a corner (`RND`, `CHF`, `CHR`; the server may name
   * others later); null for a programmed move. It has the line of the block that programs it. */
  inserted: string | null;
  /** The standard cycle or hole pattern that made the move (`CYCLE81`, `HOLES1`, ...); null otherwise. */
  cycle: string | null;
  /** The move's machining time in seconds (`time_s`); null when unknown or when the server has no times. */
  time: number | null;
}

export interface PreviewResult {
  file: string;
  units: string;
  moves: PreviewMove[];
  /** What the analysis assumed about the entry state (e.g. units: "G71"); empty when nothing. */
  assumed: Record<string, string>;
  /** The machining time of the whole program: the server's `program_time`, else `time` (the CLI's
   * answer, which is the whole program); null when the answer has neither. */
  time: ProgramTime | null;
}

export class PreviewFormatError extends Error {}

function fail(where: string, what: string): never {
  throw new PreviewFormatError(`endpoint preview: ${where}: ${what}`);
}

function isObject(value: unknown): value is Record<string, unknown> {
  return typeof value === 'object' && value !== null && !Array.isArray(value);
}

function axisValues(value: unknown, where: string): AxisValues {
  if (!isObject(value)) fail(where, 'expected an object of axis values');
  const out: AxisValues = {};
  for (const [axis, number] of Object.entries(value)) {
    if (typeof number !== 'number' || !Number.isFinite(number)) {
      fail(where, `axis ${axis} is not a finite number`);
    }
    out[axis.toUpperCase()] = number;
  }
  return out;
}

function arcOf(value: unknown, where: string): PreviewArc | null {
  if (value === null || value === undefined) return null;
  if (!isObject(value)) fail(where, 'expected an arc object or null');
  const radius = value.radius;
  const sweep = value.sweep;
  if (typeof radius !== 'number' || !(radius > 0) || !Number.isFinite(radius)) {
    fail(where, 'arc radius is not a positive number');
  }
  if (typeof sweep !== 'number' || !Number.isFinite(sweep)) fail(where, 'arc sweep is not a number');
  // The direction is `clockwise: bool`; `direction: "cw" | "ccw"` is accepted as well.
  let clockwise: boolean;
  if (typeof value.clockwise === 'boolean') {
    clockwise = value.clockwise;
  } else if (value.direction === 'cw' || value.direction === 'ccw') {
    clockwise = value.direction === 'cw';
  } else {
    fail(where, 'arc has neither `clockwise` nor `direction`');
  }
  return { centre: axisValues(value.centre, `${where}.centre`), radius, clockwise, sweep };
}

function axisNames(value: unknown, where: string, field: string): string[] {
  const names = value ?? [];
  if (!Array.isArray(names) || names.some((axis) => typeof axis !== 'string')) {
    fail(where, `${field} is not a list of axis names`);
  }
  return (names as string[]).map((axis) => axis.toUpperCase());
}

function isPositiveInteger(value: unknown): value is number {
  return typeof value === 'number' && Number.isInteger(value) && value >= 1;
}

function optionalFile(value: unknown, where: string): string | null {
  if (value === null || value === undefined) return null;
  if (typeof value !== 'string') fail(where, 'file is not a string');
  return value;
}

function stackOf(value: unknown, where: string): PreviewCallSite[] {
  if (value === null || value === undefined) return [];
  if (!Array.isArray(value)) fail(where, 'stack is not a list of call sites');
  return value.map((site, depth) => {
    const at = `${where}.stack[${depth}]`;
    if (!isObject(site)) fail(at, 'expected an object with file and line');
    if (!isPositiveInteger(site.line)) fail(at, 'line is not a positive integer');
    return { file: optionalFile(site.file, at), line: site.line };
  });
}

function entryState(value: unknown): Record<string, string> {
  if (value === null || value === undefined) return {};
  if (!isObject(value)) fail('answer', 'assumed is not an object');
  const out: Record<string, string> = {};
  for (const [name, setting] of Object.entries(value)) {
    if (typeof setting !== 'string') fail('answer', `assumed ${name} is not a string`);
    out[name] = setting;
  }
  return out;
}

function optionalName(value: unknown, where: string, field: string): string | null {
  if (value === null || value === undefined) return null;
  if (typeof value !== 'string' || value === '') fail(where, `${field} is not a name`);
  return value.toUpperCase();
}

function optionalSeconds(value: unknown, where: string): number | null {
  if (value === null || value === undefined) return null;
  if (typeof value !== 'number' || !Number.isFinite(value) || value < 0) fail(where, 'time_s is not a number of seconds');
  return value;
}

function moveOf(value: unknown, index: number): PreviewMove {
  const where = `moves[${index}]`;
  if (!isObject(value)) fail(where, 'expected an object');
  const line = value.line;
  if (typeof line !== 'number' || !Number.isInteger(line) || line < 1) fail(where, 'line is not a positive integer');
  const motion = value.motion;
  if (typeof motion !== 'string') fail(where, 'motion is not a string');
  const block = typeof value.block === 'string' ? value.block : null;
  const feed = typeof value.feed === 'number' && Number.isFinite(value.feed) ? value.feed : null;
  const pass = value.pass ?? null;
  if (pass !== null && !isPositiveInteger(pass)) fail(where, 'pass is not a positive integer');
  const conditional = value.conditional ?? false;
  if (typeof conditional !== 'boolean') fail(where, 'conditional is not true or false');
  return {
    line,
    block,
    motion,
    start: axisValues(value.start ?? {}, `${where}.start`),
    end: axisValues(value.end, `${where}.end`),
    mcs: value.mcs === null || value.mcs === undefined ? null : axisValues(value.mcs, `${where}.mcs`),
    arc: arcOf(value.arc, `${where}.arc`),
    feed,
    uncertain: axisNames(value.uncertain, where, 'uncertain'),
    pass,
    file: optionalFile(value.file, where),
    stack: stackOf(value.stack, where),
    assumed: axisNames(value.assumed, where, 'assumed'),
    conditional,
    inserted: optionalName(value.inserted, where, 'inserted'),
    cycle: optionalName(value.cycle, where, 'cycle'),
    time: optionalSeconds(value.time_s, where),
  };
}

/** Reads the command's answer; throws PreviewFormatError naming the first thing that is wrong. */
export function parsePreview(value: unknown): PreviewResult {
  if (!isObject(value)) fail('answer', 'expected an object');
  if (!Array.isArray(value.moves)) fail('answer', 'has no list of moves');
  const moves = value.moves.map(moveOf);
  return {
    file: typeof value.file === 'string' ? value.file : '',
    units: typeof value.units === 'string' ? value.units : 'mm',
    moves,
    assumed: entryState(value.assumed),
    time: parseProgramTime(value.program_time) ?? parseProgramTime(value.time),
  };
}

/** The line of the previewed file that causes a move: the outermost call's, or the move's own. */
export function outermostLine(move: Pick<PreviewMove, 'line' | 'stack'>): number {
  return move.stack.length ? move.stack[0].line : move.line;
}
