// The toolpath page's glue: messages from the extension, pointer and keyboard input, and redraws on
// the next animation frame. The drawing itself is in render.ts, the geometry in geometry.ts, the
// moves a line causes in selection.ts and the words for a move in describe.ts; the 3D mode is in
// mode3d.ts (and view3d.ts, scene3d.ts), the status line's layout in statusLine.ts.

import { fileLabel } from '../core/files';
import { describeProgramTime, type ProgramTime } from '../core/machiningTime';
import type { FromPage, ToPage } from '../core/messages';
import { AXES, concatPacked, emptyPacked, FLAG_UNCERTAIN_X, MOTIONS, revivePacked, type PackedToolpath } from '../core/packed';
import { assumedEntryState, callPath, moveNotes, moveOrigin, moveTime } from './describe';
import {
  fitView, guessPlane, KIND_UNCERTAIN, panBy, pickMove, PLANE_NAMES, project, revealPoint, zoomAt, type Plane, type Projected, type View,
} from './geometry';
import { Mode3d } from './mode3d';
import { LIGHT_STYLES, render, STYLES, type Palette, type RenderStats } from './render';
import { fileIndexOf, movesCausedBy, passesOf, segmentsCausedBy } from './selection';
import { showStatus } from './statusLine';

interface VsCodeApi {
  postMessage(message: FromPage): void;
}
declare function acquireVsCodeApi(): VsCodeApi;

const vscode = acquireVsCodeApi();
const canvas = document.getElementById('canvas') as HTMLCanvasElement;
const box = document.getElementById('canvas-box') as HTMLDivElement;
const statusLine = document.getElementById('status') as HTMLDivElement;
const planeSelect = document.getElementById('plane') as HTMLSelectElement;
const tip = document.getElementById('tip') as HTMLDivElement;
const context = canvas.getContext('2d')!;
const modeButtons = { '2d': document.getElementById('mode-2d') as HTMLButtonElement, '3d': document.getElementById('mode-3d') as HTMLButtonElement };

const state = {
  generation: -1,
  title: '',
  units: 'mm',
  serverPlane: null as Plane | null,
  parts: [] as PackedToolpath[],
  packed: emptyPacked(),
  projected: project(emptyPacked(), 'G17'),
  view: null as View | null,
  /** The user panned or zoomed: new data no longer refits the view. */
  userMoved: false,
  /** The editor's cursor line (1-based; 0: none) and its file's URI (undefined: the previewed file). */
  cursorLine: 0,
  cursorFile: undefined as string | undefined,
  /** The move the user clicked, while the cursor is on its line; -1 otherwise. */
  picked: -1,
  /** The entry state the analysis assumed (units, distance, plane). */
  assumed: {} as Record<string, string>,
  /** The program's machining time from the last complete load; null when the server gave none. */
  time: null as ProgramTime | null,
  done: false,
  /** Parts are drawn as they arrive (a new program), or collected in `incoming` (an edit). */
  progressive: true,
  incoming: [] as PackedToolpath[],
  /** Moves of the current load that arrived so far. */
  arrived: 0,
  projectedAt: 0,
  projectPending: false,
  error: '',
  stats: null as RenderStats | null,
  renderMs: 0,
  width: 0,
  height: 0,
};

/** The highlighted segments of the cursor's line, computed again only when the line or the drawing changes. */
const highlighted = { projected: null as Projected | null, file: undefined as string | undefined, line: 0, segments: new Uint32Array(0) };

function highlight(): Uint32Array {
  const { projected, cursorFile, cursorLine } = state;
  if (highlighted.projected !== projected || highlighted.file !== cursorFile || highlighted.line !== cursorLine) {
    const file = fileIndexOf(state.packed, cursorFile);
    highlighted.segments = cursorLine ? segmentsCausedBy(projected, state.packed, file, cursorLine) : new Uint32Array(0);
    Object.assign(highlighted, { projected, file: cursorFile, line: cursorLine });
  }
  return highlighted.segments;
}

