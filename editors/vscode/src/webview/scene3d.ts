// The toolpath in space, for the 3D view: every drawable move as straight segments (arcs tessellated
// from the server's centre, radius and sweep, helices rising along the axis across the arc's plane),
// each with its move and its kind (the same kinds as the plane view, so that both draw alike), and
// thinning into the buffers that are drawn: segments closer than a pixel at the current zoom are
// joined, as the plane view does. Plain functions on typed arrays, so that they run in the webview
// and in unit tests under Node; three.js is only in view3d.ts.

import { FLAG_CLOCKWISE, FLAG_CONDITIONAL, FLAG_INSERTED_MASK, FLAG_RAPID, FLAG_UNCERTAIN_X, holeAxis, type PackedToolpath } from '../core/packed';
import {
  arcScale, impossibleCircle, KIND_ARC, KIND_ARC_IMPOSSIBLE, KIND_ARC_UNVERIFIED, KIND_CONDITIONAL, KIND_HOLE, KIND_INSERTED, KIND_RAPID,
  KIND_UNCERTAIN, PLANE_AXES, type Plane,
} from './geometry';

export interface Bounds3 {
  min: [number, number, number];
  max: [number, number, number];
}

export interface Paths3d {
  /** Segments (tessellated arcs count once per piece). */
  count: number;
  /** x0, y0, z0, x1, y1, z1 of each segment, relative to `origin` (so that float32 keeps its digits). */
  points: Float32Array;
  /** The packed move each segment draws. */
  moveIndex: Uint32Array;
  /** The kind of each segment (KIND_* of geometry.ts). */
  kind: Uint8Array;
  origin: [number, number, number];
  bounds: Bounds3 | null;
  /** Moves left out because a coordinate is unknown. */
  hidden: number;
  /** Moves drawn from an arc whose numbers do not fit a circle: straight, as in the plane view. */
  arcsUnverified: number;
  /** Segments of conditional moves. */
  conditional: number;
  /** Circles that cannot exist (no arc from the server): drawn dashed in the error colour, marked. */
  impossible: number;
  /** Hole positions (x, y, z relative to `origin`, and the hole's move), one per hole as in the plane view. */
  holePoints: Float32Array;
  holeMove: Uint32Array;
  /** The first segment of each move (-1 when the move is not drawn), for the highlight. */
  firstSegment: Int32Array;
}

/** Chord error of tessellated arcs as a part of the toolpath's diagonal: far below a pixel when fitted. */
const ARC_TOLERANCE = 2e-4;
const MAX_ARC_PIECES = 256;

/** The plane of an arc: the two axes its centre has. */
function arcPlane(packed: PackedToolpath, arc: number): Plane | null {
  const has = (k: number) => !Number.isNaN(packed.arcCentre[arc * 3 + k]);
  if (has(0) && has(1)) return 'G17';
  if (has(2) && has(0)) return 'G18';
  if (has(1) && has(2)) return 'G19';
  return null;
}

/** Axes that never have a value in the whole program (a lathe's Y): drawn at 0 instead of hiding every move. */
function absentAxes(packed: PackedToolpath): boolean[] {
  const seen = [false, false, false];
  for (let i = 0; i < packed.count * 3; i++) {
    if (!Number.isNaN(packed.start[i]) || !Number.isNaN(packed.end[i])) seen[i % 3] = true;
  }
  return seen.map((s) => !s);
}

/** The kind of a move, as the plane view would give it, apart from arcs and holes. */
function baseKind(flags: number): number {
  let k = flags & FLAG_RAPID ? KIND_RAPID : 0;
  if (flags & (FLAG_UNCERTAIN_X | (FLAG_UNCERTAIN_X << 1) | (FLAG_UNCERTAIN_X << 2))) k |= KIND_UNCERTAIN;
  if (flags & FLAG_CONDITIONAL) k |= KIND_CONDITIONAL;
  if (flags & FLAG_INSERTED_MASK) k |= KIND_INSERTED;
  return k;
}

class Growable {
  points = new Float32Array(1024 * 6);
  moves = new Uint32Array(1024);
  kinds = new Uint8Array(1024);
  count = 0;
  push(a: ArrayLike<number>, b: ArrayLike<number>, move: number, kind: number): void {
    if (this.count === this.moves.length) {
      const size = this.count * 2;
      const points = new Float32Array(size * 6);
      points.set(this.points);
      const moves = new Uint32Array(size);
      moves.set(this.moves);
      const kinds = new Uint8Array(size);
      kinds.set(this.kinds);
      Object.assign(this, { points, moves, kinds });
    }
    this.points.set([a[0], a[1], a[2], b[0], b[1], b[2]], this.count * 6);
    this.moves[this.count] = move;
    this.kinds[this.count] = kind;
    this.count++;
  }
}

