// Fetching a program's toolpath range by range and handing each part to the page. A newer load (the
// program was edited) makes older ones stop at their next range, so an edit never waits for the
// end of a stale million-line answer. The loader also knows which other files (called programs)
// the toolpath runs through, so that the editor can link them to the picture too.

import { chunkRanges, movesInRange, previewArguments, DEFAULT_CHUNK_LINES } from './chunks';
import type { PlaneName, ToPage } from './messages';
import { fileUri } from './files';
import { packMoves } from './packed';
import { parsePreview } from './preview';
import type { ProgramTime } from './machiningTime';

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
  /** The key (URI) of a file the server named, with the previewed file's URI as the base of relative
   * paths; default `fileUri`. */
  fileKey?: (name: string, base: string) => string;
}

export class ToolpathLoader {
  private generation = 0;
  /** The previewed file of the newest load, the called files of the last complete load, and those
   * the newest load met so far. */
  private previewed = '';
  private complete = new Set<string>();
  private arriving = new Set<string>();

  constructor(private readonly deps: LoaderDeps) {}

  /** The generation of the newest load. */
  get current(): number {
    return this.generation;
  }

  /** Whether `uri` is a file of a called program in the toolpath shown (or arriving). */
  isCalledFile(uri: string): boolean {
    return uri !== this.previewed && (this.complete.has(uri) || this.arriving.has(uri));
  }

  async load(request: LoadRequest): Promise<void> {
    const generation = ++this.generation;
    const post = this.deps.post;
    if (request.uri !== this.previewed) this.complete = new Set();
    this.previewed = request.uri;
    const arriving = new Set<string>();
    this.arriving = arriving;
    const key = this.deps.fileKey ?? fileUri;
    // The units and the assumed entry state are known with the first answer; until then the page
    // shows the defaults.
    let first = true;
    // The whole program's machining time, the same in every answer of one revision.
    let time: ProgramTime | null = null;
    post({ type: 'reset', generation, title: request.title, units: 'mm', plane: request.plane });
    try {
      for (const range of chunkRanges(request.lineCount, this.deps.chunkLines ?? DEFAULT_CHUNK_LINES)) {
        const answer = await this.deps.executePreview(previewArguments(request.uri, range));
        if (generation !== this.generation) return;
        const preview = parsePreview(answer);
        time = preview.time ?? time;
        if (first && (preview.units !== 'mm' || Object.keys(preview.assumed).length)) {
          const assumed = Object.keys(preview.assumed).length ? { assumed: preview.assumed } : {};
          post({ type: 'reset', generation, title: request.title, units: preview.units, plane: request.plane, ...assumed });
        }
        first = false;
        const part = movesInRange(preview.moves, range);
        const packed = packMoves(part.moves, {
          previewed: request.uri,
          aliases: preview.file ? [preview.file] : [],
          key: (name) => key(name, request.uri),
        });
        packed.files.slice(1).forEach((file) => arriving.add(file));
        post({ type: 'append', generation, packed });
        if (part.wholeProgram) break;
      }
      this.complete = arriving;
      post(time ? { type: 'done', generation, time } : { type: 'done', generation });
    } catch (error) {
      if (generation !== this.generation) return;
      const text = error instanceof Error ? error.message : String(error);
      post({ type: 'error', generation, message: `The toolpath could not be read: ${text}` });
    }
  }
}
