// The toolpath in a compact form of typed arrays: what the extension sends to the webview. A million
// moves take about 100 MB this way (96 bytes each, arcs apart) instead of hundreds as objects, and
// arrays travel to the webview without being turned into JSON.
//
// Moves are in the order the control executes them, so lines are not ascending: a loop repeats its
// lines and a call runs the lines of another file. Each move has its own line in its file (an index
// into `files`, 0 for the previewed file), the line of the previewed file that causes it (its
// outermost call, or its own line), its pass, and its call path: an index into a table of call
// sites, where each site names its file, its line and the site that called its program.
//
// What made a move costs no more than flag bits where it can: a rounding or chamfer the control
// inserts, a move of a cycle, a hole a drilling cycle makes along the tool axis. Only the cycle's
// name takes a byte per move (an index into a small table), and the time eight.

import { outermostLine, type PreviewCallSite, type PreviewMove } from './preview';

/** The axes the picture can show; a plane picks two of them. */
export const AXES = ['X', 'Y', 'Z'] as const;

export const MOTIONS = ['G0', 'G1', 'G2', 'G3', 'CIP', 'CT', 'other'] as const;
export type Motion = (typeof MOTIONS)[number];

export const FLAG_RAPID = 1;
export const FLAG_CLOCKWISE = 2;
/** Bits 2, 3, 4: X, Y, Z are named uncertain. */
export const FLAG_UNCERTAIN_X = 4;
/** Bits 5, 6, 7: the value of X, Y, Z rests on an assumed entry state. */
export const FLAG_ASSUMED_X = 32;
/** The move is on a way whose condition the analysis could not decide. */
export const FLAG_CONDITIONAL = 256;
/** The block number is a main block's (`:10`), not an `N` number. */
export const FLAG_MAIN_BLOCK = 512;
/** Bits 10 and 11: an element the control inserts at a corner; the two bits hold which (below). */
export const FLAG_INSERTED_MASK = 3 << 10;
export const FLAG_INSERTED_RND = 1 << 10;
export const FLAG_INSERTED_CHF = 2 << 10;
export const FLAG_INSERTED_CHR = 3 << 10;
/** The move is made by a standard cycle or hole pattern (its name: `cycleOf`). */
export const FLAG_CYCLE = 1 << 12;
/** Bits 13 and 14: the move drills a hole, along X, Y or Z (1, 2, 3; 0: not a hole). */
export const FLAG_HOLE_SHIFT = 13;
export const FLAG_HOLE_MASK = 3 << FLAG_HOLE_SHIFT;

const INSERTED_NAMES = ['', 'RND', 'CHF', 'CHR'] as const;

/** Which element the control inserted (`RND`, `CHF`, `CHR`), or '' for a programmed move. */
export function insertedName(flags: number): '' | 'RND' | 'CHF' | 'CHR' {
  return INSERTED_NAMES[(flags & FLAG_INSERTED_MASK) >> 10];
}

/** The axis (0, 1, 2 for X, Y, Z) along which a move drills a hole, or -1. */
export function holeAxis(flags: number): number {
  return ((flags & FLAG_HOLE_MASK) >> FLAG_HOLE_SHIFT) - 1;
}

/** Cycle names beyond this many in one toolpath keep their flag but lose their name. */
export const MAX_CYCLE_NAMES = 255;

export interface PackedToolpath {
  count: number;
  /** 1-based line of each move in its file. */
  line: Uint32Array;
  /** Index of each move's file into `files`; 0 is the previewed file. */
  file: Uint32Array;
  /** 1-based line of the previewed file that causes each move (its outermost call, or its own line). */
  outerLine: Uint32Array;
  /** The pass of a block that runs more than once (1, 2, ...); 0 when it runs once. */
  pass: Uint32Array;
  /** The block number plus one; 0 when the block has none. */
  block: Uint32Array;
  /** Index of each move's innermost call site; 0 (the empty call path) for the previewed file's blocks. */
  stack: Uint32Array;
  motion: Uint8Array;
  flags: Uint16Array;
  /** X, Y, Z of each move's start and end; NaN where unknown or not programmed. */
  start: Float64Array;
  end: Float64Array;
  feed: Float64Array;
  /** The machining time of each move in seconds; NaN where unknown. */
  time: Float64Array;
  /** Index of each move's cycle into `cycleNames`; 0 for none (or a name beyond MAX_CYCLE_NAMES). */
  cycleOf: Uint8Array;
  /** The names of the cycles that made moves; `cycleNames[0]` is '' (no cycle). */
  cycleNames: string[];
  /** Index into the arc arrays, or -1. */
  arcOf: Int32Array;
  arcCentre: Float64Array;
  arcRadius: Float64Array;
  arcSweep: Float64Array;
  /** The file table: URIs (or the server's names); `files[0]` is the previewed file. */
  files: string[];
  /** The call sites; site 0 stands for no call. A site's caller has a smaller index than the site. */
  siteFile: Uint32Array;
  siteLine: Uint32Array;
  siteCaller: Uint32Array;
}

