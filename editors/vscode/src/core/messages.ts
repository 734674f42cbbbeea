// The messages between the extension and the toolpath page.

import type { PackedToolpath } from './packed';

export type PlaneName = 'G17' | 'G18' | 'G19';

export type ToPage =
  /** A new drawing starts (a new document, or the program changed); earlier generations are dropped. */
  | { type: 'reset'; generation: number; title: string; units: string; plane: PlaneName | null }
  | { type: 'append'; generation: number; packed: PackedToolpath }
  | { type: 'done'; generation: number }
  | { type: 'error'; generation: number; message: string }
  /** The editor's cursor is on this 1-based line. */
  | { type: 'cursor'; line: number };

export type FromPage =
  | { type: 'ready' }
  /** The user clicked the segment of this 1-based line. */
  | { type: 'reveal'; line: number };
