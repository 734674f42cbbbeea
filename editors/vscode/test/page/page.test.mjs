// The toolpath page in headless Chromium: it draws the demo program (feed solid, rapid dashed, arcs,
// uncertain moves), highlights the cursor's line, reveals a clicked line, pans and zooms, matches
// the committed screenshot's outline, draws the moves of called programs and highlights the moves a
// call line causes, fades conditional moves, draws inserted roundings and chamfers and the holes of a
// drilling pattern (a click on a hole reveals its line), and prints its drawing time for a million
// moves. Set UPDATE_SCREENSHOT=1 to rewrite the baselines and docs/toolpath-preview.png.
import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';
import { launch } from './cdp.mjs';
import {
  BACKGROUND, canvasColours, covers, FEED, HIGHLIGHT, hex, near, RAPID, root, UNCERTAIN, until as untilIn, writePage,
} from './common.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const baselineFile = path.join(here, 'toolpath.baseline.json');
const contoursBaselineFile = path.join(here, 'contours.baseline.json');
const docsScreenshot = path.resolve(root, '..', '..', 'docs', 'toolpath-preview.png');
const update = process.env.UPDATE_SCREENSHOT === '1';

let page;

async function until(expression, what, timeoutMs = 20000) {
  return untilIn(page, expression, what, timeoutMs);
}

/** Screen position of a plane point in the page's current view. */
async function screen(x, y) {
  const view = await page.evaluate('toolpathDebug.state.view');
  return [view.offsetX + x * view.scale, view.offsetY - y * view.scale];
}

/** The canvas's top-left corner in the page, to turn canvas positions into pointer positions. */
async function canvasOrigin() {
  return page.evaluate('(() => { const r = document.getElementById("canvas").getBoundingClientRect(); return [r.left, r.top]; })()');
}

/** Colours (as [r, g, b]) in a square of `radius` pixels around a canvas position. */
async function colours(x, y, radius = 2) {
  return canvasColours(page, 'canvas', x, y, radius);
}

async function hasColour(x, y, colour, radius = 2, under = BACKGROUND) {
  return (await colours(x, y, radius)).some((c) => covers(c, colour, under));
}

before(async () => {
  const url = writePage();
  page = await launch({ width: 900, height: 640 });
  await page.goto(url);
  await until('harness.sent.some((m) => m.type === "ready")', 'the page to say it is ready');
  const preview = fs.readFileSync(path.join(root, 'test', 'fixtures', 'demo_mill.preview.json'), 'utf8');
  await page.evaluate(`harness.loadPreview(${preview}, 'demo_mill.mpf', 28, null, 4)`);
  await until('toolpathDebug.state.done && toolpathDebug.state.stats !== null', 'the drawing');
  await page.evaluate('toolpathDebug.redrawNow()');
});

after(async () => {
  await page?.close();
});

test('the page draws every drawable move and says what it left out', async () => {
  const state = await page.evaluate('({ count: toolpathDebug.state.packed.count, drawn: toolpathDebug.state.projected.count, status: document.getElementById("status").textContent })');
  assert.equal(state.count, 23, 'all moves arrived, through several ranges');
  assert.equal(state.drawn, 22);
  assert.match(state.status, /demo_mill\.mpf: 23 moves · plane G17 X\/Y · mm · 1 not drawn \(position unknown in this plane\)/);
});

test('feed moves are solid, rapid moves dashed, arcs round and uncertain moves marked', async () => {
  // N60 G1 X60 along Y0: solid feed colour at several points.
  for (const x of [10, 25, 40, 55]) {
    const [sx, sy] = await screen(x, 0);
    assert.ok(await hasColour(sx, sy, FEED), `feed colour at X${x} Y0`);
  }
  // N150 G0 from X10 Y0 to X35 Y10: rapid colour with gaps.
  let rapid = 0;
  let gaps = 0;
  for (let t = 0.1; t < 0.9; t += 0.02) {
    const [sx, sy] = await screen(10 + 25 * t, 10 * t);
    // The centre pixel of a thin line is blended with the background: reddish counts as rapid.
    const [[r, g, b]] = await colours(sx, sy, 0);
    if (r > g + 40 && r > b + 40) rapid++;
    else if (near([r, g, b], BACKGROUND, 30)) gaps++;
  }
  assert.ok(rapid >= 5 && gaps >= 5, `dashed: ${rapid} rapid and ${gaps} background samples`);
  // N170 full circle around X35 Y25 with radius 15.
  for (const angle of [0.3, 1.9, 3.4, 5.0]) {
    const [sx, sy] = await screen(35 + 15 * Math.cos(angle), 25 + 15 * Math.sin(angle));
    assert.ok(await hasColour(sx, sy, FEED), `circle at ${angle} rad`);
  }
  // Inside the pocket, off every segment: background.
  const [bx, by] = await screen(22, 42);
  assert.ok((await colours(bx, by, 3)).every((c) => near(c, BACKGROUND, 30)), 'empty space stays empty');
  // N240 G0 X50 Y25 after the label: uncertain.
  const [ux, uy] = await screen(42.5, 25);
  assert.ok(await hasColour(ux, uy, UNCERTAIN, 3), 'uncertain colour after the label');
});

