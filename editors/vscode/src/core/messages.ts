// The messages between the extension and the toolpath page.

import type { ProgramTime } from './machiningTime';
import type { PackedToolpath } from './packed';

export type PlaneName = 'G17' | 'G18' | 'G19';

export type ToPage =
  /** A new drawing starts (a new document, or the program changed); earlier generations are dropped. */
  | {
      type: 'reset';
      generation: number;
      title: string;
      units: string;
      plane: PlaneName | null;
      /** What the analysis assumed about the entry state (units, distance, plane); absent when nothing. */
      assumed?: Record<string, string>;
    }
  | { type: 'append'; generation: number; packed: PackedToolpath }
  /** The load is complete; `time` is the program's machining time when the server gave one. */
  | { type: 'done'; generation: number; time?: ProgramTime }
  | { type: 'error'; generation: number; message: string }
  /** The editor's cursor is on this 1-based line of the previewed file, or of `file` (a URI of the
   * toolpath's file table) when the cursor is in a called program. */
  | { type: 'cursor'; line: number; file?: string };

export type FromPage =
  | { type: 'ready' }
  /** The user clicked the segment of this 1-based line of the previewed file, or of `file` (a URI of
   * the file table) for a move of a called program. */
  | { type: 'reveal'; line: number; file?: string };
