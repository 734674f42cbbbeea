// The toolpath page's glue: messages from the extension, pointer and keyboard input, and redraws on
// the next animation frame. The drawing itself is in render.ts and the geometry in geometry.ts.

import type { FromPage, ToPage } from '../core/messages';
import { AXES, concatPacked, emptyPacked, FLAG_UNCERTAIN_X, MOTIONS, revivePacked, type PackedToolpath } from '../core/packed';
import {
  fitView, guessPlane, KIND_UNCERTAIN, panBy, pick, PLANE_NAMES, project, revealPoint, segmentsOfLine, zoomAt,
  type Plane, type View,
} from './geometry';
import { LIGHT_STYLES, render, STYLES, type RenderStats } from './render';

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
  cursorLine: 0,
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

// For the browser test: the state and the functions it needs to find segments on screen.
(window as unknown as { toolpathDebug: unknown }).toolpathDebug = { state, segmentsOfLine, redrawNow: () => draw() };

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
  const background = getComputedStyle(document.body).backgroundColor || '#1e1e1e';
  const view = state.view ?? fitView(state.projected.bounds, state.width, state.height);
  const started = performance.now();
  const highlight = state.cursorLine ? segmentsOfLine(state.projected, state.cursorLine) : ([0, 0] as [number, number]);
  // VS Code marks the webview's body with the kind of theme.
  const light = document.body.classList.contains('vscode-light') || document.body.classList.contains('vscode-high-contrast-light');
  state.stats = render(context, () => new Path2D(), state.projected, view, state.width, state.height, background, highlight, light ? LIGHT_STYLES : STYLES);
  state.renderMs = performance.now() - started;
  updateStatus(highlight);
}

function updateStatus(highlight: [number, number]): void {
  if (state.error) {
    statusLine.textContent = state.error;
    return;
  }
  const p = state.projected;
  const parts = [
    `${state.title}: ${state.packed.count.toLocaleString('en')} moves` +
      (state.done ? '' : state.progressive ? ' (loading…)' : ` (updating after the edit: ${state.arrived.toLocaleString('en')} moves so far)`),
    `plane ${p.plane} ${PLANE_NAMES[p.plane]}`,
    state.units,
  ];
  if (p.hidden) parts.push(`${p.hidden.toLocaleString('en')} not drawn (position unknown in this plane)`);
  if (state.stats?.thinned) parts.push(`${state.stats.thinned.toLocaleString('en')} thinned at this zoom`);
  if (state.stats?.arcsUnverified) parts.push(`${state.stats.arcsUnverified} arcs drawn straight (centre does not fit)`);
  if (state.cursorLine) {
    parts.push(highlight[1] > highlight[0] ? `line ${state.cursorLine}` : `line ${state.cursorLine}: no move in this plane`);
  }
  statusLine.textContent = parts.join(' · ');
}

function describe(segment: number): string {
  const p = state.projected;
  const move = p.moveIndex[segment];
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
  const uncertain = p.kind[segment] & KIND_UNCERTAIN ? '\nuncertain: the control may take another path here' : '';
  return `line ${p.line[segment]}  ${MOTIONS[packed.motion[move]]}  → ${end}${feed}${uncertain}`;
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
      }
      state.generation = message.generation;
      state.title = message.title;
      state.units = message.units;
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
      if (!state.progressive) state.parts = state.incoming;
      state.incoming = [];
      if (!state.progressive || state.projectPending) reproject();
      break;
    case 'error':
      if (message.generation !== state.generation) return;
      state.error = message.message;
      break;
    case 'cursor': {
      state.cursorLine = message.line;
      const [first, end] = segmentsOfLine(state.projected, message.line);
      if (end > first && state.view) {
        const p = state.projected;
        state.view = revealPoint(state.view, p.x1[end - 1], p.y1[end - 1], state.width, state.height);
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
  const segment = pick(state.projected, view, event.offsetX, event.offsetY);
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
  const segment = pick(state.projected, state.view, event.offsetX, event.offsetY);
  if (segment >= 0) {
    state.cursorLine = state.projected.line[segment];
    vscode.postMessage({ type: 'reveal', line: state.projected.line[segment] });
    scheduleDraw();
  }
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
  if (!state.view) return;
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
  if (event.key === 'f' || event.key === 'F') {
    fit();
  } else if (keys[event.key]) {
    state.userMoved = true;
    state.view = keys[event.key]();
    scheduleDraw();
  }
});

new ResizeObserver(() => {
  const hadData = state.view !== null;
  resize();
  if (hadData) scheduleDraw();
  else fit();
}).observe(box);
resize();
vscode.postMessage({ type: 'ready' });
