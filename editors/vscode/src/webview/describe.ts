// The words the page uses for a move: where it comes from (`N30, pass 3 of 5, SUB.SPF line 12`),
// the calls that led to it, and what is assumed or undecided about it. Plain functions on the packed
// arrays, for the page and for unit tests under Node.

import { fileLabel } from '../core/files';
import { AXES, blockText, FLAG_ASSUMED_X, FLAG_CONDITIONAL, type PackedToolpath } from '../core/packed';

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

/** The notes on a move that is conditional or rests on an assumed entry state, one per line. */
export function moveNotes(packed: PackedToolpath, move: number): string[] {
  const notes: string[] = [];
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