function motionIndex(motion: string): number {
  const upper = motion.toUpperCase();
  const normal = upper === 'G00' ? 'G0' : upper === 'G01' ? 'G1' : upper === 'G02' ? 'G2' : upper === 'G03' ? 'G3' : upper;
  const index = MOTIONS.indexOf(normal as Motion);
  return index < 0 ? MOTIONS.length - 1 : index;
}

/** Arrays for `count` moves and `arcs` arcs in the previewed file `previewed`, without calls; moves
 * have no arc until one is set. */
export function allocatePacked(count: number, arcs: number, previewed = ''): PackedToolpath {
  return {
    count,
    line: new Uint32Array(count),
    file: new Uint32Array(count),
    outerLine: new Uint32Array(count),
    pass: new Uint32Array(count),
    block: new Uint32Array(count),
    stack: new Uint32Array(count),
    motion: new Uint8Array(count),
    flags: new Uint16Array(count),
    start: new Float64Array(count * 3),
    end: new Float64Array(count * 3),
    feed: new Float64Array(count),
    time: new Float64Array(count),
    cycleOf: new Uint8Array(count),
    cycleNames: [''],
    arcOf: new Int32Array(count).fill(-1),
    arcCentre: new Float64Array(arcs * 3),
    arcRadius: new Float64Array(arcs),
    arcSweep: new Float64Array(arcs),
    files: [previewed],
    siteFile: new Uint32Array(1),
    siteLine: new Uint32Array(1),
    siteCaller: new Uint32Array(1),
  };
}

export function emptyPacked(): PackedToolpath {
  return allocatePacked(0, 0);
}

export interface FileNames {
  /** The key of the previewed file (its URI): `files[0]`. */
  previewed: string;
  /** Other names of the previewed file in the answer (its `file` field). */
  aliases?: readonly string[];
  /** The key of a file the server named (default: the name itself). */
  key?: (name: string) => string;
}

/** The file table of one part and the call sites, interned as moves are packed. */
class Tables {
  readonly files: string[];
  private readonly fileIndex = new Map<string, number>();
  readonly siteFile: number[] = [0];
  readonly siteLine: number[] = [0];
  readonly siteCaller: number[] = [0];
  private readonly siteIndex = new Map<string, number>();
  private lastStack: PreviewCallSite[] = [];
  private lastSite = 0;

  constructor(private readonly names: FileNames) {
    this.files = [names.previewed];
    this.fileIndex.set(names.previewed, 0);
    for (const alias of names.aliases ?? []) this.fileIndex.set(alias, 0);
  }

  file(name: string | null): number {
    if (name === null) return 0;
    let index = this.fileIndex.get(name);
    if (index === undefined) {
      const key = this.names.key ? this.names.key(name) : name;
      index = this.files.indexOf(key);
      if (index < 0) index = this.files.push(key) - 1;
      this.fileIndex.set(name, index);
    }
    return index;
  }

  /** The innermost site of a call path; the outermost call is always in the previewed file. */
  site(stack: PreviewCallSite[]): number {
    if (stack.length === 0) return 0;
    // Moves of one call come one after the other: the same path as the last move costs no lookup.
    const last = this.lastStack;
    if (last.length === stack.length && stack.every((s, i) => s.line === last[i].line && s.file === last[i].file)) return this.lastSite;
    let site = 0;
    stack.forEach((call, depth) => {
      const file = depth === 0 ? 0 : this.file(call.file);
      const key = `${site} ${file} ${call.line}`;
      let next = this.siteIndex.get(key);
      if (next === undefined) {
        next = this.siteLine.length;
        this.siteFile.push(file);
        this.siteLine.push(call.line);
        this.siteCaller.push(site);
        this.siteIndex.set(key, next);
      }
      site = next;
    });
    this.lastStack = stack;
    this.lastSite = site;
    return site;
  }
}

/** The two flag bits of an inserted element; a name this view does not know packs as a programmed
 * move (drawn as what it is, a line or an arc, without the note). */
function insertedCode(name: string | null): number {
  if (!name) return 0;
  if (name === 'RNDM') return 1;
  return Math.max(0, INSERTED_NAMES.indexOf(name as (typeof INSERTED_NAMES)[number]));
}

/** The index of a cycle's name in `names`, added when it is new; 0 when the table is full. */
function internCycle(names: string[], name: string): number {
  let index = names.indexOf(name, 1);
  if (index < 0 && names.length <= MAX_CYCLE_NAMES) index = names.push(name) - 1;
  return Math.max(index, 0);
}

