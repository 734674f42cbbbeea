// The 3D view of the toolpath with three.js: an orthographic camera (a pixel is the same length
// everywhere, so thinning at the current zoom works as in the plane view) that orbits, pans and zooms
// with OrbitControls; one line object per style, the highlight and the inserted elements as wide
// lines on top, holes and the marks of circles that cannot exist as points of a constant size.
// Picking projects the segments on the CPU, a chunk's box first, so that a click in a million moves
// stays within a frame or two.

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { CHUNK, HOLE_RADIUS_PX, KIND_CONDITIONAL, KIND_INSERTED } from './geometry';
import { IMPOSSIBLE_MARK_PX, styleOf, type Palette } from './render';
import { coarsen, thin, type Paths3d } from './scene3d';

/** Segments of the highlight beyond this many are drawn one pixel wide (wide lines cost a quad each). */
const MAX_WIDE_HIGHLIGHT = 200_000;
/** The thinning is computed again when the size of a pixel changed by more than this factor. */
const RETHIN_FACTOR = 2;
const MIN_PIXELS = 0.75;
/** Segments drawn in the frames while the user orbits, pans or zooms (see `coarsen`). */
const INTERACTION_BUDGET = 40_000;

export interface Stats3d {
  drawn: number;
  thinned: number;
  renderMs: number;
  thinMs: number;
  /** The last frame drew the coarse drawing of an interaction. */
  coarse: boolean;
}

/** A texture of a ring or a cross, drawn once on a small canvas, for points of a constant size. */
function spriteTexture(shape: 'ring' | 'cross', size: number): THREE.Texture {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size * 4;
  const ctx = canvas.getContext('2d')!;
  ctx.scale(4, 4);
  ctx.strokeStyle = '#ffffff';
  ctx.lineWidth = shape === 'ring' ? 1.5 : 2;
  ctx.beginPath();
  if (shape === 'ring') {
    ctx.arc(size / 2, size / 2, HOLE_RADIUS_PX, 0, 2 * Math.PI);
  } else {
    const r = IMPOSSIBLE_MARK_PX;
    const c = size / 2;
    ctx.moveTo(c - r, c - r);
    ctx.lineTo(c + r, c + r);
    ctx.moveTo(c - r, c + r);
    ctx.lineTo(c + r, c - r);
  }
  ctx.stroke();
  return new THREE.CanvasTexture(canvas);
}

