// How the toolpath of a long program is fetched: in line ranges, so that the first part is drawn
// while the server still works on the rest and no single answer holds a million moves.

import { outermostLine, type PreviewMove } from './preview';

/** A range of 0-based lines, `end` exclusive. */
export interface LineRange {
  start: number;
  end: number;
}

/** Lines per request: about 5 MB of JSON for a program that moves on every line. */
export const DEFAULT_CHUNK_LINES = 25_000;

export function chunkRanges(lineCount: number, chunkLines = DEFAULT_CHUNK_LINES): LineRange[] {
  const size = Math.max(1, Math.floor(chunkLines));
  const ranges: LineRange[] = [];
  for (let start = 0; start < Math.max(lineCount, 1); start += size) {
    ranges.push({ start, end: Math.min(start + size, Math.max(lineCount, 1)) });
  }
  return ranges;
}

/** The arguments of `sinumerik.endpointPreview` for one range (the server's end line is inclusive or
 * exclusive: moves outside the range are dropped by `movesInRange` either way). */
export function previewArguments(uri: string, range: LineRange): [{ uri: string; startLine: number; endLine: number }] {
  return [{ uri, startLine: range.start, endLine: range.end }];
}

export interface RangeAnswer {
  moves: PreviewMove[];
  /** The server sent moves outside the range: it ignores ranges, and this answer is the whole program. */
  wholeProgram: boolean;
}

/** Keeps the moves of `range`: those whose line in the previewed file (the outermost call's line for
 * a move of a called program, else the move's own; 1-based) is in it. */
export function movesInRange(moves: PreviewMove[], range: LineRange): RangeAnswer {
  let outside = false;
  const inside: PreviewMove[] = [];
  for (const move of moves) {
    const line = outermostLine(move) - 1;
    if (line >= range.start && line < range.end) {
      inside.push(move);
    } else if (line < range.start - 1 || line > range.end) {
      // One line beyond either end is an inclusive end line, not a server that ignores ranges.
      outside = true;
    }
  }
  return outside ? { moves, wholeProgram: true } : { moves: inside, wholeProgram: false };
}