/** Names of drilling cycles, whose feed moves along the tool axis alone are holes. The hole patterns
 * (HOLES1, HOLES2, CYCLE801) only position; the modal drilling cycle they trigger drills. */
const DRILLING_CYCLE = /^CYCLE(8[1-9]|840)$/;

/** The axis along which move `index` drills: a feed move of a drilling cycle, straight, along one
 * axis alone (the tool axis, whatever the plane), the others known and unchanged or unknown at both
 * ends; -1 otherwise. */
export function drillAxisOf(packed: PackedToolpath, index: number, cycle: string): number {
  if (!DRILLING_CYCLE.test(cycle) || MOTIONS[packed.motion[index]] !== 'G1' || packed.arcOf[index] >= 0) return -1;
  let axis = -1;
  for (let k = 0; k < 3; k++) {
    const from = packed.start[index * 3 + k];
    const to = packed.end[index * 3 + k];
    if (Number.isNaN(from) && Number.isNaN(to)) continue;
    if (Number.isNaN(from) || Number.isNaN(to)) return -1;
    if (Math.abs(to - from) <= 1e-9 * Math.max(1, Math.abs(from))) continue;
    if (axis >= 0) return -1;
    axis = k;
  }
  return axis;
}

/** `N30` → 31, `:30` → 31 and the main-block flag; 0 when there is no number. */
function blockNumber(block: string | null): [number, number] {
  const match = block ? /^([N:])(\d{1,10})$/i.exec(block.trim()) : null;
  if (!match) return [0, 0];
  const number = Number(match[2]);
  if (number >= 0xffffffff) return [0, 0];
  return [number + 1, match[1] === ':' ? FLAG_MAIN_BLOCK : 0];
}

/** The text of a packed block number, or '' when the move's block has none. */
export function blockText(packed: PackedToolpath, move: number): string {
  const block = packed.block[move];
  if (!block) return '';
  return `${packed.flags[move] & FLAG_MAIN_BLOCK ? ':' : 'N'}${block - 1}`;
}

export function packMoves(moves: readonly PreviewMove[], names: FileNames = { previewed: '' }): PackedToolpath {
  const count = moves.length;
  const arcCount = moves.reduce((total, move) => total + (move.arc ? 1 : 0), 0);
  const packed = allocatePacked(count, arcCount);
  const tables = new Tables(names);
  let arcIndex = 0;
  moves.forEach((move, index) => {
    packed.line[index] = move.line;
    packed.file[index] = tables.file(move.file);
    packed.outerLine[index] = outermostLine(move);
    packed.pass[index] = move.pass ?? 0;
    packed.stack[index] = tables.site(move.stack);
    packed.motion[index] = motionIndex(move.motion);
    const [block, mainBlock] = blockNumber(move.block);
    packed.block[index] = block;
    let flags = (packed.motion[index] === 0 ? FLAG_RAPID : 0) | mainBlock | (move.conditional ? FLAG_CONDITIONAL : 0);
    AXES.forEach((axis, k) => {
      packed.start[index * 3 + k] = move.start[axis] ?? NaN;
      packed.end[index * 3 + k] = move.end[axis] ?? NaN;
      if (move.uncertain.includes(axis)) flags |= FLAG_UNCERTAIN_X << k;
      if (move.assumed.includes(axis)) flags |= FLAG_ASSUMED_X << k;
    });
    packed.feed[index] = move.feed ?? NaN;
    packed.time[index] = move.time ?? NaN;
    flags |= insertedCode(move.inserted) << 10;
    if (move.arc) {
      if (move.arc.clockwise) flags |= FLAG_CLOCKWISE;
      AXES.forEach((axis, k) => {
        packed.arcCentre[arcIndex * 3 + k] = move.arc!.centre[axis] ?? NaN;
      });
      packed.arcRadius[arcIndex] = move.arc.radius;
      packed.arcSweep[arcIndex] = move.arc.sweep;
      packed.arcOf[index] = arcIndex++;
    }
    if (move.cycle) {
      flags |= FLAG_CYCLE;
      packed.cycleOf[index] = internCycle(packed.cycleNames, move.cycle);
      const axis = drillAxisOf(packed, index, move.cycle);
      if (axis >= 0) flags |= (axis + 1) << FLAG_HOLE_SHIFT;
    }
    packed.flags[index] = flags;
  });
  packed.files = tables.files;
  packed.siteFile = Uint32Array.from(tables.siteFile);
  packed.siteLine = Uint32Array.from(tables.siteLine);
  packed.siteCaller = Uint32Array.from(tables.siteCaller);
  return packed;
}

/** Joins parts fetched one after the other into one toolpath: their file tables become one (by
 * key), and so do their call sites. */
