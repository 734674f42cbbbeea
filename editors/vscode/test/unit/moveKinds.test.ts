// What made a move, through the whole way to the page: inserted roundings and chamfers, cycle moves
// and holes read from the preview, packed as flags, joined, revived, projected (holes only in the plane
// across the tool axis), picked, drawn and described.

import assert from 'node:assert/strict';
import { test } from 'node:test';
import {
  allocatePacked, concatPacked, drillAxisOf, FLAG_CYCLE, FLAG_HOLE_MASK, FLAG_HOLE_SHIFT, FLAG_INSERTED_CHF, FLAG_INSERTED_CHR, FLAG_INSERTED_MASK, FLAG_INSERTED_RND,
  holeAxis, insertedName, MAX_CYCLE_NAMES, MOTIONS, packMoves, revivePacked,
} from '../../src/core/packed';
import { parsePreview, PreviewFormatError, type PreviewMove } from '../../src/core/preview';
import { madeBy, moveNotes, moveTime } from '../../src/webview/describe';
import { fitView, HOLE_RADIUS_PX, KIND_HOLE, KIND_INSERTED, pick, pickHole, pickMove, project, toScreen } from '../../src/webview/geometry';
import { render, STYLES } from '../../src/webview/render';
import { segmentsCausedBy } from '../../src/webview/selection';
import { move, readFixture } from './fixtures';

const fixtureMoves = () => parsePreview(readFixture('contours_drill.preview.json')).moves;
const contours = () => packMoves(fixtureMoves());
// The fixture's moves are found by what the server says of them, not by their place, so that the tests
// hold when the fixture is written again by the server (which may position or order differently):
// the rounding, the two chamfers, the moves of the pattern on line 15 (positioning by HOLES1, G0 to
// the safety plane, G1 to the depth and G0 to RTP by CYCLE81) and the drilling moves among them.
const FIXTURE = fixtureMoves();
const where = (test: (m: PreviewMove) => boolean) => FIXTURE.flatMap((m, i) => (test(m) ? [i] : []));
const [RND] = where((m) => m.inserted === 'RND');
const [CHF] = where((m) => m.inserted === 'CHF');
const [CHR] = where((m) => m.inserted === 'CHR');
const PATTERN = where((m) => m.line === 15);
const DRILLS = where((m) => m.cycle === 'CYCLE81' && m.motion === 'G1');
const [POSITIONING] = where((m) => m.cycle === 'HOLES1');
const [RAPID_DOWN] = where((m) => m.cycle === 'CYCLE81' && m.motion === 'G0');
/** The holes of T125's N30, HOLES1(20, 10, 0, 10, 15, 4), as a set: the order is not the reference's. */
const HOLES = [[30, 10], [45, 10], [60, 10], [75, 10]];
const asSet = (points: number[][]) => points.map(([x, y]) => `${x} ${y}`).sort();

test('the preview names inserted elements, cycles and times, and refuses malformed ones', () => {
  const moves = fixtureMoves();
  assert.deepEqual(moves.map((m) => m.inserted).filter(Boolean), ['RND', 'CHF', 'CHR']);
  assert.equal(moves[RND].arc?.radius, 5);
  assert.equal(moves[RND].line, 7, 'the line of the block that programs it');
  assert.equal(DRILLS.length, 4);
  assert.deepEqual(asSet(DRILLS.map((i) => [moves[i].end.X, moves[i].end.Y])), asSet(HOLES));
  assert.ok(DRILLS.every((i) => moves[i].line === 15), 'the line of the HOLES1 call');
  assert.equal(moves[POSITIONING].line, 15);
  assert.equal(moves[0].cycle, null);
  assert.equal(moves[0].time, null, 'a move without a known start has no time');
  assert.equal(moves[DRILLS[0]].time, 3.6, '6 mm at F100');
  const answer = (extra: Record<string, unknown>) => ({ moves: [{ line: 1, motion: 'G1', end: { X: 1 }, ...extra }] });
  assert.equal(parsePreview(answer({ inserted: 'rnd', cycle: 'cycle82' })).moves[0].inserted, 'RND');
  assert.equal(parsePreview(answer({ cycle: 'cycle82' })).moves[0].cycle, 'CYCLE82');
  assert.throws(() => parsePreview(answer({ inserted: 5 })), (e: Error) => e instanceof PreviewFormatError && /inserted is not a name/.test(e.message));
  assert.throws(() => parsePreview(answer({ cycle: '' })), /cycle is not a name/);
  assert.throws(() => parsePreview(answer({ time_s: -1 })), /time_s is not a number of seconds/);
  assert.throws(() => parsePreview(answer({ time_s: '3' })), /time_s/);
});

