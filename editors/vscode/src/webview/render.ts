// Drawing the projected toolpath on a 2D canvas: only chunks that touch the screen are visited, and
// segments shorter than a pixel are joined into one line (thinned), so that a program of a million
// moves draws in a few tens of milliseconds. The canvas is an interface so that unit tests can record
// what would be drawn. Moves on a way whose condition the analysis could not decide are drawn in their
// kind's style, faded. A rounding or chamfer the control inserts is drawn as what it is (an arc or a
// line) in the feed's colour, a little wider; a hole is a ring at its position.

import {
  CHUNK, HOLE_RADIUS_PX, KIND_ARC, KIND_ARC_IMPOSSIBLE, KIND_ARC_UNVERIFIED, KIND_CONDITIONAL, KIND_HOLE, KIND_INSERTED, KIND_RAPID, KIND_UNCERTAIN,
  toScreen, type Projected, type View,
} from './geometry';

/** The part of CanvasRenderingContext2D / Path2D used here. */
export interface PathLike {
  moveTo(x: number, y: number): void;
  lineTo(x: number, y: number): void;
  ellipse(x: number, y: number, rx: number, ry: number, rotation: number, start: number, end: number, anticlockwise: boolean): void;
}

export interface CanvasLike {
  strokeStyle: string | unknown;
  lineWidth: number;
  fillStyle: string | unknown;
  setLineDash(segments: number[]): void;
  stroke(path: PathLike): void;
  fillRect(x: number, y: number, w: number, h: number): void;
  clearRect(x: number, y: number, w: number, h: number): void;
}

export interface Style {
  colour: string;
  width: number;
  dash: number[];
}

export type Palette = Record<'feed' | 'rapid' | 'uncertainFeed' | 'uncertainRapid' | 'highlight' | 'inserted' | 'impossible', Style>;

/** For dark themes: feed, rapid, both when a plane coordinate is uncertain, the cursor's block, an
 * inserted rounding or chamfer at feed, and a circle that cannot exist (VS Code's error colour, in
 * short dashes unlike the rapid's long ones, with a cross on its middle). */
export const STYLES: Palette = {
  feed: { colour: '#3b8eea', width: 1.5, dash: [] },
  rapid: { colour: '#e05252', width: 1.5, dash: [6, 4] },
  uncertainFeed: { colour: '#d7a600', width: 1.5, dash: [2, 3] },
  uncertainRapid: { colour: '#d7a600', width: 1.5, dash: [6, 3, 2, 3] },
  highlight: { colour: '#ffd500', width: 4, dash: [] },
  inserted: { colour: '#3b8eea', width: 3, dash: [] },
  impossible: { colour: '#f14c4c', width: 2, dash: [3, 3] },
};

/** The same styles in darker colours, for light themes. */
export const LIGHT_STYLES: Palette = {
  feed: { ...STYLES.feed, colour: '#0b5cad' },
  rapid: { ...STYLES.rapid, colour: '#c62828' },
  uncertainFeed: { ...STYLES.uncertainFeed, colour: '#9a6b00' },
  uncertainRapid: { ...STYLES.uncertainRapid, colour: '#9a6b00' },
  highlight: { ...STYLES.highlight, colour: '#e07000' },
  inserted: { ...STYLES.inserted, colour: '#0b5cad' },
  impossible: { ...STYLES.impossible, colour: '#e51400' },
};

export type StyleName = keyof Palette;

export function styleOf(kind: number): StyleName {
  if (kind & KIND_ARC_IMPOSSIBLE) return 'impossible';
  if (kind & KIND_UNCERTAIN) return kind & KIND_RAPID ? 'uncertainRapid' : 'uncertainFeed';
  if (kind & KIND_RAPID) return 'rapid';
  return kind & KIND_INSERTED ? 'inserted' : 'feed';
}

/** The opacity of conditional moves, as the two hex digits appended to a `#rrggbb` colour. */
export const CONDITIONAL_ALPHA = '80';

/** A style's colour faded for conditional moves. */
export function fadedColour(colour: string): string {
  return /^#[0-9a-fA-F]{6}$/.test(colour) ? colour + CONDITIONAL_ALPHA : colour;
}

/** End-point squares are drawn on at most this many highlighted segments (else on the last only). */
export const MAX_MARKERS = 64;

export interface RenderStats {
  /** Segments visited (in chunks that touch the screen). */
  visited: number;
  /** Line and arc commands issued. */
  drawn: number;
  /** Segments joined into their neighbour because they were shorter than a pixel. */
  thinned: number;
  /** Chunks skipped as off screen. */
  culledChunks: number;
  arcsUnverified: number;
  /** Hole rings drawn (those on screen, at most one per cell of the ring's radius). */
  holes: number;
  /** Circles that cannot exist, drawn dashed and marked. */
  impossible: number;
}