/** The moves of the cursor's line for the 3D view, computed again only when the line or the toolpath changes. */
const cursorMoves = { packed: null as PackedToolpath | null, file: undefined as string | undefined, line: 0, moves: [] as number[] };

function highlightMoves(): number[] {
  const { packed, cursorFile, cursorLine } = state;
  if (cursorMoves.packed !== packed || cursorMoves.file !== cursorFile || cursorMoves.line !== cursorLine) {
    const moves = cursorLine ? movesCausedBy(packed, fileIndexOf(packed, cursorFile), cursorLine) : [];
    Object.assign(cursorMoves, { packed, file: cursorFile, line: cursorLine, moves });
  }
  return cursorMoves.moves;
}

/** The palette for the theme: VS Code marks the webview's body with the kind of theme. */
function palette(): Palette {
  const light = document.body.classList.contains('vscode-light') || document.body.classList.contains('vscode-high-contrast-light');
  return light ? LIGHT_STYLES : STYLES;
}

function backgroundColour(): string {
  return getComputedStyle(document.body).backgroundColor || '#1e1e1e';
}

/** How often a move's block runs, remembered per file and line until the toolpath changes. */
const passCounts = { packed: null as PackedToolpath | null, counts: new Map<number, number>() };

function passes(move: number): number {
  const packed = state.packed;
  if (!packed.pass[move]) return 0;
  if (passCounts.packed !== packed) Object.assign(passCounts, { packed, counts: new Map() });
  const key = packed.file[move] * 2 ** 32 + packed.line[move];
  let count = passCounts.counts.get(key);
  if (count === undefined) passCounts.counts.set(key, (count = passesOf(packed, move)));
  return count;
}

/** The user clicked a move (in either view): select its line in the editor. */
function pickedMove(move: number): void {
  const file = state.packed.file[move];
  state.picked = move;
  state.cursorLine = state.packed.line[move];
  state.cursorFile = file ? state.packed.files[file] : undefined;
  vscode.postMessage(file ? { type: 'reveal', line: state.cursorLine, file: state.cursorFile } : { type: 'reveal', line: state.cursorLine });
  scheduleDraw();
}

const mode3d = new Mode3d(document.getElementById('canvas3d') as HTMLCanvasElement, {
  packed: () => state.packed,
  cursorMoves: highlightMoves,
  palette,
  background: backgroundColour,
  describe: (move) => describeMove(move, false),
  picked: pickedMove,
  redraw: () => scheduleDraw(),
  tip,
});

function setMode(mode: '2d' | '3d'): void {
  if (!mode3d.setActive(mode === '3d')) {
    // No WebGL here: the 3D switch says why and the plane view stays.
    mode = '2d';
    modeButtons['3d'].disabled = true;
    modeButtons['3d'].title = mode3d.failure;
  }
  canvas.style.display = mode === '3d' ? 'none' : 'block';
  planeSelect.disabled = mode === '3d';
  for (const [name, button] of Object.entries(modeButtons)) button.setAttribute('aria-pressed', String(name === mode));
  tip.style.display = 'none';
  scheduleDraw();
}
modeButtons['2d'].addEventListener('click', () => setMode('2d'));
modeButtons['3d'].addEventListener('click', () => setMode('3d'));

// For the browser test: the state and the functions it needs to find segments on screen.
(window as unknown as { toolpathDebug: unknown }).toolpathDebug = {
  state, highlight, segmentsCausedBy, fileIndexOf, mode3d, setMode, redrawNow: () => draw(),
};

function chosenPlane(): Plane {
  const choice = planeSelect.value;
  if (choice === 'G17' || choice === 'G18' || choice === 'G19') return choice;
  return state.serverPlane ?? guessPlane(state.packed);
}

