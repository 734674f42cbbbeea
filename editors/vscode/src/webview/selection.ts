// Which moves a line of a program causes, for the highlight of the editor's cursor line: the moves
// of that line itself (every pass), and for a line that calls a program, every move made through
// that call. Plain functions on the packed arrays, for the page and for unit tests under Node.

import type { PackedToolpath } from '../core/packed';
import type { Projected } from './geometry';

/** The index of a file in the toolpath's file table: 0 for the previewed file (no key, or its own),
 * -1 for a file the toolpath does not run through. */
export function fileIndexOf(packed: PackedToolpath, file: string | undefined | null): number {
  if (!file) return 0;
  return packed.files.indexOf(file);
}

/** For each call site: whether the call path that ends there passes through line `line` of file
 * `file` (a caller has a smaller index than the sites it leads to, so one pass suffices). */
function sitesThrough(packed: PackedToolpath, file: number, line: number): Uint8Array {
  const through = new Uint8Array(packed.siteLine.length);
  for (let site = 1; site < through.length; site++) {
    through[site] = through[packed.siteCaller[site]] || (packed.siteFile[site] === file && packed.siteLine[site] === line) ? 1 : 0;
  }
  return through;
}

/** A test of move indices: does line `line` (1-based) of file `file` (an index of the file table)
 * cause the move? It does when the move is that line's own (in any pass), and when the move's call
 * path passes through that line. The outermost call of a path is always in the previewed file, so
 * for the previewed file this includes every move whose outermost line is that line. */
export function causedBy(packed: PackedToolpath, file: number, line: number): (move: number) => boolean {
  if (file < 0 || line < 1) return () => false;
  const through = sitesThrough(packed, file, line);
  const calls = through.includes(1);
  const { line: lines, file: files, stack } = packed;
  return (move) => (lines[move] === line && files[move] === file) || (calls && through[stack[move]] === 1);
}

/** The moves that line `line` of file `file` causes, in order. */
export function movesCausedBy(packed: PackedToolpath, file: number, line: number): number[] {
  const test = causedBy(packed, file, line);
  const moves: number[] = [];
  for (let move = 0; move < packed.count; move++) if (test(move)) moves.push(move);
  return moves;
}

/** The drawn segments of those moves, in order (the test of `causedBy`, written out: this runs over
 * every segment of a million-move drawing when the cursor moves). */
export function segmentsCausedBy(p: Projected, packed: PackedToolpath, file: number, line: number): Uint32Array {
  if (file < 0 || line < 1) return new Uint32Array(0);
  const through = sitesThrough(packed, file, line);
  const calls = through.includes(1);
  const { line: lines, file: files, stack } = packed;
  const moveIndex = p.moveIndex;
  const segments: number[] = [];
  for (let s = 0; s < p.count; s++) {
    const move = moveIndex[s];
    if ((lines[move] === line && files[move] === file) || (calls && through[stack[move]] === 1)) segments.push(s);
  }
  return Uint32Array.from(segments);
}

/** How often the block of a move runs: the highest pass of the moves of its line in its file (0 when
 * it runs once). */
export function passesOf(packed: PackedToolpath, move: number): number {
  const line = packed.line[move];
  const file = packed.file[move];
  let most = 0;
  for (let other = 0; other < packed.count; other++) {
    if (packed.line[other] === line && packed.file[other] === file && packed.pass[other] > most) most = packed.pass[other];
  }
  return most;
}