test('inserted elements, cycle moves and holes are flag bits; cycle names a small table', () => {
  const packed = contours();
  assert.equal(packed.count, FIXTURE.length);
  assert.equal(packed.flags[RND] & FLAG_INSERTED_MASK, FLAG_INSERTED_RND);
  assert.equal(packed.flags[CHF] & FLAG_INSERTED_MASK, FLAG_INSERTED_CHF);
  assert.equal(packed.flags[CHR] & FLAG_INSERTED_MASK, FLAG_INSERTED_CHR);
  assert.deepEqual([RND, CHF, CHR].map((i) => insertedName(packed.flags[i])), ['RND', 'CHF', 'CHR']);
  assert.equal(insertedName(packed.flags[RND - 1]), '', 'the shortened block itself is programmed');
  assert.ok(packed.arcOf[RND] >= 0 && packed.arcOf[CHF] < 0, 'the rounding keeps its arc, the chamfer is straight');
  assert.deepEqual([...packed.cycleNames].sort(), ['', 'CYCLE81', 'HOLES1']);
  const nameOf = (i: number) => packed.cycleNames[packed.cycleOf[i]];
  assert.deepEqual(FIXTURE.map((_, i) => nameOf(i)), FIXTURE.map((m) => m.cycle ?? ''));
  const cycleMoves = [...packed.flags].flatMap((flags, i) => (flags & FLAG_CYCLE ? [i] : []));
  assert.deepEqual(cycleMoves, PATTERN, 'every move of the pattern, and no other');
  const holes = [...packed.flags].flatMap((flags, i) => (flags & FLAG_HOLE_MASK ? [i] : []));
  assert.deepEqual(holes, DRILLS, 'the feed moves of CYCLE81, not its rapids nor the positioning');
  assert.ok(DRILLS.every((i) => holeAxis(packed.flags[i]) === 2), 'along Z');
  assert.equal(holeAxis(packed.flags[POSITIONING]), -1);
  assert.equal(holeAxis(packed.flags[RAPID_DOWN]), -1);
  assert.ok(Number.isNaN(packed.time[0]));
  assert.equal(packed.time[DRILLS[0]], 3.6);
});

test('a hole is a drilling cycle\'s straight feed move along one axis alone', () => {
  const drill = (motion: string, start: Record<string, number>, end: Record<string, number>, extra: Partial<PreviewMove> = {}) => {
    const packed = packMoves([move(4, motion, start, end, { cycle: 'CYCLE81', ...extra })]);
    return drillAxisOf(packed, 0, packed.cycleNames[packed.cycleOf[0]]);
  };
  assert.equal(drill('G1', { X: 1, Y: 2, Z: 1 }, { X: 1, Y: 2, Z: -5 }), 2);
  assert.equal(drill('G1', { X: 1, Y: 2, Z: 1 }, { X: 1, Y: -3, Z: 1 }, { cycle: 'CYCLE83' }), 1, 'under G18 the tool axis is Y');
  assert.equal(drill('G1', { X: 8, Z: 3 }, { X: 0, Z: 3 }, { cycle: 'CYCLE82' }), 0, 'an axis unknown at both ends does not count');
  assert.equal(drill('G0', { X: 1, Y: 2, Z: 1 }, { X: 1, Y: 2, Z: -5 }), -1, 'a rapid drills nothing');
  assert.equal(drill('G1', { X: 1, Y: 2, Z: 1 }, { X: 2, Y: 2, Z: -5 }), -1, 'two axes move');
  assert.equal(drill('G1', { X: 1, Y: 2, Z: 1 }, { X: 1, Y: 2, Z: 1 }), -1, 'no axis moves');
  assert.equal(drill('G1', { X: 1, Y: 2, Z: 1 }, { X: 1, Z: -5 }), -1, 'Y may have moved');
  assert.equal(drill('G1', { X: 1, Y: 2, Z: 1 }, { X: 1, Y: 2, Z: -5 }, { cycle: 'HOLES1' }), -1, 'a pattern only positions');
  assert.equal(drill('G1', { X: 1, Y: 2, Z: 1 }, { X: 1, Y: 2, Z: -5 }, { cycle: 'POCKET3' }), -1, 'a milling cycle plunges, it does not drill');
  const arc = { centre: { X: 1, Y: 2 }, radius: 1, clockwise: false, sweep: 360 };
  assert.equal(drill('G2', { X: 1, Y: 3, Z: 1 }, { X: 1, Y: 3, Z: -5 }, { arc }), -1, 'a helix is no hole');
});