/** The segments of every drawable move, in the order the control runs them. */
export function buildPaths(packed: PackedToolpath): Paths3d {
  const absent = absentAxes(packed);
  const n = packed.count;
  const value = (array: Float64Array, i: number, k: number) => (absent[k] ? 0 : array[i * 3 + k]);
  // The origin: the first known start, so that coordinates stay small in float32.
  const origin: [number, number, number] = [0, 0, 0];
  for (let i = 0; i < n; i++) {
    const p = [0, 1, 2].map((k) => value(packed.start, i, k));
    if (p.every((v) => !Number.isNaN(v))) {
      origin.splice(0, 3, ...p);
      break;
    }
  }
  let min = [Infinity, Infinity, Infinity];
  let max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k++) {
      for (const v of [value(packed.start, i, k), value(packed.end, i, k)]) {
        if (!Number.isNaN(v)) {
          min[k] = Math.min(min[k], v);
          max[k] = Math.max(max[k], v);
        }
      }
    }
  }
  const diagonal = Math.hypot(...[0, 1, 2].map((k) => (max[k] > min[k] ? max[k] - min[k] : 0))) || 1;
  const tolerance = diagonal * ARC_TOLERANCE;
  const out = new Growable();
  const firstSegment = new Int32Array(n).fill(-1);
  const holes: number[] = [];
  const holeMoves: number[] = [];
  let hidden = 0;
  let arcsUnverified = 0;
  let conditional = 0;
  let impossible = 0;
  min = [Infinity, Infinity, Infinity];
  max = [-Infinity, -Infinity, -Infinity];
  const s = [0, 0, 0];
  const e = [0, 0, 0];
  const a = [0, 0, 0];
  const b = [0, 0, 0];
  let lastHole = -1;
  for (let i = 0; i < n; i++) {
    let known = true;
    for (let k = 0; k < 3; k++) {
      s[k] = value(packed.start, i, k) - origin[k];
      e[k] = value(packed.end, i, k) - origin[k];
      if (Number.isNaN(s[k]) || Number.isNaN(e[k])) known = false;
    }
    if (!known) {
      hidden++;
      continue;
    }
    for (let k = 0; k < 3; k++) {
      min[k] = Math.min(min[k], s[k], e[k]);
      max[k] = Math.max(max[k], s[k], e[k]);
    }
    const flags = packed.flags[i];
    let kind = baseKind(flags);
    if (kind & KIND_CONDITIONAL) conditional++;
    const axis = holeAxis(flags);
    if (axis >= 0) {
      // The pecks of one hole are one ring, as in the plane view: the same line drilling at the same place.
      const again = lastHole >= 0 && packed.line[lastHole] === packed.line[i] && packed.file[lastHole] === packed.file[i] &&
        [0, 1, 2].every((k) => k === axis || packed.start[lastHole * 3 + k] === packed.start[i * 3 + k]);
      if (!again) {
        kind |= KIND_HOLE;
        holes.push(s[0], s[1], s[2]);
        holeMoves.push(i);
      }
      lastHole = i;
    }
    firstSegment[i] = out.count;
    const arc = packed.arcOf[i];
    const plane = arc >= 0 ? arcPlane(packed, arc) : null;
    if (arc >= 0 && plane) {
      const [h, v] = PLANE_AXES[plane];
      const across = 3 - h - v;
      const ch = packed.arcCentre[arc * 3 + h] - origin[h];
      const cv = packed.arcCentre[arc * 3 + v] - origin[v];
      const radius = packed.arcRadius[arc];
      const scale = arcScale(s[h], s[v], e[h], e[v], ch, cv, radius);
      if (scale) {
        const rh = radius / scale[0];
        const rv = radius / scale[1];
        const a0 = Math.atan2((s[v] - cv) * scale[1], (s[h] - ch) * scale[0]);
        const magnitude = (packed.arcSweep[arc] * Math.PI) / 180;
        const sweep = flags & FLAG_CLOCKWISE ? -magnitude : magnitude;
        const r = Math.max(rh, rv);
        const step = r > tolerance ? 2 * Math.acos(Math.max(-1, 1 - tolerance / r)) : Math.PI / 2;
        const pieces = Math.min(MAX_ARC_PIECES, Math.max(2, Math.ceil(Math.abs(sweep) / step)));
        a[0] = s[0];
        a[1] = s[1];
        a[2] = s[2];
        for (let piece = 1; piece <= pieces; piece++) {
          const t = piece / pieces;
          if (piece === pieces) {
            b[0] = e[0];
            b[1] = e[1];
            b[2] = e[2];
          } else {
            const angle = a0 + sweep * t;
            b[h] = ch + rh * Math.cos(angle);
            b[v] = cv + rv * Math.sin(angle);
            b[across] = s[across] + (e[across] - s[across]) * t;
          }
          out.push(a, b, i, kind | KIND_ARC);
          for (let k = 0; k < 3; k++) {
            min[k] = Math.min(min[k], b[k]);
            max[k] = Math.max(max[k], b[k]);
            a[k] = b[k];
          }
        }
        continue;
      }
      arcsUnverified++;
      kind |= KIND_ARC_UNVERIFIED;
    } else if (arc >= 0) {
      arcsUnverified++;
      kind |= KIND_ARC_UNVERIFIED;
    } else if (impossibleCircle(packed, i)) {
      kind |= KIND_ARC_IMPOSSIBLE;
      impossible++;
    }
    out.push(s, e, i, kind);
  }
  const count = out.count;
  return {
    count,
    points: out.points.slice(0, count * 6),
    moveIndex: out.moves.slice(0, count),
    kind: out.kinds.slice(0, count),
    origin,
    bounds: count ? { min: min as Bounds3['min'], max: max as Bounds3['max'] } : null,
    hidden,
    arcsUnverified,
    conditional,
    impossible,
    holePoints: Float32Array.from(holes),
    holeMove: Uint32Array.from(holeMoves),
    firstSegment,
  };
}

