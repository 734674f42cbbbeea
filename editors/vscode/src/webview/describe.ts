// The words the page uses for a move: where it comes from (`N30, pass 3 of 5, SUB.SPF line 12`),
// the calls that led to it, and what is assumed or undecided about it. Plain functions on the packed
// arrays, for the page and for unit tests under Node.

import { fileLabel } from '../core/files';
import { AXES, blockText, FLAG_ASSUMED_X, FLAG_CONDITIONAL, FLAG_CYCLE, holeAxis, insertedName, type PackedToolpath } from '../core/packed';
import { impossibleCircle } from './geometry';

/** Where a move comes from: its block number, its pass of `passes` (when its block runs more than
 * once) and its line, with the file's name for a move of a called program. */
export function moveOrigin(packed: PackedToolpath, move: number, passes: number): string {
  const parts: string[] = [];
  const block = blockText(packed, move);
  if (block) parts.push(block);
  const pass = packed.pass[move];
  if (pass) parts.push(passes >= pass ? `pass ${pass} of ${passes}` : `pass ${pass}`);
  const file = packed.file[move];
  parts.push(file ? `${fileLabel(packed.files[file])} line ${packed.line[move]}` : `line ${packed.line[move]}`);
  return parts.join(', ');
}

/** The calls that led to a move, outermost first (`called at A.MPF line 8, SUB.SPF line 3`), or ''. */
export function callPath(packed: PackedToolpath, move: number): string {
  const sites: string[] = [];
  for (let site = packed.stack[move]; site !== 0; site = packed.siteCaller[site]) {
    sites.unshift(`${fileLabel(packed.files[packed.siteFile[site]] || 'program')} line ${packed.siteLine[site]}`);
    if (sites.length > 64) break;
  }
  return sites.length ? `called at ${sites.join(', ')}` : '';
}

/** A length or radius for the words of a move: at most four decimals. */
function amount(value: number): string {
  return String(Number(value.toFixed(4)));
}

/** The length of a straight move over the axes known at both ends. */
function straightLength(packed: PackedToolpath, move: number): number {
  let sum = 0;
  for (let k = 0; k < 3; k++) {
    const d = packed.end[move * 3 + k] - packed.start[move * 3 + k];
    if (!Number.isNaN(d)) sum += d * d;
  }
  return Math.sqrt(sum);
}

/** What made a move that the program does not write as a block of its own: a rounding or chamfer the
 * control inserts at a corner (`rounding R5 inserted by RND`), a cycle's move, a hole; or ''. */
export function madeBy(packed: PackedToolpath, move: number): string {
  const flags = packed.flags[move];
  const inserted = insertedName(flags);
  if (inserted) {
    const arc = packed.arcOf[move];
    if (arc >= 0) return `rounding R${amount(packed.arcRadius[arc])} inserted by ${inserted}`;
    return `chamfer ${amount(straightLength(packed, move))} long inserted by ${inserted}`;
  }
  if (!(flags & FLAG_CYCLE)) return '';
  const name = packed.cycleNames[packed.cycleOf[move]] || 'a cycle';
  const axis = holeAxis(flags);
  return axis >= 0 ? `hole drilled by ${name} along ${AXES[axis]}` : `made by ${name}`;
}

/** A move's machining time for its description (`  3.6 s`), or '' when it is not known. */
export function moveTime(packed: PackedToolpath, move: number): string {
  const seconds = packed.time[move];
  return seconds === undefined || Number.isNaN(seconds) ? '' : `  ${amount(seconds)} s`;
}

/** The notes on a move that is inserted, made by a cycle, conditional or rests on an assumed entry
 * state, one per line. */
export function moveNotes(packed: PackedToolpath, move: number): string[] {
  const notes: string[] = [];
  const made = madeBy(packed, move);
  if (made) notes.push(made);
  if (impossibleCircle(packed, move)) notes.push('no circle fits these numbers (see the problem on this line): drawn dashed from start to end, marked ✕');
  const flags = packed.flags[move];
  if (flags & FLAG_CONDITIONAL) notes.push('conditional: on a way whose condition the analysis could not decide');
  const assumed = AXES.filter((_, k) => flags & (FLAG_ASSUMED_X << k));
  if (assumed.length) notes.push(`assumed: ${assumed.join(' ')} rest on the assumed entry state`);
  return notes;
}

/** The entry state the analysis assumed, for the status line (`entry state assumed: G71 G90 G17`). */
export function assumedEntryState(assumed: Record<string, string> | undefined): string {
  const settings = Object.values(assumed ?? {}).filter((setting) => setting !== '');
  return settings.length ? `entry state assumed: ${settings.join(' ')}` : '';
}
