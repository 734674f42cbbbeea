// The 3D mode of the toolpath page: it builds the toolpath in space when the mode is chosen or the
// drawing changes, draws it in the same colours as the plane view, and links it to the code the same
// way (the cursor's moves highlighted, a click reveals the move's line, the tooltip describes the
// move under the pointer). The page (main.ts) keeps the state; this file only reads it through `Host`.

import type { PackedToolpath } from '../core/packed';
import { MAX_MARKERS, type Palette } from './render';
import { buildPaths, type Paths3d } from './scene3d';
import { View3d } from './view3d';

export interface Host {
  packed(): PackedToolpath;
  /** The moves the cursor's line causes, in order. */
  cursorMoves(): ArrayLike<number>;
  palette(): Palette;
  background(): string;
  /** The tooltip's words for a move. */
  describe(move: number): string;
  /** The user clicked a move: select its line in the editor. */
  picked(move: number): void;
  /** Something changed that needs a redraw. */
  redraw(): void;
  tip: HTMLDivElement;
}

export class Mode3d {
  active = false;
  view: View3d | null = null;
  paths: Paths3d | null = null;
  /** Why the 3D view cannot be shown (no WebGL), or ''. */
  failure = '';
  private pathsOf: PackedToolpath | null = null;
  private highlighted: ArrayLike<number> | null = null;
  private highlightedPaths: Paths3d | null = null;
  private width = 1;
  private height = 1;
  buildMs = 0;

  constructor(private readonly canvas: HTMLCanvasElement, private readonly host: Host) {}

  /** Creates the renderer on first use: a page that never shows 3D needs no WebGL. */
  private ensureView(): View3d | null {
    if (this.view || this.failure) return this.view;
    try {
      this.view = new View3d(this.canvas, () => this.host.redraw());
    } catch (error) {
      this.failure = `3D view unavailable: ${(error as Error).message || 'no WebGL in this window'}`;
      return null;
    }
    this.view.resize(this.width, this.height);
    this.listen(this.view);
    return this.view;
  }

  setActive(active: boolean): boolean {
    if (active && !this.ensureView()) return false;
    this.active = active;
    this.canvas.style.display = active ? 'block' : 'none';
    if (this.view) this.view.controls.enabled = active;
    this.host.redraw();
    return true;
  }

  resize(width: number, height: number): void {
    this.width = width;
    this.height = height;
    this.view?.resize(width, height);
  }

  fit(): void {
    this.view?.fit();
  }

  /** A new program: the next drawing is fitted again even if the user had moved the view. */
  forgetUserView(): void {
    if (this.view) this.view.userMoved = false;
  }

  draw(): void {
    const view = this.view;
    if (!this.active || !view) return;
    const packed = this.host.packed();
    if (this.pathsOf !== packed) {
      const started = performance.now();
      this.paths = buildPaths(packed);
      this.pathsOf = packed;
      view.setPaths(this.paths);
      this.buildMs = performance.now() - started;
    }
    const moves = this.host.cursorMoves();
    const palette = this.host.palette();
    if (moves !== this.highlighted || this.highlightedPaths !== this.paths) {
      view.setHighlight(moves, palette, MAX_MARKERS);
      this.highlighted = moves;
      this.highlightedPaths = this.paths;
    }
    view.render(palette, this.host.background());
  }

  private listen(view: View3d): void {
    const canvas = this.canvas;
    const tip = this.host.tip;
    let down: { x: number; y: number } | null = null;
    canvas.addEventListener('pointerdown', (event) => {
      down = { x: event.offsetX, y: event.offsetY };
    });
    canvas.addEventListener('pointerup', (event) => {
      const start = down;
      down = null;
      // A drag orbits or pans; only a click picks.
      if (!start || Math.abs(event.offsetX - start.x) + Math.abs(event.offsetY - start.y) > 3) return;
      const move = view.pick(event.offsetX, event.offsetY);
      if (move >= 0) this.host.picked(move);
    });
    let hoverPending = false;
    let last = { x: 0, y: 0 };
    canvas.addEventListener('pointermove', (event) => {
      last = { x: event.offsetX, y: event.offsetY };
      if (event.buttons) {
        tip.style.display = 'none';
        return;
      }
      if (hoverPending) return;
      // Picking visits the segments near the pointer: at most once a frame.
      hoverPending = true;
      requestAnimationFrame(() => {
        hoverPending = false;
        const move = view.pick(last.x, last.y);
        if (move < 0) {
          tip.style.display = 'none';
          return;
        }
        tip.textContent = this.host.describe(move);
        tip.style.display = 'block';
        tip.style.left = `${Math.min(last.x + 12, this.width - tip.offsetWidth - 4)}px`;
        tip.style.top = `${last.y + 12}px`;
      });
    });
    canvas.addEventListener('pointerleave', () => {
      tip.style.display = 'none';
    });
  }
}