test('joined and revived parts keep cycle names, holes and times', () => {
  const moves = fixtureMoves();
  const whole = packMoves(moves);
  const n = moves.length;
  // A part with CYCLE86 first, then one with the pattern: the second part's table is in another order.
  const parts = [packMoves([move(30, 'G1', {}, { X: 1 }, { cycle: 'CYCLE86' })]), packMoves(moves.slice(0, RAPID_DOWN + 1)), packMoves(moves.slice(RAPID_DOWN + 1))];
  assert.deepEqual(parts[0].cycleNames, ['', 'CYCLE86']);
  const joined = concatPacked(parts);
  assert.deepEqual([...joined.cycleNames].sort(), ['', 'CYCLE81', 'CYCLE86', 'HOLES1']);
  const names = (p: typeof joined) => [...p.cycleOf].map((index) => p.cycleNames[index]);
  assert.equal(names(joined)[0], 'CYCLE86');
  assert.deepEqual(names(joined).slice(1), names(whole));
  assert.deepEqual([...joined.flags.slice(1)], [...whole.flags]);
  assert.deepEqual([...joined.time.slice(1)], [...whole.time]);
  assert.equal(joined.count, n + 1);
  const revived = revivePacked(JSON.parse(JSON.stringify(joined)));
  assert.deepEqual(revived.cycleNames, joined.cycleNames);
  assert.ok(revived.cycleOf instanceof Uint8Array && revived.time instanceof Float64Array);
  assert.deepEqual(names(revived), names(joined));
  assert.ok(Number.isNaN(revived.time[1]), 'an unknown time stays unknown, not 0');
  assert.equal(revived.time[DRILLS[0] + 1], 3.6);
});

test('a toolpath with more cycle names than the table holds keeps their flag without a name', () => {
  const many = Array.from({ length: MAX_CYCLE_NAMES + 5 }, (_, i) => move(i + 1, 'G1', {}, { X: i }, { cycle: `C${i}` }));
  const packed = packMoves(many);
  assert.equal(packed.cycleNames.length, MAX_CYCLE_NAMES + 1);
  assert.equal(packed.cycleNames[packed.cycleOf[MAX_CYCLE_NAMES - 1]], `C${MAX_CYCLE_NAMES - 1}`);
  assert.equal(packed.cycleOf[MAX_CYCLE_NAMES + 2], 0);
  assert.ok(packed.flags[MAX_CYCLE_NAMES + 2] & FLAG_CYCLE);
  assert.equal(madeBy(packed, MAX_CYCLE_NAMES + 2), 'made by a cycle');
});

test('holes show in the plane across the tool axis only, one per hole', () => {
  const packed = contours();
  const top = project(packed, 'G17');
  assert.deepEqual([...top.holeSegment].map((s) => top.moveIndex[s]), DRILLS);
  assert.deepEqual(asSet([...top.holeSegment].map((s) => [top.x0[s], top.y0[s]])), asSet(HOLES));
  assert.ok([...top.holeSegment].every((s) => top.kind[s] & KIND_HOLE));
  assert.equal(top.holeSegment.length, [...top.kind].filter((k) => k & KIND_HOLE).length);
  for (const plane of ['G18', 'G19'] as const) {
    const side = project(packed, plane);
    assert.equal(side.holeSegment.length, 0, `${plane} shows the drilling as lines along Z`);
    const drill = [...side.moveIndex].indexOf(DRILLS[0]);
    assert.ok(drill >= 0 && (side.x0[drill] !== side.x1[drill] || side.y0[drill] !== side.y1[drill]), `${plane}: the drilling move is a line`);
  }
  assert.deepEqual([...top.moveIndex].filter((_, s) => top.kind[s] & KIND_INSERTED), [RND, CHF, CHR]);
  // Pecks of one hole (CYCLE83: G1, G0 up, G0 down, G1) are one ring; the same place drilled by
  // another line is a ring of its own, so that each line can be clicked.
  const peck = (line: number, from: number, to: number) => move(line, 'G1', { X: 5, Y: 5, Z: from }, { X: 5, Y: 5, Z: to }, { cycle: 'CYCLE83' });
  const pecks = packMoves([
    peck(7, 1, -3), move(7, 'G0', { X: 5, Y: 5, Z: -3 }, { X: 5, Y: 5, Z: 1 }, { cycle: 'CYCLE83' }), peck(7, 1, -6), peck(9, 1, -6),
  ]);
  const p = project(pecks, 'G17');
  assert.deepEqual([...p.holeSegment].map((s) => p.line[s]), [7, 9]);
});