/** Half the size of the cross on the middle of a circle that cannot exist, in pixels. */
export const IMPOSSIBLE_MARK_PX = 5;

/** One path per style with its own pen, so that interleaved styles each thin on their own. */
class Pen {
  x = NaN;
  y = NaN;
  constructor(readonly path: PathLike) {}
}

const MIN_PIXELS = 0.75;

/** Adds a ring around a screen point to a path. */
function addRing(path: PathLike, x: number, y: number, radius: number): void {
  path.moveTo(x + radius, y);
  path.ellipse(x, y, radius, radius, 0, 0, 2 * Math.PI, false);
}

/** Rings closer than this many pixels are one ring: they overlap too much to be told apart. */
const RING_CELL_PX = HOLE_RADIUS_PX;

/** Draws the rings of the holes on screen, in the colour of their move's style. A ring whose centre
 * falls in a cell of RING_CELL_PX that already has one is left out, so that a dense pattern at a
 * small zoom costs no more than the screen's cells. Returns how many were drawn. */
function drawHoles(ctx: CanvasLike, newPath: () => PathLike, p: Projected, view: View, width: number, height: number, palette: Palette): number {
  const paths = new Map<string, PathLike>();
  let drawn = 0;
  const margin = HOLE_RADIUS_PX + 2;
  const columns = Math.ceil((width + 2 * margin) / RING_CELL_PX) + 1;
  const rows = Math.ceil((height + 2 * margin) / RING_CELL_PX) + 1;
  const taken = p.holeSegment.length ? new Uint8Array(columns * rows) : new Uint8Array(0);
  for (let i = 0; i < p.holeSegment.length; i++) {
    const s = p.holeSegment[i];
    const [x, y] = toScreen(view, p.x0[s], p.y0[s]);
    if (!(x >= -margin && x <= width + margin && y >= -margin && y <= height + margin)) continue;
    const cell = Math.floor((y + margin) / RING_CELL_PX) * columns + Math.floor((x + margin) / RING_CELL_PX);
    if (taken[cell]) continue;
    taken[cell] = 1;
    const style = palette[styleOf(p.kind[s])];
    const colour = p.kind[s] & KIND_CONDITIONAL ? fadedColour(style.colour) : style.colour;
    let path = paths.get(colour);
    if (!path) paths.set(colour, (path = newPath()));
    addRing(path, x, y, HOLE_RADIUS_PX);
    drawn++;
  }
  for (const [colour, path] of paths) {
    ctx.strokeStyle = colour;
    ctx.lineWidth = 1.5;
    ctx.setLineDash([]);
    ctx.stroke(path);
  }
  return drawn;
}

/** Adds segment `s` to `pen`; returns whether a command was issued. */
function addSegment(p: Projected, view: View, s: number, pen: Pen): boolean {
  const [sx, sy] = toScreen(view, p.x0[s], p.y0[s]);
  const [ex, ey] = toScreen(view, p.x1[s], p.y1[s]);
  if (Number.isNaN(pen.x) || Math.abs(sx - pen.x) > MIN_PIXELS || Math.abs(sy - pen.y) > MIN_PIXELS) {
    pen.path.moveTo(sx, sy);
    pen.x = sx;
    pen.y = sy;
  }
  const bigArc = (p.kind[s] & KIND_ARC) !== 0 && Math.max(p.rx[s], p.ry[s]) * view.scale >= 1;
  if (bigArc) {
    const [cx, cy] = toScreen(view, p.cx[s], p.cy[s]);
    const start = -p.a0[s];
    const end = -(p.a0[s] + p.sweep[s]);
    pen.path.ellipse(cx, cy, p.rx[s] * view.scale, p.ry[s] * view.scale, 0, start, end, p.sweep[s] > 0);
    pen.x = ex;
    pen.y = ey;
    return true;
  }
  if (Math.abs(ex - pen.x) <= MIN_PIXELS && Math.abs(ey - pen.y) <= MIN_PIXELS) return false;
  pen.path.lineTo(ex, ey);
  pen.x = ex;
  pen.y = ey;
  return true;
}

