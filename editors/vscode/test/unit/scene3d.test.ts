import assert from 'node:assert/strict';
import { test } from 'node:test';
import { packMoves } from '../../src/core/packed';
import { parsePreview } from '../../src/core/preview';
import { fitView, KIND_ARC, KIND_ARC_IMPOSSIBLE, KIND_HOLE, KIND_RAPID, project } from '../../src/webview/geometry';
import { render, STYLES, type CanvasLike, type PathLike } from '../../src/webview/render';
import { buildPaths, coarsen, groupOf, thin, type Paths3d } from '../../src/webview/scene3d';
import { move, readFixture } from './fixtures';

const packedOf = (name: string) => packMoves(parsePreview(readFixture(name)).moves);

/** The segments of a move, as absolute [x0, y0, z0, x1, y1, z1]. */
function segmentsOf(paths: Paths3d, moveIndex: number): number[][] {
  const out: number[][] = [];
  for (let s = 0; s < paths.count; s++) {
    if (paths.moveIndex[s] !== moveIndex) continue;
    out.push([...paths.points.subarray(s * 6, s * 6 + 6)].map((v, k) => v + paths.origin[k % 3]));
  }
  return out;
}

test('arcs are tessellated on their circle from the server\'s centre, radius and sweep', () => {
  const packed = packedOf('demo_mill.preview.json');
  const paths = buildPaths(packed);
  // N170 G2 full circle around X35 Y25, radius 15, at Z-1 (line 18).
  const circleMove = [...packed.line].indexOf(18);
  const circle = segmentsOf(paths, circleMove);
  assert.ok(circle.length >= 32, `${circle.length} pieces for a full circle`);
  for (const [x0, y0, z0, x1, y1] of circle) {
    assert.ok(Math.abs(Math.hypot(x0 - 35, y0 - 25) - 15) < 1e-3, 'every point on the circle');
    assert.ok(Math.abs(z0 + 1) < 1e-6);
    assert.ok(Math.hypot(x1 - x0, y1 - y0) < 15 * 0.25, 'no chord across the circle');
  }
  assert.ok(circle.every((s) => paths.kind[paths.firstSegment[circleMove]] & KIND_ARC && s.length === 6));
  // Clockwise: from X35 Y10 (below the centre) the first piece goes to the left (X decreases).
  assert.ok(circle[0][3] < 35, 'clockwise from below the centre goes left');
  // The quarter of N70 (line 8) from X60 Y0 to X70 Y10 around X60 Y10, counter-clockwise.
  const quarter = segmentsOf(paths, [...packed.line].indexOf(8));
  assert.deepEqual(quarter[0].slice(0, 2), [60, 0]);
  assert.deepEqual(quarter[quarter.length - 1].slice(3, 5), [70, 10]);
  const middle = quarter[Math.floor(quarter.length / 2)];
  assert.ok(middle[0] > 60 && middle[1] < 10, 'the bulge is below and right of the chord, on the circle');
  assert.equal(paths.hidden, 1, 'the first move has no known start');
  assert.ok(paths.kind[paths.firstSegment[[...packed.line].indexOf(16)]] & KIND_RAPID);
});

test('a helix rises along the axis across its plane, and a lathe program without Y is drawn at Y0', () => {
  const arc = { centre: { X: 0, Y: 0 }, radius: 10, clockwise: false, sweep: 360 };
  const helix = buildPaths(packMoves([move(2, 'G3', { X: 10, Y: 0, Z: 0 }, { X: 10, Y: 0, Z: -4 }, { arc })]));
  const pieces = segmentsOf(helix, 0);
  assert.ok(pieces.length > 16);
  // Every piece's end: on the circle, as deep as the part of the turn it has gone (counter-clockwise from X10 Y0).
  for (const [, , , x, y, z] of pieces.slice(0, -1)) {
    const turned = (Math.atan2(y, x) + 2 * Math.PI) % (2 * Math.PI);
    assert.ok(Math.abs(Math.hypot(x, y) - 10) < 1e-3);
    assert.ok(Math.abs(z + (4 * turned) / (2 * Math.PI)) < 1e-4, `Z${z} after ${turned} rad`);
  }
  const lathe = buildPaths(packMoves([move(1, 'G1', { X: 20, Z: 0 }, { X: 40, Z: -10 })]));
  assert.equal(lathe.hidden, 0);
  assert.deepEqual(segmentsOf(lathe, 0), [[20, 0, 0, 40, 0, -10]]);
});

