import assert from 'node:assert/strict';
import { test } from 'node:test';
import { packMoves } from '../../src/core/packed';
import { parsePreview } from '../../src/core/preview';
import {
  arcScale, distanceToSegment, fitView, guessPlane, KIND_ARC, KIND_ARC_UNVERIFIED, KIND_RAPID, KIND_UNCERTAIN,
  pick, project, revealPoint, toScreen, toWorld, zoomAt, type Projected,
} from '../../src/webview/geometry';
import { segmentsCausedBy } from '../../src/webview/selection';
import { move, readFixture } from './fixtures';
import type { PackedToolpath } from '../../src/core/packed';

/** The drawn segments of a line of the previewed file. */
const segmentsOfLine = (p: Projected, packed: PackedToolpath, line: number) => [...segmentsCausedBy(p, packed, 0, line)];

const demo = () => packMoves(parsePreview(readFixture('demo_mill.preview.json')).moves);

test('the demo program projects onto X/Y with its arcs, rapids and uncertain moves', () => {
  const packed = demo();
  assert.equal(guessPlane(packed), 'G17');
  const p = project(packed, 'G17');
  assert.equal(p.hidden, 1, 'the first move has no known start');
  assert.equal(p.count, packed.count - 1);
  const [first] = segmentsOfLine(p, packed, 8); // N70 G3 X70 Y10 CR=10 from X60 Y0
  assert.ok(p.kind[first] & KIND_ARC);
  assert.deepEqual([p.cx[first], p.cy[first], p.rx[first], p.ry[first]], [60, 10, 10, 10]);
  assert.ok(Math.abs(p.a0[first] + Math.PI / 2) < 1e-12, 'starts below the centre');
  assert.ok(Math.abs(p.sweep[first] - Math.PI / 2) < 1e-12, 'a quarter counter-clockwise');
  const [circle] = segmentsOfLine(p, packed, 18); // N170 G2 full circle
  assert.ok(Math.abs(p.sweep[circle] + 2 * Math.PI) < 1e-12, 'a full circle clockwise');
  const [rapid] = segmentsOfLine(p, packed, 16); // N150 G0 X35 Y10
  assert.ok(p.kind[rapid] & KIND_RAPID);
  assert.equal(p.kind[segmentsOfLine(p, packed, 7)[0]] & KIND_RAPID, 0);
  assert.ok(p.kind[segmentsOfLine(p, packed, 25)[0]] & KIND_UNCERTAIN, 'after the label every axis is uncertain');
  assert.deepEqual(p.bounds, { minX: -10, minY: -10, maxX: 70, maxY: 50 });
});

test('moves without a start or with an unknown plane axis are counted, not drawn', () => {
  const packed = packMoves([move(1, 'G0', {}, { X: 1, Y: 1 }), move(2, 'G1', { X: 1, Y: 1 }, { X: 2 }), move(3, 'G1', { X: 1, Y: 1 }, { X: 2, Y: 3 })]);
  const p = project(packed, 'G17');
  assert.equal(p.hidden, 2);
  assert.equal(p.count, 1);
  assert.deepEqual(segmentsOfLine(p, packed, 3), [0]);
  assert.deepEqual(segmentsOfLine(p, packed, 2), [], 'a line without a drawn move has no segments');
});

test('a lathe arc with X shown as a diameter is drawn as the stretched circle it is', () => {
  // G18 DIAMON: G3 from X20 Z0 to X40 Z-10 with CR=10, as `sinumerik-lsp preview` reports it.
  const arc = { centre: { X: 20, Z: -10 }, radius: 10, clockwise: false, sweep: 90 };
  const packed = packMoves([move(4, 'G3', { X: 20, Z: 0 }, { X: 40, Z: -10 }, { arc })]);
  assert.equal(guessPlane(packed), 'G18');
  const p = project(packed, 'G18');
  assert.ok(p.kind[0] & KIND_ARC);
  assert.deepEqual([p.cx[0], p.cy[0], p.rx[0], p.ry[0]], [-10, 20, 10, 20], 'Z to the right, X (diameter) up and doubled');
  assert.deepEqual(arcScale(0, 20, -10, 40, -10, 20, 10), [1, 0.5]);
  // The arc passes through the points of the true circle mapped back to diameters.
  const mid = Math.PI / 4;
  const onArc = [-10 + 10 * Math.cos(mid), 20 + 20 * Math.sin(mid)];
  assert.ok(distanceToSegment(p, 0, onArc[0], onArc[1]) < 1e-9);
});

test('an arc whose numbers fit no circle is drawn straight and marked', () => {
  const arc = { centre: { X: 0, Y: 0 }, radius: 3, clockwise: false, sweep: 90 };
  const p = project(packMoves([move(1, 'G3', { X: 5, Y: 0 }, { X: 0, Y: 5 }, { arc })]), 'G17');
  assert.ok(p.kind[0] & KIND_ARC_UNVERIFIED);
  assert.equal(p.kind[0] & KIND_ARC, 0);
});

test('fit, zoom and the screen transform agree', () => {
  const view = fitView({ minX: -10, minY: -10, maxX: 70, maxY: 50 }, 820, 620, 10);
  assert.equal(view.scale, 10);
  assert.deepEqual(toScreen(view, -10, 50), [10, 10]);
  assert.deepEqual(toScreen(view, 70, -10), [810, 610]);
  const zoomed = zoomAt(view, 2, 300, 200);
  assert.deepEqual(toWorld(zoomed, 300, 200), toWorld(view, 300, 200), 'the point under the pointer stays');
  assert.equal(zoomed.scale, 20);
  assert.equal(revealPoint(view, 30, 20, 820, 620), view, 'a visible point does not move the view');
  assert.equal(revealPoint(view, 70, -10, 820, 620), view, 'neither does a point of the fitted drawing');
  const moved = revealPoint(view, 500, 20, 820, 620);
  assert.deepEqual(toScreen(moved, 500, 20)[0], 410);
});

test('picking finds the segment under the pointer, and nothing far from every segment', () => {
  const p = project(demo(), 'G17');
  const view = fitView(p.bounds, 820, 620, 10);
  const [sx, sy] = toScreen(view, 30, 0); // on N60 G1 X60 (line 7)
  assert.equal(p.line[pick(p, view, sx, sy + 3)], 7);
  const [cx, cy] = toScreen(view, 35 + 15 * Math.cos(1), 25 + 15 * Math.sin(1)); // on the full circle, line 18
  assert.equal(p.line[pick(p, view, cx, cy)], 18);
  const [ex, ey] = toScreen(view, 65, 5); // inside the rounded corner, off the arc
  assert.equal(pick(p, view, ex - 40, ey + 40), -1);
});