test('the cursor line is highlighted, and a click on a segment reveals its line', async () => {
  await page.evaluate('harness.setCursor(8)');
  await until('toolpathDebug.state.cursorLine === 8', 'the cursor message');
  await page.evaluate('toolpathDebug.redrawNow()');
  const [hx, hy] = await screen(60 + 10 * Math.cos(-Math.PI / 4), 10 + 10 * Math.sin(-Math.PI / 4));
  assert.ok(await hasColour(hx, hy, HIGHLIGHT), 'the arc of line 8 is highlighted');
  const [fx, fy] = await screen(30, 0);
  assert.ok(!(await hasColour(fx, fy, HIGHLIGHT, 1)), 'line 7 is not');

  const [ox, oy] = await canvasOrigin();
  const [cx, cy] = await screen(35, 50); // N100 G1 X10 along Y50, line 11
  await page.hover(ox + cx, oy + cy + 2);
  assert.match(await page.evaluate('document.getElementById("tip").textContent'), /^N100, line 11 {2}G1 {2}→ X10 Y50 Z-2 F500$/);
  await page.mouse('mousePressed', ox + cx, oy + cy + 2);
  await page.mouse('mouseReleased', ox + cx, oy + cy + 2);
  await until('harness.sent.some((m) => m.type === "reveal")', 'a reveal message');
  assert.deepEqual(await page.evaluate('harness.sent.filter((m) => m.type === "reveal")'), [{ type: 'reveal', line: 11 }]);
});

test('the wheel zooms around the pointer and a drag pans without revealing a line', async () => {
  const [ox, oy] = await canvasOrigin();
  const before = await page.evaluate('toolpathDebug.state.view');
  const [px, py] = [300, 200];
  await page.wheel(ox + px, oy + py, -300);
  await until(`toolpathDebug.state.view.scale > ${before.scale * 1.2}`, 'the zoom');
  const zoomed = await page.evaluate('toolpathDebug.state.view');
  const world = (view) => [(px - view.offsetX) / view.scale, (view.offsetY - py) / view.scale];
  assert.ok(Math.hypot(world(zoomed)[0] - world(before)[0], world(zoomed)[1] - world(before)[1]) < 1e-6, 'the point under the pointer stays');
  const reveals = await page.evaluate('harness.sent.filter((m) => m.type === "reveal").length');
  await page.mouse('mousePressed', ox + 400, oy + 300);
  await page.mouse('mouseMoved', ox + 430, oy + 300);
  await page.mouse('mouseMoved', ox + 460, oy + 320);
  await page.mouse('mouseReleased', ox + 460, oy + 320);
  const panned = await page.evaluate('toolpathDebug.state.view');
  assert.ok(Math.abs(panned.offsetX - zoomed.offsetX - 60) < 1e-6 && Math.abs(panned.offsetY - zoomed.offsetY - 20) < 1e-6);
  assert.equal(await page.evaluate('harness.sent.filter((m) => m.type === "reveal").length'), reveals);
  await page.evaluate('document.getElementById("fit").click()');
  await page.evaluate('toolpathDebug.redrawNow()');
});

/** Which cells of a 45 x 30 grid over the canvas hold anything but background. */
async function inkGrid() {
  return page.evaluate(`(() => {
    const canvas = document.getElementById('canvas');
    const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    const columns = 45, rows = 30, grid = [];
    for (let row = 0; row < rows; row++) {
      let line = '';
      for (let column = 0; column < columns; column++) {
        let ink = false;
        const x0 = Math.floor(column * canvas.width / columns), x1 = Math.floor((column + 1) * canvas.width / columns);
        const y0 = Math.floor(row * canvas.height / rows), y1 = Math.floor((row + 1) * canvas.height / rows);
        for (let y = y0; y < y1 && !ink; y++) for (let x = x0; x < x1 && !ink; x++) {
          const i = (y * canvas.width + x) * 4;
          ink = Math.abs(data[i] - 30) + Math.abs(data[i + 1] - 30) + Math.abs(data[i + 2] - 30) > 60;
        }
        line += ink ? '#' : '.';
      }
      grid.push(line);
    }
    return grid;
  })()`);
}

