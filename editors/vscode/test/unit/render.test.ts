import assert from 'node:assert/strict';
import { test } from 'node:test';
import { allocatePacked, FLAG_RAPID, packMoves, type PackedToolpath } from '../../src/core/packed';
import { parsePreview } from '../../src/core/preview';
import { fitView, project, toScreen, zoomAt } from '../../src/webview/geometry';
import { segmentsCausedBy } from '../../src/webview/selection';
import { fadedColour, LIGHT_STYLES, MAX_MARKERS, render, STYLES, type CanvasLike, type PathLike } from '../../src/webview/render';
import { readFixture } from './fixtures';

interface Command { op: string; args: number[] }

class RecordingPath implements PathLike {
  commands: Command[] = [];
  moveTo(...args: number[]) { this.commands.push({ op: 'moveTo', args }); }
  lineTo(...args: number[]) { this.commands.push({ op: 'lineTo', args }); }
  ellipse(x: number, y: number, rx: number, ry: number, rotation: number, start: number, end: number, anticlockwise: boolean) {
    this.commands.push({ op: 'ellipse', args: [x, y, rx, ry, rotation, start, end, anticlockwise ? 1 : 0] });
  }
}

class RecordingCanvas implements CanvasLike {
  strokeStyle: unknown = '';
  fillStyle: unknown = '';
  lineWidth = 1;
  dash: number[] = [];
  strokes: { colour: unknown; width: number; dash: number[]; path: RecordingPath }[] = [];
  fills = 0;
  setLineDash(segments: number[]) { this.dash = segments; }
  stroke(path: PathLike) { this.strokes.push({ colour: this.strokeStyle, width: this.lineWidth, dash: this.dash, path: path as RecordingPath }); }
  fillRect() { this.fills++; }
  clearRect() {}
}

const demoPacked = () => packMoves(parsePreview(readFixture('demo_mill.preview.json')).moves);
const demo = () => project(demoPacked(), 'G17');
/** The drawn segments of a line of the demo program. */
const segmentsOfLine = (p: ReturnType<typeof demo>, line: number) => segmentsCausedBy(p, demoPacked(), 0, line);

test('the demo program draws feeds solid, rapids dashed, arcs as arcs and the cursor line on top', () => {
  const p = demo();
  const view = fitView(p.bounds, 820, 620, 10);
  const canvas = new RecordingCanvas();
  const highlight = segmentsOfLine(p, 8);
  const stats = render(canvas, () => new RecordingPath(), p, view, 820, 620, '#000', highlight);
  assert.equal(stats.visited, p.count);
  const byColour = new Map(canvas.strokes.map((s) => [s.colour, s]));
  assert.deepEqual(byColour.get(STYLES.rapid.colour)!.dash, STYLES.rapid.dash);
  assert.deepEqual(byColour.get(STYLES.feed.colour)!.dash, []);
  const feedArcs = byColour.get(STYLES.feed.colour)!.path.commands.filter((c) => c.op === 'ellipse');
  assert.equal(feedArcs.length, 5, 'four rounded corners and one full circle');
  const circle = feedArcs.find((c) => c.args[2] === 150)!;
  assert.deepEqual(circle.args.slice(0, 2), [460, 260], 'centre X35 Y25 on screen');
  assert.ok(Math.abs(Math.abs(circle.args[6] - circle.args[5]) - 2 * Math.PI) < 1e-12);
  assert.equal(circle.args[7], 0, 'clockwise in the plane is clockwise on screen');
  const last = canvas.strokes[canvas.strokes.length - 1];
  assert.equal(last.colour, STYLES.highlight.colour, 'the highlight is drawn last');
  assert.equal(last.path.commands.filter((c) => c.op === 'ellipse').length, 1);
  assert.equal(canvas.fills, 2, 'background and the end-point marker');
});

test('a light theme draws with the light palette', () => {
  const p = demo();
  const canvas = new RecordingCanvas();
  render(canvas, () => new RecordingPath(), p, fitView(p.bounds, 820, 620, 10), 820, 620, '#fff', segmentsOfLine(p, 8), LIGHT_STYLES);
  const colours = new Set(canvas.strokes.map((s) => s.colour));
  assert.deepEqual(colours, new Set([LIGHT_STYLES.feed.colour, LIGHT_STYLES.rapid.colour, LIGHT_STYLES.uncertainFeed.colour, LIGHT_STYLES.highlight.colour]));
});

