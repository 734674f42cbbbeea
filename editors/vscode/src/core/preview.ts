// The answer of the server's `sinumerik.endpointPreview` command (the same JSON as
// `sinumerik-lsp preview`), read defensively: a malformed answer is an error with a clear message,
// never a picture with invented numbers.

/** Axis name to value; an axis that is missing is unknown. */
export type AxisValues = Record<string, number>;

export interface PreviewArc {
  centre: AxisValues;
  radius: number;
  clockwise: boolean;
  /** Opening angle in degrees, 0 to 360. */
  sweep: number;
}

export interface PreviewMove {
  /** 1-based line of the block. */
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
}

export interface PreviewResult {
  file: string;
  units: string;
  moves: PreviewMove[];
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

function moveOf(value: unknown, index: number): PreviewMove {
  const where = `moves[${index}]`;
  if (!isObject(value)) fail(where, 'expected an object');
  const line = value.line;
  if (typeof line !== 'number' || !Number.isInteger(line) || line < 1) fail(where, 'line is not a positive integer');
  const motion = value.motion;
  if (typeof motion !== 'string') fail(where, 'motion is not a string');
  const block = typeof value.block === 'string' ? value.block : null;
  const feed = typeof value.feed === 'number' && Number.isFinite(value.feed) ? value.feed : null;
  const uncertainRaw = value.uncertain ?? [];
  if (!Array.isArray(uncertainRaw) || uncertainRaw.some((axis) => typeof axis !== 'string')) {
    fail(where, 'uncertain is not a list of axis names');
  }
  return {
    line,
    block,
    motion,
    start: axisValues(value.start ?? {}, `${where}.start`),
    end: axisValues(value.end, `${where}.end`),
    mcs: value.mcs === null || value.mcs === undefined ? null : axisValues(value.mcs, `${where}.mcs`),
    arc: arcOf(value.arc, `${where}.arc`),
    feed,
    uncertain: (uncertainRaw as string[]).map((axis) => axis.toUpperCase()),
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
  };
}