test('the drawing matches the committed screenshot outline', async () => {
  await page.evaluate('harness.setCursor(9)');
  await until('toolpathDebug.state.cursorLine === 9', 'the cursor message');
  await page.evaluate('harness.setCursor(8)');
  await until('toolpathDebug.state.cursorLine === 8', 'the cursor message');
  await page.evaluate('toolpathDebug.redrawNow()');
  const grid = await inkGrid();
  const shot = await page.screenshot();
  fs.writeFileSync(path.join(root, 'out', 'page', 'toolpath.png'), shot);
  if (update || !fs.existsSync(baselineFile)) {
    fs.writeFileSync(baselineFile, JSON.stringify(grid, null, 1) + '\n');
    fs.writeFileSync(docsScreenshot, shot);
    console.log(`wrote ${baselineFile} and ${docsScreenshot}`);
  }
  const baseline = JSON.parse(fs.readFileSync(baselineFile, 'utf8'));
  let differing = 0;
  grid.forEach((row, r) => [...row].forEach((cell, c) => (differing += cell === baseline[r][c] ? 0 : 1)));
  const inked = grid.join('').split('#').length - 1;
  assert.ok(inked > 60, `${inked} cells hold the drawing`);
  assert.ok(differing <= 12, `${differing} of 1350 cells differ from the baseline:\n${grid.join('\n')}`);
});

test('in a light theme the page draws with the light palette', async () => {
  await page.evaluate('document.body.classList.add("vscode-light"); document.body.style.background = "#ffffff"; toolpathDebug.redrawNow()');
  const [sx, sy] = await screen(30, 0);
  assert.ok(await hasColour(sx, sy, hex('#0b5cad'), 2, [255, 255, 255]), 'dark blue feed on white');
  const [bx, by] = await screen(22, 42);
  assert.ok((await colours(bx, by, 2)).every((c) => near(c, [255, 255, 255], 10)), 'the theme background');
  await page.evaluate('document.body.classList.remove("vscode-light"); document.body.style.background = ""; toolpathDebug.redrawNow()');
});

test('after an edit the old drawing stays until the new one is complete', async () => {
  const preview = JSON.parse(fs.readFileSync(path.join(root, 'test', 'fixtures', 'demo_mill.preview.json'), 'utf8'));
  // The edit removed the blocks after the label.
  const edited = { ...preview, moves: preview.moves.filter((move) => move.line < 24) };
  const loading = page.evaluate(`harness.loadPreview(${JSON.stringify(edited)}, 'demo_mill.mpf', 24, null, 6, 150)`);
  await until('!toolpathDebug.state.done', 'the update to start');
  await page.evaluate('toolpathDebug.redrawNow()');
  const during = await page.evaluate('({ count: toolpathDebug.state.packed.count, status: document.getElementById("status").textContent })');
  assert.equal(during.count, 23, 'the old drawing is still shown');
  assert.match(during.status, /updating after the edit/);
  await loading;
  await until('toolpathDebug.state.done', 'the update');
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.equal(await page.evaluate('toolpathDebug.state.packed.count'), 20);
  const [ux, uy] = await screen(42.5, 25);
  assert.ok(!(await hasColour(ux, uy, UNCERTAIN, 3)), 'the removed uncertain move is gone');
});

const SLOT_URI = 'file:///work/SLOT.SPF';