export function concatPacked(parts: readonly PackedToolpath[]): PackedToolpath {
  if (parts.length === 1) return parts[0];
  const count = parts.reduce((total, part) => total + part.count, 0);
  const arcs = parts.reduce((total, part) => total + part.arcRadius.length, 0);
  const out = allocatePacked(count, arcs, parts[0]?.files[0] ?? '');
  const files = out.files;
  const siteFile = [0];
  const siteLine = [0];
  const siteCaller = [0];
  const siteIndex = new Map<string, number>();
  let at = 0;
  let arcAt = 0;
  for (const part of parts) {
    const fileMap = part.files.map((name, index) => {
      if (index === 0) return 0;
      const found = files.indexOf(name, 1);
      return found >= 0 ? found : files.push(name) - 1;
    });
    const siteMap = new Uint32Array(part.siteLine.length);
    for (let site = 1; site < part.siteLine.length; site++) {
      const caller = siteMap[part.siteCaller[site]];
      const file = fileMap[part.siteFile[site]];
      const key = `${caller} ${file} ${part.siteLine[site]}`;
      let index = siteIndex.get(key);
      if (index === undefined) {
        index = siteLine.push(part.siteLine[site]) - 1;
        siteFile.push(file);
        siteCaller.push(caller);
        siteIndex.set(key, index);
      }
      siteMap[site] = index;
    }
    out.line.set(part.line, at);
    out.outerLine.set(part.outerLine, at);
    out.pass.set(part.pass, at);
    out.block.set(part.block, at);
    out.motion.set(part.motion, at);
    out.flags.set(part.flags, at);
    out.start.set(part.start, at * 3);
    out.end.set(part.end, at * 3);
    out.feed.set(part.feed, at);
    out.time.set(part.time, at);
    const cycleMap = part.cycleNames.map((name, index) => (index === 0 ? 0 : internCycle(out.cycleNames, name)));
    for (let i = 0; i < part.count; i++) {
      out.cycleOf[at + i] = cycleMap[part.cycleOf[i]] ?? 0;
      out.arcOf[at + i] = part.arcOf[i] < 0 ? -1 : part.arcOf[i] + arcAt;
      out.file[at + i] = fileMap[part.file[i]];
      out.stack[at + i] = siteMap[part.stack[i]];
    }
    out.arcCentre.set(part.arcCentre, arcAt * 3);
    out.arcRadius.set(part.arcRadius, arcAt);
    out.arcSweep.set(part.arcSweep, arcAt);
    at += part.count;
    arcAt += part.arcRadius.length;
  }
  out.siteFile = Uint32Array.from(siteFile);
  out.siteLine = Uint32Array.from(siteLine);
  out.siteCaller = Uint32Array.from(siteCaller);
  return out;
}

type TypedArrayConstructor =
  | Uint32ArrayConstructor | Uint16ArrayConstructor | Uint8ArrayConstructor | Float64ArrayConstructor | Int32ArrayConstructor;

const FIELDS: [keyof PackedToolpath, TypedArrayConstructor][] = [
  ['line', Uint32Array], ['file', Uint32Array], ['outerLine', Uint32Array], ['pass', Uint32Array], ['block', Uint32Array],
  ['stack', Uint32Array], ['motion', Uint8Array], ['flags', Uint16Array], ['start', Float64Array], ['end', Float64Array],
  ['feed', Float64Array], ['time', Float64Array], ['cycleOf', Uint8Array], ['arcOf', Int32Array], ['arcCentre', Float64Array], ['arcRadius', Float64Array], ['arcSweep', Float64Array],
  ['siteFile', Uint32Array], ['siteLine', Uint32Array], ['siteCaller', Uint32Array],
];

function listOf(field: unknown): unknown[] {
  if (ArrayBuffer.isView(field)) return Array.from(field as unknown as ArrayLike<unknown>);
  if (Array.isArray(field)) return field;
  if (field && typeof field === 'object') return Object.values(field);
  return [];
}

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
    const values = listOf(field);
    const array = new Type(values.length);
    // JSON writes NaN (unknown) as null, which must not become 0.
    values.forEach((item, index) => (array[index] = typeof item === 'number' ? item : NaN));
    (out as unknown as Record<string, unknown>)[name] = array;
  }
  const files = listOf(record.files).map((name) => (typeof name === 'string' ? name : ''));
  out.files = files.length ? files : [''];
  const cycleNames = listOf(record.cycleNames).map((name) => (typeof name === 'string' ? name : ''));
  out.cycleNames = cycleNames.length ? cycleNames : [''];
  // Site 0 (no call) is always there.
  if (out.siteLine.length === 0) {
    out.siteFile = new Uint32Array(1);
    out.siteLine = new Uint32Array(1);
    out.siteCaller = new Uint32Array(1);
  }
  return out;
}
