// Drawing the projected toolpath on a 2D canvas: only chunks that touch the screen are visited, and
// segments shorter than a pixel are joined into one line (thinned), so that a program of a million
// moves draws in a few tens of milliseconds. The canvas is an interface so that unit tests can record
// what would be drawn.

import { CHUNK, KIND_ARC, KIND_ARC_UNVERIFIED, KIND_RAPID, KIND_UNCERTAIN, toScreen, type Projected, type View } from './geometry';

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

export type Palette = Record<'feed' | 'rapid' | 'uncertainFeed' | 'uncertainRapid' | 'highlight', Style>;

/** For dark themes: feed, rapid, both when a plane coordinate is uncertain, and the cursor's block. */
export const STYLES: Palette = {
  feed: { colour: '#3b8eea', width: 1.5, dash: [] },
  rapid: { colour: '#e05252', width: 1.5, dash: [6, 4] },
  uncertainFeed: { colour: '#d7a600', width: 1.5, dash: [2, 3] },
  uncertainRapid: { colour: '#d7a600', width: 1.5, dash: [6, 3, 2, 3] },
  highlight: { colour: '#ffd500', width: 4, dash: [] },
};

/** The same styles in darker colours, for light themes. */
export const LIGHT_STYLES: Palette = {
  feed: { ...STYLES.feed, colour: '#0b5cad' },
  rapid: { ...STYLES.rapid, colour: '#c62828' },
  uncertainFeed: { ...STYLES.uncertainFeed, colour: '#9a6b00' },
  uncertainRapid: { ...STYLES.uncertainRapid, colour: '#9a6b00' },
  highlight: { ...STYLES.highlight, colour: '#e07000' },
};

export type StyleName = keyof Palette;

export function styleOf(kind: number): StyleName {
  if (kind & KIND_UNCERTAIN) return kind & KIND_RAPID ? 'uncertainRapid' : 'uncertainFeed';
  return kind & KIND_RAPID ? 'rapid' : 'feed';
}

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
}

/** One path per style with its own pen, so that interleaved styles each thin on their own. */
class Pen {
  x = NaN;
  y = NaN;
  constructor(readonly path: PathLike) {}
}

const MIN_PIXELS = 0.75;

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
  highlight: [number, number] = [0, 0],
  palette: Palette = STYLES,
): RenderStats {
  ctx.clearRect(0, 0, width, height);
  ctx.fillStyle = background;
  ctx.fillRect(0, 0, width, height);
  const stats: RenderStats = { visited: 0, drawn: 0, thinned: 0, culledChunks: 0, arcsUnverified: 0 };
  const pens = new Map<StyleName, Pen>();
  const penFor = (style: StyleName) => {
    let pen = pens.get(style);
    if (!pen) {
      pen = new Pen(newPath());
      pens.set(style, pen);
    }
    return pen;
  };
  // The visible world rectangle, a little larger so that thick lines at the edge are drawn.
  const pad = 4 / view.scale;
  const left = -view.offsetX / view.scale - pad;
  const right = (width - view.offsetX) / view.scale + pad;
  const top = view.offsetY / view.scale + pad;
  const bottom = (view.offsetY - height) / view.scale - pad;
  const chunks = p.chunkBox.length / 4;
  for (let c = 0; c < chunks; c++) {
    const box = c * 4;
    if (p.chunkBox[box] > right || p.chunkBox[box + 2] < left || p.chunkBox[box + 1] > top || p.chunkBox[box + 3] < bottom) {
      stats.culledChunks++;
      continue;
    }
    for (let s = c * CHUNK; s < Math.min(p.count, (c + 1) * CHUNK); s++) {
      stats.visited++;
      if (p.kind[s] & KIND_ARC_UNVERIFIED) stats.arcsUnverified++;
      if (addSegment(p, view, s, penFor(styleOf(p.kind[s])))) stats.drawn++;
      else stats.thinned++;
    }
  }
  for (const [name, pen] of pens) {
    const style = palette[name];
    ctx.strokeStyle = style.colour;
    ctx.lineWidth = style.width;
    ctx.setLineDash(style.dash);
    ctx.stroke(pen.path);
  }
  const [first, end] = highlight;
  if (end > first) {
    const pen = new Pen(newPath());
    for (let s = first; s < end; s++) addSegment(p, view, s, pen);
    const style = palette.highlight;
    ctx.strokeStyle = style.colour;
    ctx.lineWidth = style.width;
    ctx.setLineDash(style.dash);
    ctx.stroke(pen.path);
    // A square on the block's end point, so that a move shorter than a pixel is still seen.
    const [ex, ey] = toScreen(view, p.x1[end - 1], p.y1[end - 1]);
    ctx.fillStyle = style.colour;
    ctx.fillRect(ex - 3, ey - 3, 6, 6);
  }
  return stats;
}