test('the moves of a called program are drawn, and a call line highlights every move it causes', async () => {
  const calls = fs.readFileSync(path.join(root, 'test', 'fixtures', 'calls_mill.preview.json'), 'utf8');
  await page.evaluate('harness.setCursor(1)'); // a line without moves: nothing highlighted
  await page.evaluate(`harness.loadPreview(${calls}, 'calls_mill.mpf', 19, null, 4)`);
  await until('toolpathDebug.state.done && toolpathDebug.state.title === "calls_mill.mpf"', 'the drawing of calls_mill.mpf');
  await page.evaluate('toolpathDebug.redrawNow()');
  const loaded = await page.evaluate('({ count: toolpathDebug.state.packed.count, files: toolpathDebug.state.packed.files })');
  assert.equal(loaded.count, 23, 'the moves of the program and the three runs of SLOT.SPF, through several ranges');
  assert.deepEqual(loaded.files, ['file:///work/calls_mill.mpf', SLOT_URI]);
  // The cut of SLOT.SPF line 4 in its first run (X10 to X30 at Y10) and in its third (X30 to X50 at Y30).
  for (const [x, y] of [[15, 10], [20, 10], [25, 10], [35, 30], [40, 30], [45, 30]]) {
    const [sx, sy] = await screen(x, y);
    assert.ok(await hasColour(sx, sy, FEED), `the slot is drawn at X${x} Y${y}`);
  }

  // The cursor on line 8, N70 SLOT P2: both runs of that call, and not the run of N50 on line 6.
  await page.evaluate('harness.setCursor(8)');
  await until('toolpathDebug.state.cursorLine === 8', 'the cursor message');
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.equal(await page.evaluate('toolpathDebug.highlight().length'), 6);
  for (const x of [20, 40]) {
    const [sx, sy] = await screen(x, 30);
    assert.ok(await hasColour(sx, sy, HIGHLIGHT), `the call's cut at X${x} Y30 is highlighted`);
  }
  const [ox1, oy1] = await screen(20, 10);
  assert.ok(!(await hasColour(ox1, oy1, HIGHLIGHT, 1)), 'the run of the other call is not');
  assert.match(await page.evaluate('document.getElementById("status").textContent'), / · line 8: 6 moves$/);

  // The cursor in SLOT.SPF on line 4: its cut in all three runs.
  await page.evaluate(`harness.setCursor(4, '${SLOT_URI}')`);
  await until('toolpathDebug.state.cursorFile !== undefined', 'the cursor in SLOT.SPF');
  await page.evaluate('toolpathDebug.redrawNow()');
  for (const [x, y] of [[20, 10], [20, 30], [40, 30]]) {
    const [sx, sy] = await screen(x, y);
    assert.ok(await hasColour(sx, sy, HIGHLIGHT), `SLOT.SPF line 4 at X${x} Y${y} is highlighted`);
  }
  assert.match(await page.evaluate('document.getElementById("status").textContent'), / · SLOT\.SPF line 4: 3 moves$/);

  // Hovering the third run names the block, the pass, the file and the call; a click asks for that file's line.
  const [ox, oy] = await canvasOrigin();
  const [cx, cy] = await screen(42, 30);
  await page.hover(ox + cx, oy + cy + 1);
  assert.equal(await page.evaluate('document.getElementById("tip").textContent'),
    'N20, pass 3 of 3, SLOT.SPF line 4  G1  → X50 Y30 Z-2 F400  3 s\ncalled at calls_mill.mpf line 8');
  const reveals = await page.evaluate('harness.sent.filter((m) => m.type === "reveal").length');
  await page.mouse('mousePressed', ox + cx, oy + cy + 1);
  await page.mouse('mouseReleased', ox + cx, oy + cy + 1);
  await until(`harness.sent.filter((m) => m.type === "reveal").length > ${reveals}`, 'a reveal message');
  assert.deepEqual(await page.evaluate('harness.sent[harness.sent.length - 1]'), { type: 'reveal', line: 4, file: SLOT_URI });
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.match(await page.evaluate('document.getElementById("status").textContent'), / · N20, pass 3 of 3, SLOT\.SPF line 4$/);
});

test('a conditional move is drawn faded, and the legend and the status say what that means', async () => {
  await page.evaluate('harness.setCursor(1)');
  await until('toolpathDebug.state.cursorLine === 1', 'the cursor message');
  await page.evaluate('toolpathDebug.redrawNow()');
  /** The most blue above the background around a point: a feed line drawn in full or faded. */
  const blue = async (x, y) => {
    const [sx, sy] = await screen(x, y);
    return Math.max(...(await colours(sx, sy, 2)).map(([, , b]) => b - BACKGROUND[2]));
  };
  const full = await blue(20, 10); // SLOT.SPF's cut of the first run
  const faded = await blue(70, 40); // N160 G1 X80 under IF $A_IN[1]==1
  assert.ok(full > 150, `a feed move in full: ${full}`);
  assert.ok(faded > 50 && faded < 130, `the conditional move, faded: ${faded}`);
  const status = await page.evaluate('document.getElementById("status").textContent');
  assert.match(status, / · 1 conditional \(faded\) · /);
  const legend = await page.evaluate('(() => { const item = document.querySelector(".swatch.conditional").parentElement; return [item.textContent, item.title]; })()');
  assert.deepEqual(legend, ['conditional', 'faded: on a way whose condition the analysis could not decide']);
});