test('a click on or near a hole\'s ring picks the hole, not the rapids that end there', () => {
  const packed = contours();
  const p = project(packed, 'G17');
  const view = fitView(p.bounds, 800, 600);
  const [hx, hy] = toScreen(view, 45, 10);
  const hole = pickHole(p, view, hx + HOLE_RADIUS_PX + 2, hy);
  const drill = p.moveIndex[hole];
  assert.ok(DRILLS.includes(drill) && packed.end[drill * 3] === 45, 'the drilling move of the hole at X45');
  assert.equal(p.line[hole], 15, 'whose line is the HOLES1 call');
  assert.equal(pickHole(p, view, hx + HOLE_RADIUS_PX + 4, hy), -1, 'outside the ring');
  assert.notEqual(pick(p, view, hx, hy), hole, 'the segments alone pick a rapid that ends at the hole');
  assert.equal(pickMove(p, view, hx, hy - 1), hole);
  const [lx, ly] = toScreen(view, 50, 30); // on N60 Y50, away from every hole
  assert.equal(p.line[pickMove(p, view, lx, ly)], 8);
  // The rounding is picked on its arc, and is the line of the block that programs it.
  const [ax, ay] = toScreen(view, 45 + 5 * Math.cos(-Math.PI / 4), 5 + 5 * Math.sin(-Math.PI / 4));
  const arc = pickMove(p, view, ax, ay);
  assert.equal(p.moveIndex[arc], RND);
  assert.equal(p.line[arc], 7);
  // The cursor on the HOLES1 line highlights every move of the pattern and its drilling.
  assert.deepEqual([...segmentsCausedBy(p, packed, 0, 15)].map((s) => p.moveIndex[s]), PATTERN);
});

interface Stroke { colour: unknown; width: number; ellipses: number[][] }

function recordRender(highlightLine = 0) {
  const packed = contours();
  const p = project(packed, 'G17');
  const view = fitView(p.bounds, 800, 600);
  const strokes: Stroke[] = [];
  const canvas = {
    strokeStyle: '' as unknown, fillStyle: '' as unknown, lineWidth: 1,
    setLineDash() {}, fillRect() {}, clearRect() {},
    stroke(path: unknown) { strokes.push({ colour: this.strokeStyle, width: this.lineWidth, ellipses: (path as { ellipses: number[][] }).ellipses }); },
  };
  const newPath = () => {
    const ellipses: number[][] = [];
    return { ellipses, moveTo() {}, lineTo() {}, ellipse: (...args: number[]) => void ellipses.push(args) };
  };
  const highlight = highlightLine ? segmentsCausedBy(p, packed, 0, highlightLine) : [];
  const stats = render(canvas, newPath as never, p, view, 800, 600, '#000', highlight);
  return { strokes, stats, view };
}

test('holes are drawn as rings, the inserted rounding as a wider arc in the feed colour', () => {
  const { strokes, stats, view } = recordRender();
  assert.equal(stats.holes, 4);
  const rings = strokes.filter((s) => s.ellipses.some((e) => e[2] === HOLE_RADIUS_PX));
  assert.equal(rings.length, 1, 'one path of rings');
  assert.equal(rings[0].colour, STYLES.feed.colour);
  assert.deepEqual(asSet(rings[0].ellipses.map((e) => [e[0], e[1]])), asSet(HOLES.map(([x, y]) => toScreen(view, x, y))));
  const inserted = strokes.find((s) => s.width === STYLES.inserted.width)!;
  assert.equal(inserted.colour, STYLES.feed.colour, 'the colour of the path');
  assert.deepEqual(inserted.ellipses.map((e) => e[2]), [5 * view.scale], 'the rounding is its arc');
  const feed = strokes.find((s) => s.colour === STYLES.feed.colour && s.width === STYLES.feed.width && s.ellipses.every((e) => e[2] !== HOLE_RADIUS_PX))!;
  assert.equal(feed.ellipses.length, 0, 'the programmed moves are straight');
});