function reproject(): void {
  state.projectedAt = performance.now();
  state.projectPending = false;
  state.packed = concatPacked(state.parts.length ? state.parts : [emptyPacked()]);
  state.parts = state.packed.count ? [state.packed] : [];
  state.projected = project(state.packed, chosenPlane());
  if ((!state.view || !state.userMoved) && state.projected.bounds) {
    state.view = fitView(state.projected.bounds, state.width, state.height);
  }
}

let frameRequested = false;
function scheduleDraw(): void {
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(() => {
    frameRequested = false;
    draw();
  });
}

function resize(): void {
  const ratio = window.devicePixelRatio || 1;
  state.width = box.clientWidth;
  state.height = box.clientHeight;
  canvas.width = Math.max(1, Math.round(state.width * ratio));
  canvas.height = Math.max(1, Math.round(state.height * ratio));
  context.setTransform(ratio, 0, 0, ratio, 0, 0);
}

function draw(): void {
  const started = performance.now();
  if (mode3d.active) {
    mode3d.draw();
    state.renderMs = performance.now() - started;
    updateStatus(highlight());
    return;
  }
  const view = state.view ?? fitView(state.projected.bounds, state.width, state.height);
  const segments = highlight();
  state.stats = render(context, () => new Path2D(), state.projected, view, state.width, state.height, backgroundColour(), segments, palette());
  state.renderMs = performance.now() - started;
  updateStatus(segments);
}

/** The status line's words for the cursor: the clicked move, or the line and how many moves it causes. */
function cursorStatus(segments: Uint32Array): string {
  if (state.picked >= 0 && state.picked < state.packed.count) return moveOrigin(state.packed, state.picked, passes(state.picked));
  const where = state.cursorFile ? `${fileLabel(state.cursorFile)} line ${state.cursorLine}` : `line ${state.cursorLine}`;
  if (fileIndexOf(state.packed, state.cursorFile) < 0) return `${where}: not part of this toolpath`;
  const count = mode3d.active ? highlightMoves().length : segments.length;
  if (count === 0) return mode3d.active ? `${where}: no move` : `${where}: no move in this plane`;
  return count === 1 ? where : `${where}: ${count.toLocaleString('en')} moves`;
}

function updateStatus(segments: Uint32Array): void {
  if (state.error) {
    showStatus(statusLine, [state.error]);
    return;
  }
  const p = state.projected;
  const space = mode3d.active ? mode3d.paths : null;
  const parts = [
    `${state.title}: ${state.packed.count.toLocaleString('en')} moves` +
      (state.done ? '' : state.progressive ? ' (loading…)' : ` (updating after the edit: ${state.arrived.toLocaleString('en')} moves so far)`),
    space ? '3D' : `plane ${p.plane} ${PLANE_NAMES[p.plane]}`,
    state.units,
  ];
  const holes = space ? space.holeMove.length : p.holeSegment.length;
  if (holes) parts.push(`${holes.toLocaleString('en')} ${holes === 1 ? 'hole' : 'holes'}`);
  if (space?.hidden) parts.push(`${space.hidden.toLocaleString('en')} not drawn (position unknown)`);
  else if (!space && p.hidden) parts.push(`${p.hidden.toLocaleString('en')} not drawn (position unknown in this plane)`);
  const thinned = space ? (mode3d.view?.stats.thinned ?? 0) : (state.stats?.thinned ?? 0);
  if (thinned) parts.push(`${thinned.toLocaleString('en')} thinned at this zoom`);
  const unverified = space ? space.arcsUnverified : (state.stats?.arcsUnverified ?? 0);
  if (unverified) parts.push(`${unverified} arcs drawn straight (centre does not fit)`);
  const impossible = space ? space.impossible : (state.stats?.impossible ?? 0);
  if (impossible) parts.push(`${impossible} ${impossible === 1 ? 'circle' : 'circles'} that cannot exist (dashed, ✕)`);
  if (p.conditional) parts.push(`${p.conditional.toLocaleString('en')} conditional (faded)`);
  const assumed = assumedEntryState(state.assumed);
  if (assumed) parts.push(assumed);
  if (state.time) parts.push(describeProgramTime(state.time));
  if (state.cursorLine) parts.push(cursorStatus(segments));
  showStatus(statusLine, parts);
}

