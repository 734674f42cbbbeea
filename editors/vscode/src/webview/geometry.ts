// The toolpath in the working plane: projection of the packed moves onto two axes, the view
// transform (pan and zoom) and picking a segment under the pointer (selection.ts finds the segments
// a line causes).
// Plain functions on typed arrays, so that they run in the webview and in unit tests under Node.

import {
  FLAG_CLOCKWISE, FLAG_CONDITIONAL, FLAG_INSERTED_MASK, FLAG_RAPID, FLAG_UNCERTAIN_X, holeAxis, MOTIONS, type PackedToolpath,
} from '../core/packed';

export type Plane = 'G17' | 'G18' | 'G19';

/** Indexes into X, Y, Z of the horizontal and the vertical axis of each plane (G18: Z to the right, X up). */
export const PLANE_AXES: Record<Plane, readonly [number, number]> = {
  G17: [0, 1],
  G18: [2, 0],
  G19: [1, 2],
};

export const PLANE_NAMES: Record<Plane, string> = { G17: 'X/Y', G18: 'Z/X', G19: 'Y/Z' };

export const KIND_RAPID = 1;
export const KIND_UNCERTAIN = 2;
export const KIND_ARC = 4;
/** An arc whose numbers do not fit a circle in this plane: drawn as a straight line, marked. */
export const KIND_ARC_UNVERIFIED = 8;
/** A move on a way whose condition the analysis could not decide. */
export const KIND_CONDITIONAL = 16;
/** A rounding or chamfer the control inserts at a corner. */
export const KIND_INSERTED = 32;
/** A hole: a drilling move along the axis perpendicular to the plane, drawn as a ring at its position. */
export const KIND_HOLE = 64;
/** A circle the server could not construct (a radius too small for its end point, numbers that do
 * not fit): its end point is known but no arc is, so it is drawn dashed in the error colour with a
 * marker instead of as a plain straight move. */
export const KIND_ARC_IMPOSSIBLE = 128;

const CIRCLE_MOTIONS = new Set(['G2', 'G3', 'CIP', 'CT'].map((name) => MOTIONS.indexOf(name as (typeof MOTIONS)[number])));

/** Whether move `i` is a circle without the server's arc: one that cannot exist or is not known. */
export function impossibleCircle(packed: PackedToolpath, i: number): boolean {
  return packed.arcOf[i] < 0 && CIRCLE_MOTIONS.has(packed.motion[i]);
}

/** The radius of a hole's ring on screen, in pixels (the tool's radius is not known). */
export const HOLE_RADIUS_PX = 4;

/** Segments per bounding box used to skip what is off screen. */
export const CHUNK = 256;

export interface Projected {
  plane: Plane;
  count: number;
  /** The packed move each segment draws. */
  moveIndex: Uint32Array;
  /** 1-based line of each segment in its move's file, in the order the control runs them. */
  line: Uint32Array;
  kind: Uint8Array;
  x0: Float64Array;
  y0: Float64Array;
  x1: Float64Array;
  y1: Float64Array;
  /** Arc parameters per segment (only where kind has KIND_ARC): an ellipse, because a transverse axis
   * shown as a diameter stretches circles. Angles in radians in plane coordinates (vertical up). */
  cx: Float64Array;
  cy: Float64Array;
  rx: Float64Array;
  ry: Float64Array;
  a0: Float64Array;
  /** Signed sweep in radians: positive counter-clockwise. */
  sweep: Float64Array;
  /** minX, minY, maxX, maxY of each run of CHUNK segments. */
  chunkBox: Float64Array;
  bounds: Bounds | null;
  /** Moves that cannot be drawn in this plane because a coordinate is unknown. */
  hidden: number;
  /** Segments drawn for conditional moves. */
  conditional: number;
  /** The segments that are holes (kind KIND_HOLE), in order; a hole drilled in several pecks is one. */
  holeSegment: Uint32Array;
}

export interface Bounds {
  minX: number;
  minY: number;
  maxX: number;
  maxY: number;
}

