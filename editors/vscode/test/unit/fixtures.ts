// Test helpers: the committed preview fixtures (written by `sinumerik-lsp preview`) and move builders.

import * as fs from 'node:fs';
import * as path from 'node:path';
import type { PreviewMove } from '../../src/core/preview';

/** The extension's folder; tests run from out/test/unit. */
export const EXTENSION_ROOT = path.resolve(__dirname, '..', '..', '..');

export function readFixture(name: string): unknown {
  return JSON.parse(fs.readFileSync(path.join(EXTENSION_ROOT, 'test', 'fixtures', name), 'utf8'));
}

export function move(line: number, motion: string, start: Record<string, number>, end: Record<string, number>, extra: Partial<PreviewMove> = {}): PreviewMove {
  return {
    line, block: null, motion, start, end, mcs: null, arc: null, feed: 100, uncertain: [],
    pass: null, file: null, stack: [], assumed: [], conditional: false, inserted: null, cycle: null, time: null, ...extra,
  } as PreviewMove;
}