function describe(segment: number): string {
  return describeMove(state.projected.moveIndex[segment], (state.projected.kind[segment] & KIND_UNCERTAIN) !== 0);
}

/** The tooltip of a move; `uncertainHere`: a coordinate the view shows may not be the control's. */
function describeMove(move: number, uncertainHere: boolean): string {
  const packed = state.packed;
  // An axis left out of the end point is unknown when the server names it uncertain; otherwise the
  // machine does not have it.
  const end = AXES.map((axis, k) => {
    const value = packed.end[move * 3 + k];
    if (!Number.isNaN(value)) return `${axis}${Number(value.toFixed(4))}`;
    return packed.flags[move] & (FLAG_UNCERTAIN_X << k) ? `${axis} unknown` : '';
  })
    .filter((text) => text !== '')
    .join(' ');
  const feed = Number.isNaN(packed.feed[move]) ? '' : ` F${packed.feed[move]}`;
  const lines = [`${moveOrigin(packed, move, passes(move))}  ${MOTIONS[packed.motion[move]]}  → ${end}${feed}${moveTime(packed, move)}`];
  const calls = callPath(packed, move);
  if (calls) lines.push(calls);
  lines.push(...moveNotes(packed, move));
  const uncertain = uncertainHere || (mode3d.active && (packed.flags[move] & (FLAG_UNCERTAIN_X * 7)) !== 0);
  if (uncertain) lines.push('uncertain: the control may take another path here');
  return lines.join('\n');
}

window.addEventListener('message', (event: MessageEvent<ToPage>) => {
  const message = event.data;
  switch (message.type) {
    case 'reset':
      // Another program is drawn as its parts arrive, in a fitted view. The same program after an
      // edit keeps the user's view and the old drawing until the new one is complete, so that
      // typing in a long program does not make the picture flicker.
      state.progressive = message.title !== state.title || state.packed.count === 0 || state.error !== '';
      if (message.title !== state.title) {
        state.view = null;
        state.userMoved = false;
        mode3d.forgetUserView();
      }
      state.generation = message.generation;
      state.picked = -1;
      state.title = message.title;
      state.units = message.units;
      state.assumed = message.assumed ?? {};
      state.serverPlane = message.plane;
      state.incoming = [];
      state.arrived = 0;
      state.done = false;
      state.error = '';
      if (state.progressive) {
        state.parts = [];
        reproject();
      }
      break;
    case 'append': {
      if (message.generation !== state.generation) return;
      const packed = revivePacked(message.packed);
      state.arrived += packed.count;
      if (state.progressive) {
        state.parts.push(packed);
        // Projecting everything again costs time in proportion to the moves so far: at most about
        // once a second while a long program arrives.
        if (performance.now() - state.projectedAt > 1000 || state.parts.length === 1) reproject();
        else state.projectPending = true;
      } else {
        state.incoming.push(packed);
      }
      break;
    }
    case 'done':
      if (message.generation !== state.generation) return;
      state.done = true;
      state.time = message.time ?? null;
      if (!state.progressive) state.parts = state.incoming;
      state.incoming = [];
      if (!state.progressive || state.projectPending) reproject();
      break;
    case 'error':
      if (message.generation !== state.generation) return;
      state.error = message.message;
      break;
    case 'cursor': {
      // The cursor arriving on the line of the clicked move keeps that move in the status line.
      if (message.line !== state.cursorLine || message.file !== state.cursorFile) state.picked = -1;
      state.cursorLine = message.line;
      state.cursorFile = message.file;
      const segments = highlight();
      if (segments.length && state.view) {
        const p = state.projected;
        const last = segments[segments.length - 1];
        state.view = revealPoint(state.view, p.x1[last], p.y1[last], state.width, state.height);
      }
      break;
    }
  }
  scheduleDraw();
});