const HOLES = [[30, 10], [45, 10], [60, 10], [75, 10]];

test('roundings are arcs, chamfers lines, and the holes of a pattern rings that reveal their line', async () => {
  const contours = fs.readFileSync(path.join(root, 'test', 'fixtures', 'contours_drill.preview.json'), 'utf8');
  await page.evaluate('harness.setCursor(1)');
  await page.evaluate(`harness.loadPreview(${contours}, 'contours_drill.mpf', 17, null, 4)`);
  await until('toolpathDebug.state.done && toolpathDebug.state.title === "contours_drill.mpf"', 'the drawing of contours_drill.mpf');
  await page.evaluate('toolpathDebug.redrawNow()');
  const count = JSON.parse(contours).moves.length;
  assert.ok(await page.evaluate(`document.getElementById("status").textContent.startsWith(
    "contours_drill.mpf: ${count} moves · plane G17 X/Y · mm · 4 holes · 1 not drawn (position unknown in this plane)")`));

  // The rounding (T106) and the chamfers (T107, CHF and CHR) cut their corners: ink on the inserted
  // element's middle, none on the programmed corner.
  const corners = [
    ['RND at X50 Y0', [45 + 5 * Math.SQRT1_2, 5 - 5 * Math.SQRT1_2], [50, 0]],
    ['CHF at X100 Y50', [100 - 1.7678, 50 + 1.7678], [100, 50]],
    ['CHR at X100 Y100', [97.5, 97.5], [100, 100]],
  ];
  for (const [what, middle, corner] of corners) {
    const [mx, my] = await screen(...middle);
    assert.ok(await hasColour(mx, my, FEED), `${what}: the inserted element is drawn`);
    const [cx, cy] = await screen(...corner);
    assert.ok((await colours(cx, cy, 2)).every((c) => near(c, BACKGROUND, 30)), `${what}: the sharp corner is not`);
  }

  // A ring at each hole: in the feed colour on the ring above its centre, background inside and outside it.
  const view = await page.evaluate('toolpathDebug.state.view');
  for (const [x, y] of HOLES) {
    const [hx, hy] = await screen(x, y);
    assert.ok(await hasColour(hx, hy - 4, FEED, 1), `the ring of the hole at X${x} Y${y}`);
    assert.ok((await colours(hx, hy - 8, 1)).every((c) => near(c, BACKGROUND, 30)), `outside the ring at X${x} Y${y}`);
  }
  assert.ok(view.scale > 2, 'holes 15 apart are far more than a ring apart');

  // Hovering a hole's ring names the drilling move; a click reveals the line of HOLES1.
  const [ox, oy] = await canvasOrigin();
  const [hx, hy] = await screen(45, 10);
  await page.hover(ox + hx, oy + hy - 4);
  // The time is the fixture's: the words around it are the page's.
  assert.match(await page.evaluate('document.getElementById("tip").textContent'),
    /^N130, line 15 {2}G1 {2}→ X45 Y10 Z-5 F100 {2}3\.6 s\nhole drilled by CYCLE81 along Z$/);
  const reveals = await page.evaluate('harness.sent.filter((m) => m.type === "reveal").length');
  await page.mouse('mousePressed', ox + hx, oy + hy - 4);
  await page.mouse('mouseReleased', ox + hx, oy + hy - 4);
  await until(`harness.sent.filter((m) => m.type === "reveal").length > ${reveals}`, 'a reveal message');
  assert.deepEqual(await page.evaluate('harness.sent[harness.sent.length - 1]'), { type: 'reveal', line: 15 });
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.match(await page.evaluate('document.getElementById("status").textContent'), / · N130, line 15$/);
  for (const [x, y] of HOLES) {
    const [sx, sy] = await screen(x, y);
    assert.ok(await hasColour(sx, sy - 4, HIGHLIGHT, 1), `the hole at X${x} Y${y} is highlighted with its line`);
  }

  // Hovering the rounding names what inserted it.
  const [rx, ry] = await screen(45 + 5 * Math.SQRT1_2, 5 - 5 * Math.SQRT1_2);
  await page.hover(ox + rx, oy + ry);
  assert.match(await page.evaluate('document.getElementById("tip").textContent'),
    /^N50, line 7 {2}G3 {2}→ X50 Y5 Z-2 F100 {2}4\.7124 s\nrounding R5 inserted by RND$/);

  // Seen from the side (Z/X), the drilling is lines along Z and there is no ring.
  await page.evaluate('(() => { const s = document.getElementById("plane"); s.value = "G18"; s.dispatchEvent(new Event("change")); })()');
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.equal(await page.evaluate('toolpathDebug.state.projected.holeSegment.length'), 0);
  assert.doesNotMatch(await page.evaluate('document.getElementById("status").textContent'), /holes/);
  await page.evaluate('(() => { const s = document.getElementById("plane"); s.value = "auto"; s.dispatchEvent(new Event("change")); })()');
});

