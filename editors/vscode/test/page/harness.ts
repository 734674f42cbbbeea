// Stands in for VS Code around the toolpath page in the browser test: a recording acquireVsCodeApi,
// and functions that feed the page the way the extension does (through ToolpathLoader).

import { ToolpathLoader } from '../../src/core/loader';
import type { FromPage, PlaneName, ToPage } from '../../src/core/messages';
import { allocatePacked, FLAG_CYCLE, FLAG_HOLE_SHIFT, FLAG_RAPID, type PackedToolpath } from '../../src/core/packed';

const sent: FromPage[] = [];
(window as unknown as Record<string, unknown>).acquireVsCodeApi = () => ({
  postMessage: (message: FromPage) => sent.push(message),
});

function post(message: ToPage): void {
  window.postMessage(message, '*');
}

let generation = 1000;

const harness = {
  sent,
  /** Loads a preview answer (the JSON of `sinumerik-lsp preview`) in ranges of `chunkLines`, as the
   * program `file:///work/<title>`. */
  async loadPreview(answer: unknown, title: string, lineCount: number, plane: PlaneName | null, chunkLines = 4, delayMs = 0) {
    // Answers like a server with an inclusive end line, so that the page is fed in several parts: the
    // moves whose line in the previewed file (the outermost call's, else their own) is in the range.
    const whole = answer as { moves: { line: number; stack?: { line: number }[] }[] };
    const executePreview = async (args: unknown[]) => {
      const { startLine, endLine } = args[0] as { startLine: number; endLine: number };
      if (delayMs) await new Promise((resolve) => setTimeout(resolve, delayMs));
      const outermost = (move: (typeof whole.moves)[number]) => (move.stack?.length ? move.stack[0].line : move.line) - 1;
      return { ...whole, moves: whole.moves.filter((move) => outermost(move) >= startLine && outermost(move) <= endLine) };
    };
    const loader = new ToolpathLoader({ executePreview, post, chunkLines });
    await loader.load({ uri: `file:///work/${title}`, title, lineCount, plane });
  },
  /** A synthetic program of `count` short feed moves on a spiral with a rapid every 1000 moves,
   * packed directly: the page's cost at a million lines, without a million JSON objects in the test. */
  loadSynthetic(count: number) {
    const p = allocatePacked(count, 0);
    let x = 0;
    let y = 0;
    for (let i = 0; i < count; i++) {
      const angle = i * 0.01;
      const radius = 10 + i * 0.0001;
      const nx = radius * Math.cos(angle);
      const ny = radius * Math.sin(angle);
      p.line[i] = i + 2;
      p.outerLine[i] = i + 2;
      const rapid = i % 1000 === 0;
      p.motion[i] = rapid ? 0 : 1;
      p.flags[i] = rapid ? FLAG_RAPID : 0;
      p.start.set([x, y, 0], i * 3);
      p.end.set([nx, ny, 0], i * 3);
      p.feed[i] = 1000;
      x = nx;
      y = ny;
    }
    const g = ++generation;
    post({ type: 'reset', generation: g, title: `synthetic-${count}`, units: 'mm', plane: 'G17' });
    post({ type: 'append', generation: g, packed: p });
    post({ type: 'done', generation: g });
  },
  /** A drilling pattern of `side` x `side` holes 1 apart, each one CYCLE81 feed move along Z, packed
   * directly: the cost of the rings of a dense pattern. */
  loadHoles(side: number) {
    const count = side * side;
    const p = allocatePacked(count, 0);
    p.cycleNames.push('CYCLE81');
    for (let i = 0; i < count; i++) {
      const x = i % side;
      const y = Math.floor(i / side);
      p.line[i] = i + 1;
      p.outerLine[i] = i + 1;
      p.motion[i] = 1;
      p.flags[i] = FLAG_CYCLE | (3 << FLAG_HOLE_SHIFT);
      p.cycleOf[i] = 1;
      p.start.set([x, y, 1], i * 3);
      p.end.set([x, y, -5], i * 3);
    }
    const g = ++generation;
    post({ type: 'reset', generation: g, title: `holes-${count}`, units: 'mm', plane: 'G17' });
    post({ type: 'append', generation: g, packed: p });
    post({ type: 'done', generation: g });
  },
  /** A packed toolpath sent as one part, as the extension sends a loaded program. */
  loadPacked(packed: PackedToolpath, title: string) {
    const g = ++generation;
    post({ type: 'reset', generation: g, title, units: 'mm', plane: 'G17' });
    post({ type: 'append', generation: g, packed });
    post({ type: 'done', generation: g });
  },
  /** The editor's cursor on a line of the previewed file, or of `file` (a URI). */
  setCursor(line: number, file?: string) {
    post(file ? { type: 'cursor', line, file } : { type: 'cursor', line });
  },
};
(window as unknown as Record<string, unknown>).harness = harness;