planeSelect.addEventListener('change', () => {
  state.projected = project(state.packed, chosenPlane());
  fit();
});

function fit(): void {
  state.view = state.projected.bounds ? fitView(state.projected.bounds, state.width, state.height) : null;
  state.userMoved = false;
  mode3d.fit();
  scheduleDraw();
}
document.getElementById('fit')!.addEventListener('click', fit);

let drag: { x: number; y: number; moved: boolean } | null = null;
canvas.addEventListener('pointerdown', (event) => {
  drag = { x: event.offsetX, y: event.offsetY, moved: false };
  canvas.setPointerCapture(event.pointerId);
});
canvas.addEventListener('pointermove', (event) => {
  const view = state.view;
  if (drag && view) {
    const dx = event.offsetX - drag.x;
    const dy = event.offsetY - drag.y;
    if (drag.moved || Math.abs(dx) + Math.abs(dy) > 3) {
      drag.moved = true;
      state.userMoved = true;
      state.view = panBy(view, dx, dy);
      drag.x = event.offsetX;
      drag.y = event.offsetY;
      scheduleDraw();
    }
    return;
  }
  if (!view) return;
  const segment = pickMove(state.projected, view, event.offsetX, event.offsetY);
  if (segment < 0) {
    tip.style.display = 'none';
    return;
  }
  tip.textContent = describe(segment);
  tip.style.display = 'block';
  tip.style.left = `${Math.min(event.offsetX + 12, state.width - tip.offsetWidth - 4)}px`;
  tip.style.top = `${event.offsetY + 12}px`;
});
canvas.addEventListener('pointerup', (event) => {
  const wasDrag = drag?.moved;
  drag = null;
  if (wasDrag || !state.view) return;
  // A click on a hole's ring picks the hole, whose line is the cycle's call or positioning block.
  const segment = pickMove(state.projected, state.view, event.offsetX, event.offsetY);
  if (segment >= 0) pickedMove(state.projected.moveIndex[segment]);
});
canvas.addEventListener('pointerleave', () => {
  tip.style.display = 'none';
});
canvas.addEventListener(
  'wheel',
  (event) => {
    event.preventDefault();
    if (!state.view) return;
    state.userMoved = true;
    state.view = zoomAt(state.view, Math.exp(-event.deltaY * 0.0015), event.offsetX, event.offsetY);
    scheduleDraw();
  },
  { passive: false },
);
window.addEventListener('keydown', (event) => {
  if (event.key === 'f' || event.key === 'F') {
    fit();
    return;
  }
  if (!state.view || mode3d.active) return;
  const step = 40;
  const keys: Record<string, () => View> = {
    '+': () => zoomAt(state.view!, 1.25, state.width / 2, state.height / 2),
    '=': () => zoomAt(state.view!, 1.25, state.width / 2, state.height / 2),
    '-': () => zoomAt(state.view!, 0.8, state.width / 2, state.height / 2),
    ArrowLeft: () => panBy(state.view!, step, 0),
    ArrowRight: () => panBy(state.view!, -step, 0),
    ArrowUp: () => panBy(state.view!, 0, step),
    ArrowDown: () => panBy(state.view!, 0, -step),
  };
  if (keys[event.key]) {
    state.userMoved = true;
    state.view = keys[event.key]();
    scheduleDraw();
  }
});

// A resize (the panel below opening, the editor group resized) fits the drawing again unless the
// user panned or zoomed; then their view stays where it was.
new ResizeObserver(() => {
  resize();
  mode3d.resize(state.width, state.height);
  if (!state.userMoved) state.view = state.projected.bounds ? fitView(state.projected.bounds, state.width, state.height) : null;
  scheduleDraw();
}).observe(box);
resize();
vscode.postMessage({ type: 'ready' });