/** The plane a program most likely works in: the plane of its arcs, else the axes it moves. */
export function guessPlane(packed: PackedToolpath): Plane {
  const votes: Record<Plane, number> = { G17: 0, G18: 0, G19: 0 };
  for (let i = 0; i < packed.count; i++) {
    const arc = packed.arcOf[i];
    if (arc < 0) continue;
    const has = (k: number) => !Number.isNaN(packed.arcCentre[arc * 3 + k]);
    if (has(0) && has(1)) votes.G17++;
    else if (has(2) && has(0)) votes.G18++;
    else if (has(1) && has(2)) votes.G19++;
  }
  const best = (Object.keys(votes) as Plane[]).reduce((a, b) => (votes[b] > votes[a] ? b : a), 'G17');
  if (votes[best] > 0) return best;
  // Without arcs: an axis that never has a value rules its planes out.
  const seen = [false, false, false];
  for (let i = 0; i < packed.count * 3; i++) if (!Number.isNaN(packed.end[i])) seen[i % 3] = true;
  if (!seen[1] && seen[0] && seen[2]) return 'G18';
  if (!seen[0] && seen[1] && seen[2]) return 'G19';
  return 'G17';
}

function relativeError(a: number, b: number): number {
  return Math.abs(a - b) / Math.max(Math.abs(b), 1e-9);
}

/** Scale factors (1 or 0.5) on the two plane axes under which start and end lie on the arc's circle:
 * 0.5 means the axis shows a diameter. Null when no such scale fits. */
export function arcScale(
  h0: number, v0: number, h1: number, v1: number, ch: number, cv: number, radius: number,
): [number, number] | null {
  const tolerance = 1e-4;
  for (const [sh, sv] of [[1, 1], [1, 0.5], [0.5, 1], [0.5, 0.5]] as const) {
    const r0 = Math.hypot((h0 - ch) * sh, (v0 - cv) * sv);
    const r1 = Math.hypot((h1 - ch) * sh, (v1 - cv) * sv);
    if (relativeError(r0, radius) < tolerance && relativeError(r1, radius) < tolerance) return [sh, sv];
  }
  return null;
}

export function project(packed: PackedToolpath, plane: Plane): Projected {
  const [h, v] = PLANE_AXES[plane];
  const n = packed.count;
  const moveIndex = new Uint32Array(n);
  const line = new Uint32Array(n);
  const kind = new Uint8Array(n);
  const x0 = new Float64Array(n);
  const y0 = new Float64Array(n);
  const x1 = new Float64Array(n);
  const y1 = new Float64Array(n);
  const cx = new Float64Array(n);
  const cy = new Float64Array(n);
  const rx = new Float64Array(n);
  const ry = new Float64Array(n);
  const a0 = new Float64Array(n);
  const sweep = new Float64Array(n);
  let count = 0;
  let hidden = 0;
  let conditional = 0;
  // The tool axis of the plane view: the one the picture does not show.
  const across = 3 - h - v;
  const holes: number[] = [];
  for (let i = 0; i < n; i++) {
    const sh = packed.start[i * 3 + h];
    const sv = packed.start[i * 3 + v];
    const eh = packed.end[i * 3 + h];
    const ev = packed.end[i * 3 + v];
    if (Number.isNaN(sh) || Number.isNaN(sv) || Number.isNaN(eh) || Number.isNaN(ev)) {
      hidden++;
      continue;
    }
    const flags = packed.flags[i];
    let k = flags & FLAG_RAPID ? KIND_RAPID : 0;
    if (flags & ((FLAG_UNCERTAIN_X << h) | (FLAG_UNCERTAIN_X << v))) k |= KIND_UNCERTAIN;
    if (flags & FLAG_CONDITIONAL) {
      k |= KIND_CONDITIONAL;
      conditional++;
    }
    if (flags & FLAG_INSERTED_MASK) k |= KIND_INSERTED;
    if (holeAxis(flags) === across) {
      // The pecks of one hole (CYCLE83) are one ring: the same line drilling again at the same place.
      const last = holes.length ? holes[holes.length - 1] : -1;
      const lastMove = last >= 0 ? moveIndex[last] : -1;
      const again = last >= 0 && x0[last] === sh && y0[last] === sv && packed.line[lastMove] === packed.line[i] && packed.file[lastMove] === packed.file[i];
      if (!again) {
        k |= KIND_HOLE;
        holes.push(count);
      }
    }
    const arc = packed.arcOf[i];
    if (arc >= 0) {
      const ch = packed.arcCentre[arc * 3 + h];
      const cv = packed.arcCentre[arc * 3 + v];
      const radius = packed.arcRadius[arc];
      const scale = Number.isNaN(ch) || Number.isNaN(cv) ? null : arcScale(sh, sv, eh, ev, ch, cv, radius);
      if (scale) {
        k |= KIND_ARC;
        cx[count] = ch;
        cy[count] = cv;
        rx[count] = radius / scale[0];
        ry[count] = radius / scale[1];
        a0[count] = Math.atan2((sv - cv) * scale[1], (sh - ch) * scale[0]);
        const magnitude = (packed.arcSweep[arc] * Math.PI) / 180;
        sweep[count] = flags & FLAG_CLOCKWISE ? -magnitude : magnitude;
      } else {
        k |= KIND_ARC_UNVERIFIED;
      }
    } else if (impossibleCircle(packed, i)) {
      k |= KIND_ARC_IMPOSSIBLE;
    }
    moveIndex[count] = i;
    line[count] = packed.line[i];
    kind[count] = k;
    x0[count] = sh;
    y0[count] = sv;
    x1[count] = eh;
    y1[count] = ev;
    count++;
  }
  const chunks = Math.ceil(count / CHUNK);
  const chunkBox = new Float64Array(chunks * 4);
  let bounds: Bounds | null = null;
  for (let c = 0; c < chunks; c++) {
    let minX = Infinity;
    let minY = Infinity;
    let maxX = -Infinity;
    let maxY = -Infinity;
    for (let s = c * CHUNK; s < Math.min(count, (c + 1) * CHUNK); s++) {
      minX = Math.min(minX, x0[s], x1[s]);
      maxX = Math.max(maxX, x0[s], x1[s]);
      minY = Math.min(minY, y0[s], y1[s]);
      maxY = Math.max(maxY, y0[s], y1[s]);
      if (kind[s] & KIND_ARC) {
        // The arc stays inside its ellipse's box.
        minX = Math.min(minX, cx[s] - rx[s]);
        maxX = Math.max(maxX, cx[s] + rx[s]);
        minY = Math.min(minY, cy[s] - ry[s]);
        maxY = Math.max(maxY, cy[s] + ry[s]);
      }
    }
    chunkBox.set([minX, minY, maxX, maxY], c * 4);
    bounds = bounds
      ? {
          minX: Math.min(bounds.minX, minX),
          minY: Math.min(bounds.minY, minY),
          maxX: Math.max(bounds.maxX, maxX),
          maxY: Math.max(bounds.maxY, maxY),
        }
      : { minX, minY, maxX, maxY };
  }
  return {
    plane, count, moveIndex, line, kind, x0, y0, x1, y1, cx, cy, rx, ry, a0, sweep, chunkBox, bounds, hidden, conditional,
    holeSegment: Uint32Array.from(holes),
  };
}