test('conditional moves are drawn faded in their own path, and each highlighted move gets its end marker', () => {
  const packed = packMoves(parsePreview(readFixture('calls_mill.preview.json')).moves);
  const p = project(packed, 'G17');
  const canvas = new RecordingCanvas();
  const line8 = segmentsCausedBy(p, packed, 0, 8);
  render(canvas, () => new RecordingPath(), p, fitView(p.bounds, 820, 620, 10), 820, 620, '#000', line8);
  const faded = canvas.strokes.filter((s) => s.colour === fadedColour(STYLES.feed.colour));
  assert.equal(fadedColour(STYLES.feed.colour), '#3b8eea80');
  assert.equal(faded.length, 1, 'one faded path for the conditional feed move');
  assert.deepEqual(faded[0].path.commands.map((c) => c.op), ['moveTo', 'lineTo'], 'N160 G1 X80 alone');
  assert.equal(canvas.fills, 1 + line8.length, 'background and a marker on each of the six moves of line 8');
  const many = new RecordingCanvas();
  const overLimit = Uint32Array.from({ length: MAX_MARKERS + 1 }, (_, i) => i % p.count);
  render(many, () => new RecordingPath(), p, fitView(p.bounds, 820, 620, 10), 820, 620, '#000', overLimit);
  assert.equal(many.fills, 2, 'beyond the limit of markers, the last move only');
});

test('zoomed in on a corner, chunks off screen are skipped', () => {
  const packed = synthetic(10_000);
  const p = project(packed, 'G17');
  const whole = fitView(p.bounds, 800, 600);
  const [sx, sy] = toScreen(whole, 10, 0); // on the spiral's first turn
  const close = zoomAt(whole, 50, sx, sy);
  const stats = render(new RecordingCanvas(), () => new RecordingPath(), p, close, 800, 600, '#000');
  assert.ok(stats.culledChunks > 0);
  assert.ok(stats.visited > 0 && stats.visited < p.count / 2, `${stats.visited} visited`);
});

/** Short feed moves on a growing spiral with a rapid every 1000 moves. */
function synthetic(count: number): PackedToolpath {
  const p = allocatePacked(count, 0);
  let x = 10;
  let y = 0;
  for (let i = 0; i < count; i++) {
    const r = 10 + i * 0.0001;
    const nx = r * Math.cos(i * 0.002);
    const ny = r * Math.sin(i * 0.002);
    p.line[i] = i + 1;
    p.flags[i] = i % 1000 === 0 ? FLAG_RAPID : 0;
    p.start.set([x, y, 0], i * 3);
    p.end.set([nx, ny, 0], i * 3);
    x = nx;
    y = ny;
  }
  return p;
}

test('a million moves are thinned to what the pixels can show (figures printed)', () => {
  const count = 1_000_000;
  let started = performance.now();
  const p = project(synthetic(count), 'G17');
  const projectMs = performance.now() - started;
  const view = fitView(p.bounds, 800, 600);
  const canvas = new RecordingCanvas();
  started = performance.now();
  const stats = render(canvas, () => new RecordingPath(), p, view, 800, 600, '#000');
  const renderMs = performance.now() - started;
  const commands = canvas.strokes.reduce((total, s) => total + s.path.commands.length, 0);
  console.log(`1,000,000 moves: project ${projectMs.toFixed(0)} ms, render ${renderMs.toFixed(0)} ms, ${commands} path commands, ${stats.thinned} thinned`);
  assert.equal(stats.visited, count);
  // A move of no length in the plane (the spiral's first) is neither drawn nor thinned.
  let still = 0;
  for (let s = 0; s < p.count; s++) if (p.x0[s] === p.x1[s] && p.y0[s] === p.y1[s]) still++;
  assert.equal(still, 1);
  assert.equal(stats.drawn + stats.thinned + still, count);
  // Most moves are shorter than a pixel at this zoom and are joined to their neighbours.
  assert.ok(commands < count / 2, `${commands} commands`);
});