test('thinning joins what is shorter than a pixel, per style, and leaves the rest', () => {
  const moves = [];
  for (let i = 0; i < 100; i++) moves.push(move(i + 1, 'G1', { X: i * 0.01, Y: 0, Z: 0 }, { X: (i + 1) * 0.01, Y: 0, Z: 0 }));
  moves.push(move(101, 'G0', { X: 1, Y: 0, Z: 0 }, { X: 1, Y: 0, Z: 50 }));
  const paths = buildPaths(packMoves(moves));
  const fine = thin(paths, 0.001);
  assert.equal(fine.thinned, 0);
  assert.equal(fine.drawn, 101);
  const coarse = thin(paths, 0.05);
  assert.equal(coarse.drawn + coarse.thinned, 101);
  assert.ok(coarse.drawn <= 21 && coarse.thinned >= 80, `${coarse.drawn} drawn, ${coarse.thinned} thinned`);
  // The rapid is its own group, drawn whole.
  assert.deepEqual([...coarse.groups.get(groupOf(KIND_RAPID))!].map((v, k) => v + paths.origin[k % 3]), [1, 0, 0, 1, 0, 50]);
  // The joined feed ends within the tolerance (a pixel) of the last end point.
  const feed = coarse.groups.get(0)!;
  assert.ok(Math.abs(feed[feed.length - 3] + paths.origin[0] - 1) <= 0.05 + 1e-6);
});

test('holes are one point each, as rings in the plane view', () => {
  const paths = buildPaths(packedOf('contours_drill.preview.json'));
  assert.equal(paths.holeMove.length, 4);
  assert.deepEqual([...paths.holeMove].map((m) => paths.kind[paths.firstSegment[m]] & KIND_HOLE), [KIND_HOLE, KIND_HOLE, KIND_HOLE, KIND_HOLE]);
  const xs = [0, 1, 2, 3].map((h) => paths.holePoints[h * 3] + paths.origin[0]);
  assert.deepEqual(xs, [30, 45, 60, 75]);
});

class RecordingPath implements PathLike {
  commands: string[] = [];
  moveTo(x: number, y: number) { this.commands.push(`M${x.toFixed(1)},${y.toFixed(1)}`); }
  lineTo(x: number, y: number) { this.commands.push(`L${x.toFixed(1)},${y.toFixed(1)}`); }
  ellipse() { this.commands.push('E'); }
}

class RecordingCanvas implements CanvasLike {
  strokeStyle: unknown = '';
  fillStyle: unknown = '';
  lineWidth = 1;
  dash: number[] = [];
  strokes: { colour: unknown; dash: number[]; path: RecordingPath }[] = [];
  setLineDash(segments: number[]) { this.dash = segments; }
  stroke(path: PathLike) { this.strokes.push({ colour: this.strokeStyle, dash: this.dash, path: path as RecordingPath }); }
  fillRect() {}
  clearRect() {}
}

test('a circle that cannot exist is dashed in the error colour with a cross, and a plunge is not thinned', () => {
  // circle_cr.mpf: N60 G2 X60 Y40 CR=10 from X50 Y20; the server gives no arc (and finding A207).
  const packed = packedOf('circle_cr.preview.json');
  const p = project(packed, 'G17');
  const segment = [...p.moveIndex].findIndex((m) => packed.line[m] === 8);
  assert.ok(p.kind[segment] & KIND_ARC_IMPOSSIBLE);
  assert.equal(p.kind.filter((k) => (k & KIND_ARC_IMPOSSIBLE) !== 0).length, 1, 'only the rejected circle');
  const view = fitView(p.bounds, 600, 400);
  const canvas = new RecordingCanvas();
  const stats = render(canvas, () => new RecordingPath(), p, view, 600, 400, '#000');
  assert.equal(stats.thinned, 0, 'N30 G1 Z-2 has no length in X/Y: nothing is thinned');
  assert.equal(stats.impossible, 1);
  const dashed = canvas.strokes.filter((s) => s.colour === STYLES.impossible.colour);
  assert.equal(dashed.length, 2, 'the line and its cross');
  assert.deepEqual(dashed[0].dash, [3, 3]);
  assert.deepEqual(dashed[1].dash, []);
  assert.equal(dashed[1].path.commands.length, 4, 'two strokes of a cross');
  const mid = [view.offsetX + 55 * view.scale, view.offsetY - 30 * view.scale];
  assert.equal(dashed[1].path.commands[0], `M${(mid[0] - 5).toFixed(1)},${(mid[1] - 5).toFixed(1)}`, 'the cross on the middle');
  const paths = buildPaths(packed);
  assert.equal(paths.impossible, 1);
  assert.ok(paths.kind[paths.firstSegment[[...packed.line].indexOf(8)]] & KIND_ARC_IMPOSSIBLE);
});

test('while the user orbits a large drawing, runs of segments become one, from the first start to the last end', () => {
  const points = new Float32Array(10 * 6);
  for (let i = 0; i < 10; i++) points.set([i, 0, 0, i + 1, 0, 0], i * 6);
  const groups = new Map([[0, points]]);
  assert.equal(coarsen(groups, 100), groups, 'within the budget: unchanged');
  const coarse = coarsen(groups, 3).get(0)!;
  assert.deepEqual([...coarse], [0, 0, 0, 4, 0, 0, 4, 0, 0, 8, 0, 0, 8, 0, 0, 10, 0, 0]);
});