/** The drawn buffers of one style: segment end points, relative to the paths' origin. */
export interface Thinned {
  /** Per group key (see `groupOf`): x0, y0, z0, x1, y1, z1 of each drawn segment. */
  groups: Map<number, Float32Array>;
  drawn: number;
  /** Segments joined into their neighbour because they were shorter than the tolerance; a move
   * along the line of sight of no length is not counted. */
  thinned: number;
}

/** The group of a segment: its kind without the bits that do not change how it is drawn. */
export function groupOf(kind: number): number {
  return kind & (KIND_RAPID | KIND_UNCERTAIN | KIND_CONDITIONAL | KIND_INSERTED | KIND_ARC_IMPOSSIBLE);
}

/** Joins, per group, segments that end within `tolerance` of where the group's pen is (a pixel at the
 * current zoom), as the plane view does on screen. */
export function thin(paths: Paths3d, tolerance: number): Thinned {
  const pens = new Map<number, { x: number; y: number; z: number; out: number[] }>();
  let drawn = 0;
  let thinned = 0;
  const p = paths.points;
  for (let s = 0; s < paths.count; s++) {
    const group = groupOf(paths.kind[s]);
    let pen = pens.get(group);
    if (!pen) pens.set(group, (pen = { x: NaN, y: NaN, z: NaN, out: [] }));
    const o = s * 6;
    const far = (x: number, y: number, z: number) =>
      !(Math.abs(x - pen!.x) <= tolerance && Math.abs(y - pen!.y) <= tolerance && Math.abs(z - pen!.z) <= tolerance);
    if (far(p[o], p[o + 1], p[o + 2])) {
      pen.x = p[o];
      pen.y = p[o + 1];
      pen.z = p[o + 2];
    }
    if (!far(p[o + 3], p[o + 4], p[o + 5])) {
      if (p[o] !== p[o + 3] || p[o + 1] !== p[o + 4] || p[o + 2] !== p[o + 5]) thinned++;
      continue;
    }
    pen.out.push(pen.x, pen.y, pen.z, p[o + 3], p[o + 4], p[o + 5]);
    pen.x = p[o + 3];
    pen.y = p[o + 4];
    pen.z = p[o + 5];
    drawn++;
  }
  const groups = new Map<number, Float32Array>();
  for (const [group, pen] of pens) if (pen.out.length) groups.set(group, Float32Array.from(pen.out));
  return { groups, drawn, thinned };
}

/** Fewer segments for the frames while the user orbits, pans or zooms a large toolpath: runs of
 * `stride` drawn segments of a group become one, from the run's first start to its last end, so
 * that at most about `budget` segments are drawn; the full drawing returns when the user lets go. */
export function coarsen(groups: Map<number, Float32Array>, budget: number): Map<number, Float32Array> {
  let total = 0;
  for (const points of groups.values()) total += points.length / 6;
  const stride = Math.ceil(total / Math.max(1, budget));
  if (stride <= 1) return groups;
  const out = new Map<number, Float32Array>();
  for (const [group, points] of groups) {
    const count = points.length / 6;
    const runs = Math.ceil(count / stride);
    const coarse = new Float32Array(runs * 6);
    for (let run = 0; run < runs; run++) {
      const first = run * stride;
      const last = Math.min(count, first + stride) - 1;
      coarse.set(points.subarray(first * 6, first * 6 + 3), run * 6);
      coarse.set(points.subarray(last * 6 + 3, last * 6 + 6), run * 6 + 3);
    }
    out.set(group, coarse);
  }
  return out;
}