export class View3d {
  readonly renderer: THREE.WebGLRenderer;
  readonly camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.001, 1000);
  readonly controls: OrbitControls;
  private readonly scene = new THREE.Scene();
  private readonly content = new THREE.Group();
  /** The coarse drawing for the frames of an interaction with a large toolpath (empty otherwise). */
  private readonly coarse = new THREE.Group();
  private interacting = false;
  private readonly overlay = new THREE.Group();
  private paths: Paths3d | null = null;
  private chunkBox = new Float32Array(0);
  private palette: Palette | null = null;
  private builtTolerance = NaN;
  private width = 1;
  private height = 1;
  /** Half the height of the fitted frustum, in world units. */
  private halfHeight = 1;
  private fitting = false;
  private readonly ringTexture = spriteTexture('ring', 2 * HOLE_RADIUS_PX + 4);
  private readonly crossTexture = spriteTexture('cross', 2 * IMPOSSIBLE_MARK_PX + 4);
  /** The user orbited, panned or zoomed: new data and a resize no longer refit. */
  userMoved = false;
  stats: Stats3d = { drawn: 0, thinned: 0, renderMs: 0, thinMs: 0, coarse: false };

  constructor(readonly canvas: HTMLCanvasElement, private readonly changed: () => void) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.screenSpacePanning = true;
    this.controls.zoomToCursor = true;
    this.controls.addEventListener('change', () => {
      if (!this.fitting) this.userMoved = true;
      this.changed();
    });
    this.controls.addEventListener('start', () => {
      this.interacting = true;
    });
    this.controls.addEventListener('end', () => {
      this.interacting = false;
      this.changed();
    });
    this.scene.add(this.content, this.coarse, this.overlay);
  }

  /** The world position (the program's coordinates) of a point relative to the paths' origin. */
  private relative(x: number, y: number, z: number): THREE.Vector3 {
    const o = this.paths?.origin ?? [0, 0, 0];
    return new THREE.Vector3(x - o[0], y - o[1], z - o[2]);
  }

  /** Where a point of the program (absolute coordinates) is on the canvas, in CSS pixels. */
  toScreen(x: number, y: number, z: number): [number, number] {
    const p = this.relative(x, y, z).project(this.camera);
    return [((p.x + 1) / 2) * this.width, ((1 - p.y) / 2) * this.height];
  }

  setPaths(paths: Paths3d): void {
    this.paths = paths;
    const chunks = Math.ceil(paths.count / CHUNK);
    this.chunkBox = new Float32Array(chunks * 6);
    for (let c = 0; c < chunks; c++) {
      const box = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
      for (let s = c * CHUNK; s < Math.min(paths.count, (c + 1) * CHUNK); s++) {
        for (let k = 0; k < 6; k++) {
          const v = paths.points[s * 6 + k];
          box[k % 3] = Math.min(box[k % 3], v);
          box[3 + (k % 3)] = Math.max(box[3 + (k % 3)], v);
        }
      }
      this.chunkBox.set(box, c * 6);
    }
    this.builtTolerance = NaN;
    if (!this.userMoved) this.fit();
  }

  resize(width: number, height: number): void {
    this.width = Math.max(1, width);
    this.height = Math.max(1, height);
    this.renderer.setSize(this.width, this.height, false);
    if (this.userMoved) this.frame();
    else this.fit();
  }

  /** The frustum for the current aspect around the kept half height. */
  private frame(): void {
    const aspect = this.width / this.height;
    Object.assign(this.camera, { left: -this.halfHeight * aspect, right: this.halfHeight * aspect, top: this.halfHeight, bottom: -this.halfHeight });
    this.camera.updateProjectionMatrix();
  }

  /** Looks at the whole toolpath from the front, right and above (Z up), filling the canvas. */
  fit(): void {
    const b = this.paths?.bounds;
    const min = new THREE.Vector3(...(b?.min ?? [-1, -1, -1]));
    const max = new THREE.Vector3(...(b?.max ?? [1, 1, 1]));
    const centre = min.clone().add(max).multiplyScalar(0.5);
    const radius = Math.max(max.distanceTo(min) / 2, 1e-3);
    const direction = new THREE.Vector3(1, -1.4, 1.1).normalize();
    this.fitting = true;
    this.camera.position.copy(centre).addScaledVector(direction, radius * 4);
    this.camera.near = radius * 0.01;
    this.camera.far = radius * 10;
    this.camera.zoom = 1;
    this.controls.target.copy(centre);
    this.camera.lookAt(centre);
    // The segments' end points seen from the camera decide the size (at most about 200,000 of them
    // looked at; without segments the box's corners), with a margin of 20 pixels as in the plane view.
    this.camera.updateMatrixWorld();
    const view = this.camera.matrixWorldInverse;
    const extent = [Infinity, Infinity, -Infinity, -Infinity];
    const p = new THREE.Vector3();
    const reach = () => {
      p.applyMatrix4(view);
      extent[0] = Math.min(extent[0], p.x);
      extent[1] = Math.min(extent[1], p.y);
      extent[2] = Math.max(extent[2], p.x);
      extent[3] = Math.max(extent[3], p.y);
    };
    const points = this.paths?.points;
    if (points && points.length) {
      const stride = Math.max(1, Math.ceil(points.length / 3 / 200_000));
      for (let i = 0; i < points.length / 3; i += stride) {
        p.set(points[i * 3], points[i * 3 + 1], points[i * 3 + 2]);
        reach();
      }
    } else {
      for (let corner = 0; corner < 8; corner++) {
        p.set(corner & 1 ? max.x : min.x, corner & 2 ? max.y : min.y, corner & 4 ? max.z : min.z);
        reach();
      }
    }
    // Centre what is seen: move the camera and its target across the line of sight.
    const local = centre.clone().applyMatrix4(view);
    const shift = new THREE.Vector3((extent[0] + extent[2]) / 2 - local.x, (extent[1] + extent[3]) / 2 - local.y, 0)
      .transformDirection(this.camera.matrixWorld)
      .multiplyScalar(Math.hypot((extent[0] + extent[2]) / 2 - local.x, (extent[1] + extent[3]) / 2 - local.y));
    this.camera.position.add(shift);
    this.controls.target.add(shift);
    const halfW = Math.max((extent[2] - extent[0]) / 2, 1e-6);
    const halfH = Math.max((extent[3] - extent[1]) / 2, 1e-6);
    const usableW = Math.max(this.width - 40, 1);
    const usableH = Math.max(this.height - 40, 1);
    // World units per pixel that fit both directions; the frustum's half height follows from it.
    const perPixel = Math.max((2 * halfW) / usableW, (2 * halfH) / usableH);
    this.halfHeight = (perPixel * this.height) / 2;
    this.frame();
    this.controls.update();
    this.fitting = false;
    this.userMoved = false;
    this.changed();
  }

  /** World units per CSS pixel at the current zoom. */
  worldPerPixel(): number {
    return (this.camera.top - this.camera.bottom) / this.camera.zoom / this.height;
  }

  private clear(group: THREE.Group): void {
    for (const child of [...group.children]) {
      group.remove(child);
      const object = child as THREE.Mesh;
      object.geometry?.dispose();
      (object.material as THREE.Material | undefined)?.dispose();
    }
  }

  /** Builds the drawn objects for the current pixel size (the thinning) and palette. */
  private rebuild(palette: Palette): void {
    const paths = this.paths;
    this.clear(this.content);
    this.palette = palette;
    if (!paths) return;
    const started = performance.now();
    const tolerance = this.worldPerPixel() * MIN_PIXELS;
    this.builtTolerance = tolerance;
    const thinned = thin(paths, tolerance);
    this.addLines(this.content, thinned.groups, palette);
    this.clear(this.coarse);
    if (thinned.drawn > INTERACTION_BUDGET) this.addLines(this.coarse, coarsen(thinned.groups, INTERACTION_BUDGET), palette);
    this.addMarks(paths, palette, thinned, started);
  }

  /** One line object per group (style), in the palette's colours and dashes. */
  private addLines(target: THREE.Group, groups: Map<number, Float32Array>, palette: Palette): void {
    for (const [group, points] of groups) {
      const style = palette[styleOf(group)];
      const faded = (group & KIND_CONDITIONAL) !== 0;
      if (group & KIND_INSERTED) {
        const geometry = new LineSegmentsGeometry().setPositions(points);
        const material = new LineMaterial({ color: style.colour, linewidth: style.width, transparent: faded, opacity: faded ? 0.5 : 1 });
        material.resolution.set(this.width, this.height);
        target.add(new LineSegments2(geometry, material));
        continue;
      }
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
      const dashed = style.dash.length > 0;
      let material: THREE.LineBasicMaterial;
      if (dashed) {
        // Each segment's dashes start at its own start; the distance along it is in world units and the
        // material's scale (set per frame) turns it into pixels.
        const distance = new Float32Array(points.length / 3);
        for (let i = 0; i < distance.length; i += 2) {
          const o = i * 3;
          distance[i + 1] = Math.hypot(points[o + 3] - points[o], points[o + 4] - points[o + 1], points[o + 5] - points[o + 2]);
        }
        geometry.setAttribute('lineDistance', new THREE.BufferAttribute(distance, 1));
        material = new THREE.LineDashedMaterial({ color: style.colour, dashSize: style.dash[0], gapSize: style.dash[1] });
      } else {
        material = new THREE.LineBasicMaterial({ color: style.colour });
      }
      if (faded) Object.assign(material, { transparent: true, opacity: 0.5 });
      target.add(new THREE.LineSegments(geometry, material));
    }
  }

  /** The holes, the marks of circles that cannot exist, and the statistics of the last build. */
  private addMarks(paths: Paths3d, palette: Palette, thinned: { drawn: number; thinned: number }, started: number): void {
    this.addPoints(this.content, paths.holePoints, this.ringTexture, 2 * HOLE_RADIUS_PX + 4, (i) => {
      const move = paths.holeMove[i];
      const s = paths.firstSegment[move];
      return palette[styleOf(s >= 0 ? paths.kind[s] : 0)].colour;
    });
    const marks: number[] = [];
    for (let s = 0; s < paths.count; s++) {
      if (styleOf(paths.kind[s]) !== 'impossible') continue;
      const o = s * 6;
      marks.push((paths.points[o] + paths.points[o + 3]) / 2, (paths.points[o + 1] + paths.points[o + 4]) / 2, (paths.points[o + 2] + paths.points[o + 5]) / 2);
    }
    this.addPoints(this.content, Float32Array.from(marks), this.crossTexture, 2 * IMPOSSIBLE_MARK_PX + 4, () => palette.impossible.colour);
    this.stats.drawn = thinned.drawn;
    this.stats.thinned = thinned.thinned;
    this.stats.thinMs = performance.now() - started;
  }

  private addPoints(group: THREE.Group, points: Float32Array, map: THREE.Texture | null, size: number, colour: (i: number) => string): void {
    if (!points.length) return;
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
    const colours = new Float32Array(points.length);
    const c = new THREE.Color();
    for (let i = 0; i < points.length / 3; i++) {
      c.set(colour(i));
      colours.set([c.r, c.g, c.b], i * 3);
    }
    geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    const material = new THREE.PointsMaterial({ size, sizeAttenuation: false, vertexColors: true, map, transparent: map !== null, alphaTest: map ? 0.3 : 0, depthTest: false });
    const object = new THREE.Points(geometry, material);
    object.renderOrder = 5;
    group.add(object);
  }

  /** Shows the segments of these moves on top, wide, in the highlight colour, with a square on each
   * end point (on the last only when there are many, as in the plane view). */
  setHighlight(moves: ArrayLike<number>, palette: Palette, maxMarkers: number): void {
    this.clear(this.overlay);
    const paths = this.paths;
    if (!paths || moves.length === 0) return;
    const points: number[] = [];
    const ends: number[] = [];
    const holes: number[] = [];
    for (let i = 0; i < moves.length; i++) {
      const move = moves[i];
      const first = paths.firstSegment[move];
      if (first < 0) continue;
      for (let s = first; s < paths.count && paths.moveIndex[s] === move; s++) {
        for (let k = 0; k < 6; k++) points.push(paths.points[s * 6 + k]);
      }
      const o = (points.length / 6 - 1) * 6;
      if (moves.length <= maxMarkers || i === moves.length - 1) ends.push(points[o + 3], points[o + 4], points[o + 5]);
    }
    const chosen = new Set(Array.from(moves));
    for (let h = 0; h < paths.holeMove.length; h++) {
      if (chosen.has(paths.holeMove[h])) holes.push(paths.holePoints[h * 3], paths.holePoints[h * 3 + 1], paths.holePoints[h * 3 + 2]);
    }
    const style = palette.highlight;
    const segments = Float32Array.from(points);
    let object: THREE.Object3D;
    if (segments.length / 6 <= MAX_WIDE_HIGHLIGHT) {
      const material = new LineMaterial({ color: style.colour, linewidth: style.width, depthTest: false });
      material.resolution.set(this.width, this.height);
      object = new LineSegments2(new LineSegmentsGeometry().setPositions(segments), material);
    } else {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(segments, 3));
      object = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: style.colour, depthTest: false }));
    }
    object.renderOrder = 10;
    this.overlay.add(object);
    this.addPoints(this.overlay, Float32Array.from(ends), null, 6, () => style.colour);
    this.addPoints(this.overlay, Float32Array.from(holes), this.ringTexture, 2 * HOLE_RADIUS_PX + 4, () => style.colour);
    for (const child of this.overlay.children) child.renderOrder = 10;
  }

  render(palette: Palette, background: string): Stats3d {
    const started = performance.now();
    const perPixel = this.worldPerPixel();
    const ratio = perPixel * MIN_PIXELS / this.builtTolerance;
    if (palette !== this.palette || !(ratio < RETHIN_FACTOR && ratio > 1 / RETHIN_FACTOR)) this.rebuild(palette);
    const coarse = this.interacting && this.coarse.children.length > 0;
    this.content.visible = !coarse;
    this.coarse.visible = coarse;
    this.stats.coarse = coarse;
    for (const group of [this.content, this.coarse, this.overlay]) {
      for (const child of group.children) {
        const material = (child as THREE.Mesh).material;
        if (material instanceof THREE.LineDashedMaterial) material.scale = 1 / perPixel;
        if (material instanceof LineMaterial) material.resolution.set(this.width, this.height);
      }
    }
    this.renderer.setClearColor(new THREE.Color(background));
    this.renderer.render(this.scene, this.camera);
    this.stats.renderMs = performance.now() - started;
    return this.stats;
  }

  /** The move under a canvas point: a hole within its ring first, else the nearest segment within
   * `tolerancePx`; -1 for nothing. */
  pick(sx: number, sy: number, tolerancePx = 6): number {
    const paths = this.paths;
    if (!paths) return -1;
    this.camera.updateMatrixWorld();
    const m = new THREE.Matrix4().multiplyMatrices(this.camera.projectionMatrix, this.camera.matrixWorldInverse).elements;
    const w = this.width;
    const h = this.height;
    // Orthographic: no division by w.
    const screenX = (x: number, y: number, z: number) => ((m[0] * x + m[4] * y + m[8] * z + m[12] + 1) / 2) * w;
    const screenY = (x: number, y: number, z: number) => ((1 - (m[1] * x + m[5] * y + m[9] * z + m[13])) / 2) * h;
    const reach = HOLE_RADIUS_PX + 3;
    let best = -1;
    let bestDistance = reach;
    const holes = paths.holePoints;
    for (let i = 0; i < paths.holeMove.length; i++) {
      const d = Math.hypot(screenX(holes[i * 3], holes[i * 3 + 1], holes[i * 3 + 2]) - sx, screenY(holes[i * 3], holes[i * 3 + 1], holes[i * 3 + 2]) - sy);
      if (d <= bestDistance) {
        best = paths.holeMove[i];
        bestDistance = d;
      }
    }
    if (best >= 0) return best;
    bestDistance = tolerancePx;
    const p = paths.points;
    const box = this.chunkBox;
    for (let c = 0; c < box.length / 6; c++) {
      let minX = Infinity;
      let maxX = -Infinity;
      let minY = Infinity;
      let maxY = -Infinity;
      for (let corner = 0; corner < 8; corner++) {
        const x = box[c * 6 + (corner & 1 ? 3 : 0)];
        const y = box[c * 6 + (corner & 2 ? 4 : 1)];
        const z = box[c * 6 + (corner & 4 ? 5 : 2)];
        const cx = screenX(x, y, z);
        const cy = screenY(x, y, z);
        minX = Math.min(minX, cx);
        maxX = Math.max(maxX, cx);
        minY = Math.min(minY, cy);
        maxY = Math.max(maxY, cy);
      }
      if (sx < minX - tolerancePx || sx > maxX + tolerancePx || sy < minY - tolerancePx || sy > maxY + tolerancePx) continue;
      for (let s = c * CHUNK; s < Math.min(paths.count, (c + 1) * CHUNK); s++) {
        const o = s * 6;
        const x0 = screenX(p[o], p[o + 1], p[o + 2]);
        const y0 = screenY(p[o], p[o + 1], p[o + 2]);
        const dx = screenX(p[o + 3], p[o + 4], p[o + 5]) - x0;
        const dy = screenY(p[o + 3], p[o + 4], p[o + 5]) - y0;
        const lengthSquared = dx * dx + dy * dy;
        const t = lengthSquared === 0 ? 0 : Math.min(1, Math.max(0, ((sx - x0) * dx + (sy - y0) * dy) / lengthSquared));
        const d = Math.hypot(sx - (x0 + t * dx), sy - (y0 + t * dy));
        if (d <= bestDistance) {
          best = paths.moveIndex[s];
          bestDistance = d;
        }
      }
    }
    return best;
  }
}