/** Screen x = offsetX + scale * h; screen y = offsetY - scale * v (the vertical axis points up). */
export interface View {
  scale: number;
  offsetX: number;
  offsetY: number;
}

export function fitView(bounds: Bounds | null, width: number, height: number, marginPx = 20): View {
  if (!bounds) return { scale: 1, offsetX: width / 2, offsetY: height / 2 };
  const spanX = Math.max(bounds.maxX - bounds.minX, 1e-6);
  const spanY = Math.max(bounds.maxY - bounds.minY, 1e-6);
  const usableW = Math.max(width - 2 * marginPx, 1);
  const usableH = Math.max(height - 2 * marginPx, 1);
  const scale = Math.min(usableW / spanX, usableH / spanY);
  const midX = (bounds.minX + bounds.maxX) / 2;
  const midY = (bounds.minY + bounds.maxY) / 2;
  return { scale, offsetX: width / 2 - midX * scale, offsetY: height / 2 + midY * scale };
}

export function toScreen(view: View, x: number, y: number): [number, number] {
  return [view.offsetX + x * view.scale, view.offsetY - y * view.scale];
}

export function toWorld(view: View, sx: number, sy: number): [number, number] {
  return [(sx - view.offsetX) / view.scale, (view.offsetY - sy) / view.scale];
}

/** Zooms by `factor` keeping the world point under (sx, sy) where it is. */
export function zoomAt(view: View, factor: number, sx: number, sy: number): View {
  const scale = Math.min(Math.max(view.scale * factor, 1e-9), 1e12);
  const [wx, wy] = toWorld(view, sx, sy);
  return { scale, offsetX: sx - wx * scale, offsetY: sy + wy * scale };
}

export function panBy(view: View, dx: number, dy: number): View {
  return { scale: view.scale, offsetX: view.offsetX + dx, offsetY: view.offsetY + dy };
}