test('the cursor on a pattern\'s line rings its holes in the highlight colour', () => {
  const { strokes } = recordRender(15);
  const last = strokes[strokes.length - 1];
  assert.equal(last.colour, STYLES.highlight.colour);
  assert.equal(last.ellipses.filter((e) => e[2] === HOLE_RADIUS_PX).length, 4);
  const { strokes: plain } = recordRender(7);
  assert.equal(plain[plain.length - 1].ellipses.filter((e) => e[2] === HOLE_RADIUS_PX).length, 0, 'line 7 has no hole');
});

test('the description says what made a move and how long it takes', () => {
  const packed = contours();
  assert.equal(madeBy(packed, RND), 'rounding R5 inserted by RND');
  assert.equal(madeBy(packed, CHF), 'chamfer 5 long inserted by CHF');
  assert.equal(madeBy(packed, CHR), 'chamfer 7.0711 long inserted by CHR');
  assert.equal(madeBy(packed, POSITIONING), 'made by HOLES1');
  assert.equal(madeBy(packed, RAPID_DOWN), 'made by CYCLE81');
  assert.equal(madeBy(packed, DRILLS[0]), 'hole drilled by CYCLE81 along Z');
  assert.equal(madeBy(packed, RND - 1), '');
  assert.deepEqual(moveNotes(packed, DRILLS[0]), ['hole drilled by CYCLE81 along Z']);
  assert.equal(moveTime(packed, DRILLS[0]), '  3.6 s');
  assert.equal(moveTime(packed, RND), '  4.7124 s', 'a quarter of a circle of 5 at F100');
  assert.equal(moveTime(packed, 0), '', 'unknown');
});

test('a dense pattern draws at most a ring per cell of the ring\'s radius, and every ring when zoomed in (figures printed)', () => {
  // 250,000 holes on a 500 x 500 grid 1 apart, each drilled by one CYCLE81 feed move along Z.
  const side = 500;
  const count = side * side;
  const packed = allocatePacked(count, 0);
  const drillFlags = FLAG_CYCLE | (3 << FLAG_HOLE_SHIFT);
  for (let i = 0; i < count; i++) {
    const x = i % side;
    const y = Math.floor(i / side);
    packed.line[i] = i + 1;
    packed.motion[i] = MOTIONS.indexOf('G1');
    packed.flags[i] = drillFlags;
    packed.start.set([x, y, 1], i * 3);
    packed.end.set([x, y, -5], i * 3);
  }
  const p = project(packed, 'G17');
  assert.equal(p.holeSegment.length, count);
  const canvas = { strokeStyle: '' as unknown, fillStyle: '' as unknown, lineWidth: 1, setLineDash() {}, fillRect() {}, clearRect() {}, stroke() {} };
  const newPath = () => ({ moveTo() {}, lineTo() {}, ellipse() {} });
  const fitted = fitView(p.bounds, 800, 600);
  const started = performance.now();
  const whole = render(canvas, newPath, p, fitted, 800, 600, '#000');
  const ms = performance.now() - started;
  const cells = Math.ceil((800 + 2 * (HOLE_RADIUS_PX + 2)) / HOLE_RADIUS_PX + 1) * Math.ceil((600 + 2 * (HOLE_RADIUS_PX + 2)) / HOLE_RADIUS_PX + 1);
  console.log(`250,000 holes fitted in 800 x 600: ${whole.holes} rings drawn in ${ms.toFixed(0)} ms`);
  assert.ok(whole.holes > 0 && whole.holes <= cells && whole.holes < count / 2, `${whole.holes} rings`);
  // Zoomed so that holes are 20 pixels apart: every hole on screen has its ring.
  const near = { scale: 20, offsetX: 10, offsetY: 590 };
  const zoomed = render(canvas, newPath, p, near, 800, 600, '#000');
  const onScreen = [...p.holeSegment].filter((s) => {
    const [x, y] = toScreen(near, p.x0[s], p.y0[s]);
    return x >= -(HOLE_RADIUS_PX + 2) && x <= 800 + HOLE_RADIUS_PX + 2 && y >= -(HOLE_RADIUS_PX + 2) && y <= 600 + HOLE_RADIUS_PX + 2;
  }).length;
  assert.equal(zoomed.holes, onScreen);
  assert.ok(onScreen > 1000);
});