export function render(
  ctx: CanvasLike,
  newPath: () => PathLike,
  p: Projected,
  view: View,
  width: number,
  height: number,
  background: string,
  highlight: ArrayLike<number> = [],
  palette: Palette = STYLES,
): RenderStats {
  ctx.clearRect(0, 0, width, height);
  ctx.fillStyle = background;
  ctx.fillRect(0, 0, width, height);
  const stats: RenderStats = { visited: 0, drawn: 0, thinned: 0, culledChunks: 0, arcsUnverified: 0, holes: 0, impossible: 0 };
  // One pen per style and per faded or not: index 2 * style + (conditional ? 1 : 0), looked up by kind.
  const names = Object.keys(palette) as StyleName[];
  const penOfKind = new Uint8Array(KIND_ARC_IMPOSSIBLE * 2);
  penOfKind.forEach((_, kind) => (penOfKind[kind] = 2 * names.indexOf(styleOf(kind)) + (kind & KIND_CONDITIONAL ? 1 : 0)));
  const pens: (Pen | undefined)[] = [];
  const penFor = (kind: number) => (pens[penOfKind[kind]] ??= new Pen(newPath()));
  // The visible world rectangle, a little larger so that thick lines at the edge are drawn.
  const pad = 4 / view.scale;
  const left = -view.offsetX / view.scale - pad;
  const right = (width - view.offsetX) / view.scale + pad;
  const top = view.offsetY / view.scale + pad;
  const bottom = (view.offsetY - height) / view.scale - pad;
  const chunks = p.chunkBox.length / 4;
  const impossible: number[] = [];
  for (let c = 0; c < chunks; c++) {
    const box = c * 4;
    if (p.chunkBox[box] > right || p.chunkBox[box + 2] < left || p.chunkBox[box + 1] > top || p.chunkBox[box + 3] < bottom) {
      stats.culledChunks++;
      continue;
    }
    for (let s = c * CHUNK; s < Math.min(p.count, (c + 1) * CHUNK); s++) {
      stats.visited++;
      if (p.kind[s] & KIND_ARC_UNVERIFIED) stats.arcsUnverified++;
      if (p.kind[s] & KIND_ARC_IMPOSSIBLE) impossible.push(s);
      if (addSegment(p, view, s, penFor(p.kind[s]))) stats.drawn++;
      // A move along the axis across the plane has no length here: it is not thinned, there is nothing to draw.
      else if (p.x0[s] !== p.x1[s] || p.y0[s] !== p.y1[s]) stats.thinned++;
    }
  }
  pens.forEach((pen, index) => {
    if (!pen) return;
    const style = palette[names[index >> 1]];
    ctx.strokeStyle = index & 1 ? fadedColour(style.colour) : style.colour;
    ctx.lineWidth = style.width;
    ctx.setLineDash(style.dash);
    ctx.stroke(pen.path);
  });
  stats.holes = drawHoles(ctx, newPath, p, view, width, height, palette);
  if (highlight.length > 0) {
    const pen = new Pen(newPath());
    for (let i = 0; i < highlight.length; i++) {
      const s = highlight[i];
      addSegment(p, view, s, pen);
      if (p.kind[s] & KIND_HOLE) {
        const [x, y] = toScreen(view, p.x0[s], p.y0[s]);
        addRing(pen.path, x, y, HOLE_RADIUS_PX);
        pen.x = NaN;
      }
    }
    const style = palette.highlight;
    ctx.strokeStyle = style.colour;
    ctx.lineWidth = style.width;
    ctx.setLineDash(style.dash);
    ctx.stroke(pen.path);
    // A square on each end point, so that a move shorter than a pixel is still seen; on the last
    // one only when there are many.
    ctx.fillStyle = style.colour;
    const first = highlight.length > MAX_MARKERS ? highlight.length - 1 : 0;
    for (let i = first; i < highlight.length; i++) {
      const [ex, ey] = toScreen(view, p.x1[highlight[i]], p.y1[highlight[i]]);
      ctx.fillRect(ex - 3, ey - 3, 6, 6);
    }
  }
  // The crosses last, so that a highlighted circle that cannot exist keeps its mark.
  stats.impossible = impossible.length;
  if (impossible.length) {
    const marks = newPath();
    for (const s of impossible) {
      const [mx, my] = toScreen(view, (p.x0[s] + p.x1[s]) / 2, (p.y0[s] + p.y1[s]) / 2);
      const r = IMPOSSIBLE_MARK_PX;
      marks.moveTo(mx - r, my - r);
      marks.lineTo(mx + r, my + r);
      marks.moveTo(mx - r, my + r);
      marks.lineTo(mx + r, my - r);
    }
    ctx.strokeStyle = palette.impossible.colour;
    ctx.lineWidth = 2;
    ctx.setLineDash([]);
    ctx.stroke(marks);
  }
  return stats;
}