/** Centres the world point when it is off screen (closer to an edge than `margin`, which is less than
 * fitView's margin so that a fitted drawing never moves). */
export function revealPoint(view: View, x: number, y: number, width: number, height: number, margin = 10): View {
  const [sx, sy] = toScreen(view, x, y);
  let dx = 0;
  let dy = 0;
  if (sx < margin || sx > width - margin) dx = width / 2 - sx;
  if (sy < margin || sy > height - margin) dy = height / 2 - sy;
  return dx === 0 && dy === 0 ? view : panBy(view, dx, dy);
}

function normaliseAngle(angle: number): number {
  const turn = 2 * Math.PI;
  return ((angle % turn) + turn) % turn;
}

/** Distance in world units from (px, py) to segment s. */
export function distanceToSegment(p: Projected, s: number, px: number, py: number): number {
  if (p.kind[s] & KIND_ARC) {
    // Distance to the ellipse, measured in the circle's frame and scaled back: exact for circles,
    // close enough for picking on stretched ones.
    const ux = (px - p.cx[s]) / p.rx[s];
    const uy = (py - p.cy[s]) / p.ry[s];
    const angle = Math.atan2(uy, ux);
    const sweep = p.sweep[s];
    const along = sweep >= 0 ? normaliseAngle(angle - p.a0[s]) : normaliseAngle(p.a0[s] - angle);
    if (along <= Math.abs(sweep) + 1e-9 || Math.abs(sweep) >= 2 * Math.PI - 1e-9) {
      const radial = Math.abs(Math.hypot(ux, uy) - 1);
      return radial * Math.min(p.rx[s], p.ry[s]);
    }
    return Math.min(Math.hypot(px - p.x0[s], py - p.y0[s]), Math.hypot(px - p.x1[s], py - p.y1[s]));
  }
  const dx = p.x1[s] - p.x0[s];
  const dy = p.y1[s] - p.y0[s];
  const lengthSquared = dx * dx + dy * dy;
  const t = lengthSquared === 0 ? 0 : Math.min(1, Math.max(0, ((px - p.x0[s]) * dx + (py - p.y0[s]) * dy) / lengthSquared));
  return Math.hypot(px - (p.x0[s] + t * dx), py - (p.y0[s] + t * dy));
}

/** The segment nearest to the screen point within `tolerancePx`, or -1. */
export function pick(p: Projected, view: View, sx: number, sy: number, tolerancePx = 6): number {
  const [px, py] = toWorld(view, sx, sy);
  const tolerance = tolerancePx / view.scale;
  let best = -1;
  let bestDistance = tolerance;
  const chunks = p.chunkBox.length / 4;
  for (let c = 0; c < chunks; c++) {
    const box = c * 4;
    if (
      px < p.chunkBox[box] - tolerance || px > p.chunkBox[box + 2] + tolerance ||
      py < p.chunkBox[box + 1] - tolerance || py > p.chunkBox[box + 3] + tolerance
    ) {
      continue;
    }
    for (let s = c * CHUNK; s < Math.min(p.count, (c + 1) * CHUNK); s++) {
      const distance = distanceToSegment(p, s, px, py);
      if (distance <= bestDistance) {
        best = s;
        bestDistance = distance;
      }
    }
  }
  return best;
}

/** The hole whose ring (of HOLE_RADIUS_PX, plus `tolerancePx`) is nearest to the screen point, as
 * its segment, or -1. */
export function pickHole(p: Projected, view: View, sx: number, sy: number, tolerancePx = 3): number {
  const reach = HOLE_RADIUS_PX + tolerancePx;
  let best = -1;
  let bestDistance = reach;
  for (let i = 0; i < p.holeSegment.length; i++) {
    const s = p.holeSegment[i];
    const [hx, hy] = toScreen(view, p.x0[s], p.y0[s]);
    const distance = Math.hypot(hx - sx, hy - sy);
    if (distance <= bestDistance) {
      best = s;
      bestDistance = distance;
    }
  }
  return best;
}

/** What the pointer is on: a hole when it is inside a hole's ring (a ring covers the rapid moves that
 * lead to it and away), else the nearest segment; -1 for nothing. */
export function pickMove(p: Projected, view: View, sx: number, sy: number): number {
  const hole = pickHole(p, view, sx, sy);
  return hole >= 0 ? hole : pick(p, view, sx, sy);
}
