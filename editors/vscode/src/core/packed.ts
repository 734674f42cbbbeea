// The toolpath in a compact form of typed arrays: what the extension sends to the webview. A million
// moves take about 60 MB this way instead of hundreds as objects, and arrays travel to the webview
// without being turned into JSON.

import type { PreviewMove } from './preview';

/** The axes the picture can show; a plane picks two of them. */
export const AXES = ['X', 'Y', 'Z'] as const;

export const MOTIONS = ['G0', 'G1', 'G2', 'G3', 'CIP', 'CT', 'other'] as const;
export type Motion = (typeof MOTIONS)[number];

export const FLAG_RAPID = 1;
export const FLAG_CLOCKWISE = 2;
/** Bits 2, 3, 4: X, Y, Z are named uncertain. */
export const FLAG_UNCERTAIN_X = 4;

export interface PackedToolpath {
  count: number;
  /** 1-based line of each move, ascending. */
  line: Uint32Array;
  motion: Uint8Array;
  flags: Uint8Array;
  /** X, Y, Z of each move's start and end; NaN where unknown or not programmed. */
  start: Float64Array;
  end: Float64Array;
  feed: Float64Array;
  /** Index into the arc arrays, or -1. */
  arcOf: Int32Array;
  arcCentre: Float64Array;
  arcRadius: Float64Array;
  arcSweep: Float64Array;
}

function motionIndex(motion: string): number {
  const upper = motion.toUpperCase();
  const normal = upper === 'G00' ? 'G0' : upper === 'G01' ? 'G1' : upper === 'G02' ? 'G2' : upper === 'G03' ? 'G3' : upper;
  const index = MOTIONS.indexOf(normal as Motion);
  return index < 0 ? MOTIONS.length - 1 : index;
}

/** Arrays for `count` moves and `arcs` arcs; moves have no arc until one is set. */
export function allocatePacked(count: number, arcs: number): PackedToolpath {
  return {
    count,
    line: new Uint32Array(count),
    motion: new Uint8Array(count),
    flags: new Uint8Array(count),
    start: new Float64Array(count * 3),
    end: new Float64Array(count * 3),
    feed: new Float64Array(count),
    arcOf: new Int32Array(count).fill(-1),
    arcCentre: new Float64Array(arcs * 3),
    arcRadius: new Float64Array(arcs),
    arcSweep: new Float64Array(arcs),
  };
}

export function emptyPacked(): PackedToolpath {
  return allocatePacked(0, 0);
}

export function packMoves(moves: readonly PreviewMove[]): PackedToolpath {
  const count = moves.length;
  const arcCount = moves.reduce((total, move) => total + (move.arc ? 1 : 0), 0);
  const packed = allocatePacked(count, arcCount);
  let arcIndex = 0;
  moves.forEach((move, index) => {
    packed.line[index] = move.line;
    packed.motion[index] = motionIndex(move.motion);
    let flags = packed.motion[index] === 0 ? FLAG_RAPID : 0;
    AXES.forEach((axis, k) => {
      packed.start[index * 3 + k] = move.start[axis] ?? NaN;
      packed.end[index * 3 + k] = move.end[axis] ?? NaN;
      if (move.uncertain.includes(axis)) flags |= FLAG_UNCERTAIN_X << k;
    });
    packed.feed[index] = move.feed ?? NaN;
    if (move.arc) {
      if (move.arc.clockwise) flags |= FLAG_CLOCKWISE;
      AXES.forEach((axis, k) => {
        packed.arcCentre[arcIndex * 3 + k] = move.arc!.centre[axis] ?? NaN;
      });
      packed.arcRadius[arcIndex] = move.arc.radius;
      packed.arcSweep[arcIndex] = move.arc.sweep;
      packed.arcOf[index] = arcIndex++;
    }
    packed.flags[index] = flags;
  });
  return packed;
}

/** Joins parts fetched one after the other into one toolpath. */
export function concatPacked(parts: readonly PackedToolpath[]): PackedToolpath {
  if (parts.length === 1) return parts[0];
  const count = parts.reduce((total, part) => total + part.count, 0);
  const arcs = parts.reduce((total, part) => total + part.arcRadius.length, 0);
  const out = allocatePacked(count, arcs);
  let at = 0;
  let arcAt = 0;
  for (const part of parts) {
    out.line.set(part.line, at);
    out.motion.set(part.motion, at);
    out.flags.set(part.flags, at);
    out.start.set(part.start, at * 3);
    out.end.set(part.end, at * 3);
    out.feed.set(part.feed, at);
    for (let i = 0; i < part.count; i++) {
      out.arcOf[at + i] = part.arcOf[i] < 0 ? -1 : part.arcOf[i] + arcAt;
    }
    out.arcCentre.set(part.arcCentre, arcAt * 3);
    out.arcRadius.set(part.arcRadius, arcAt);
    out.arcSweep.set(part.arcSweep, arcAt);
    at += part.count;
    arcAt += part.arcRadius.length;
  }
  return out;
}

type TypedArrayConstructor = Uint32ArrayConstructor | Uint8ArrayConstructor | Float64ArrayConstructor | Int32ArrayConstructor;

const FIELDS: [keyof PackedToolpath, TypedArrayConstructor][] = [
  ['line', Uint32Array], ['motion', Uint8Array], ['flags', Uint8Array], ['start', Float64Array], ['end', Float64Array],
  ['feed', Float64Array], ['arcOf', Int32Array], ['arcCentre', Float64Array], ['arcRadius', Float64Array], ['arcSweep', Float64Array],
];

/** The toolpath as it arrived in the page: typed arrays stay as they are; arrays that a message
 * channel turned into plain arrays or index-keyed objects become typed arrays again. */
export function revivePacked(value: unknown): PackedToolpath {
  const record = value as Record<string, unknown>;
  const out = { count: Number(record.count) || 0 } as PackedToolpath;
  for (const [name, Type] of FIELDS) {
    const field = record[name];
    if (field instanceof Type) {
      (out as unknown as Record<string, unknown>)[name] = field;
      continue;
    }
    let values: unknown[] = [];
    if (ArrayBuffer.isView(field)) values = Array.from(field as unknown as ArrayLike<unknown>);
    else if (Array.isArray(field)) values = field;
    else if (field && typeof field === 'object') values = Object.values(field);
    const array = new Type(values.length);
    // JSON writes NaN (unknown) as null, which must not become 0.
    values.forEach((item, index) => (array[index] = typeof item === 'number' ? item : NaN));
    (out as unknown as Record<string, unknown>)[name] = array;
  }
  return out;
}