test('the contours and holes match their committed outline', async () => {
  await page.evaluate('harness.setCursor(1)');
  await until('toolpathDebug.state.cursorLine === 1', 'the cursor message');
  await page.evaluate('toolpathDebug.redrawNow()');
  const grid = await inkGrid();
  fs.writeFileSync(path.join(root, 'out', 'page', 'contours.png'), await page.screenshot());
  if (update || !fs.existsSync(contoursBaselineFile)) {
    fs.writeFileSync(contoursBaselineFile, JSON.stringify(grid, null, 1) + '\n');
    console.log(`wrote ${contoursBaselineFile}`);
  }
  const baseline = JSON.parse(fs.readFileSync(contoursBaselineFile, 'utf8'));
  let differing = 0;
  grid.forEach((row, r) => [...row].forEach((cell, c) => (differing += cell === baseline[r][c] ? 0 : 1)));
  assert.ok(differing <= 12, `${differing} of 1350 cells differ from the baseline:\n${grid.join('\n')}`);
});

test('a pattern of 250,000 holes draws its rings within a frame budget (figures printed)', async () => {
  await page.evaluate('harness.loadHoles(500)');
  await until('toolpathDebug.state.packed.count === 250000 && toolpathDebug.state.done', '250,000 holes', 60000);
  const times = await page.evaluate(`(() => {
    const out = [];
    for (let i = 0; i < 5; i++) { toolpathDebug.redrawNow(); out.push(toolpathDebug.state.renderMs); }
    return { times: out, stats: toolpathDebug.state.stats };
  })()`);
  const sorted = [...times.times].sort((a, b) => a - b);
  console.log(`250,000 holes in Chromium: median redraw ${sorted[2].toFixed(1)} ms (best ${sorted[0].toFixed(1)}), ${times.stats.holes} rings drawn`);
  assert.equal(await page.evaluate('toolpathDebug.state.projected.holeSegment.length'), 250000);
  assert.ok(times.stats.holes > 1000 && times.stats.holes < 250000, `${times.stats.holes} rings`);
});

test('the info line shows the program\'s machining time once the load is complete', async () => {
  const preview = JSON.parse(fs.readFileSync(path.join(root, 'test', 'fixtures', 'demo_mill.preview.json'), 'utf8'));
  const program_time = { total_s: 95.5, feed_s: 90, rapid_s: 3, dwell_s: 2.5, unknown_moves: 1 };
  await page.evaluate(`harness.loadPreview(${JSON.stringify({ ...preview, program_time })}, 'timed.mpf', 28, null, 4)`);
  await until('toolpathDebug.state.done', 'the timed load');
  await page.evaluate('toolpathDebug.redrawNow()');
  const status = await page.evaluate('document.getElementById("status").textContent');
  assert.match(status, / · machining time at least 1 min 36 s, feed 1 min 30 s, rapid 3 s, dwell 2\.5 s \(1 moves of unknown time/);
});

test('a million moves draw within a frame budget (figures printed)', async () => {
  await page.evaluate('harness.loadSynthetic(1000000)');
  await until('toolpathDebug.state.packed.count === 1000000 && toolpathDebug.state.done', 'a million moves', 60000);
  const times = await page.evaluate(`(() => {
    const out = [];
    for (let i = 0; i < 5; i++) { toolpathDebug.redrawNow(); out.push(toolpathDebug.state.renderMs); }
    return { times: out, stats: toolpathDebug.state.stats };
  })()`);
  const sorted = [...times.times].sort((a, b) => a - b);
  console.log(`1,000,000 moves in Chromium: median redraw ${sorted[2].toFixed(1)} ms (best ${sorted[0].toFixed(1)}), ${times.stats.drawn} drawn, ${times.stats.thinned} thinned`);
  assert.equal(times.stats.visited, 1000000, 'the whole spiral is on screen');
  assert.ok(times.stats.thinned > 0);
});
