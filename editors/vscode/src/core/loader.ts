// Fetching a program's toolpath range by range and handing each part to the page. A newer load (the
// program was edited) makes older ones stop at their next range, so an edit never waits for the
// end of a stale million-line answer.

import { chunkRanges, movesInRange, previewArguments, DEFAULT_CHUNK_LINES } from './chunks';
import type { PlaneName, ToPage } from './messages';
import { packMoves } from './packed';
import { parsePreview } from './preview';

export const PREVIEW_COMMAND = 'sinumerik.endpointPreview';

export interface LoadRequest {
  uri: string;
  title: string;
  lineCount: number;
  plane: PlaneName | null;
}

export interface LoaderDeps {
  /** Runs `workspace/executeCommand` with these arguments. */
  executePreview: (args: unknown[]) => Promise<unknown>;
  post: (message: ToPage) => void;
  chunkLines?: number;
}

export class ToolpathLoader {
  private generation = 0;

  constructor(private readonly deps: LoaderDeps) {}

  /** The generation of the newest load. */
  get current(): number {
    return this.generation;
  }

  async load(request: LoadRequest): Promise<void> {
    const generation = ++this.generation;
    const post = this.deps.post;
    // The units are known with the first answer; until then the page shows the default.
    let first = true;
    post({ type: 'reset', generation, title: request.title, units: 'mm', plane: request.plane });
    try {
      for (const range of chunkRanges(request.lineCount, this.deps.chunkLines ?? DEFAULT_CHUNK_LINES)) {
        const answer = await this.deps.executePreview(previewArguments(request.uri, range));
        if (generation !== this.generation) return;
        const preview = parsePreview(answer);
        if (first && preview.units !== 'mm') {
          post({ type: 'reset', generation, title: request.title, units: preview.units, plane: request.plane });
        }
        first = false;
        const part = movesInRange(preview.moves, range);
        post({ type: 'append', generation, packed: packMoves(part.moves) });
        if (part.wholeProgram) break;
      }
      post({ type: 'done', generation });
    } catch (error) {
      if (generation !== this.generation) return;
      const text = error instanceof Error ? error.message : String(error);
      post({ type: 'error', generation, message: `The toolpath could not be read: ${text}` });
    }
  }
}
