// The toolpath page's 3D view in headless Chromium (WebGL in software): it draws the demo program in
// the plane view's colours with arcs as arcs, highlights the cursor's block (the pixels of the
// highlighted segment have the highlight colour), a click on a segment posts the message that selects
// its line, it orbits, pans, zooms and fits, a hole and a circle that cannot exist are drawn as in
// the plane view, it prints its load and frame times for a million moves, and without WebGL the 3D
// switch is disabled and says why. The picture is written
// to out/page/toolpath3d.png (and docs/toolpath-3d.png with UPDATE_SCREENSHOT=1).
import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { after, before, test } from 'node:test';
import { launch } from './cdp.mjs';
import { BACKGROUND, canvasColours, covers, ERROR, FEED, HIGHLIGHT, near, RAPID, root, until as untilIn, writePage } from './common.mjs';

const docsScreenshot = path.resolve(root, '..', '..', 'docs', 'toolpath-3d.png');
const update = process.env.UPDATE_SCREENSHOT === '1';
const fixture = (name) => fs.readFileSync(path.join(root, 'test', 'fixtures', name), 'utf8');

let page;
const until = (expression, what, timeoutMs) => untilIn(page, expression, what, timeoutMs);

/** Where a point of the program is on the 3D canvas, with the view as it is now. */
const screen = (x, y, z) => page.evaluate(`toolpathDebug.mode3d.view.toScreen(${x}, ${y}, ${z})`);
const colours = (x, y, radius = 2) => canvasColours(page, 'canvas3d', x, y, radius);
const hasColour = async (x, y, colour, radius = 2) => (await colours(x, y, radius)).some((c) => covers(c, colour));
const canvasOrigin = () => page.evaluate('(() => { const r = document.getElementById("canvas3d").getBoundingClientRect(); return [r.left, r.top]; })()');
const reveals = () => page.evaluate('harness.sent.filter((m) => m.type === "reveal")');
const status = () => page.evaluate('document.getElementById("status").textContent');

async function load(name, title, lines) {
  await page.evaluate(`harness.loadPreview(${fixture(name)}, '${title}', ${lines}, null, 4)`);
  await until(`toolpathDebug.state.done && toolpathDebug.state.title === '${title}'`, `the drawing of ${title}`);
  await page.evaluate('toolpathDebug.redrawNow()');
}

/** Samples along a line: how many show `colour` (in a 3 x 3 square: a one-pixel line is blended)
 * and how many are background only. */
async function dashes(from, to, colour) {
  let marked = 0;
  let gaps = 0;
  for (let t = 0.1; t < 0.9; t += 0.02) {
    const [sx, sy] = await screen(...from.map((v, k) => v + (to[k] - v) * t));
    const square = await colours(sx, sy, 1);
    if (square.some((c) => covers(c, colour))) marked++;
    else if (square.every((c) => near(c, BACKGROUND, 30))) gaps++;
  }
  return { marked, gaps };
}

async function click(x, y) {
  const [ox, oy] = await canvasOrigin();
  await page.mouse('mousePressed', ox + x, oy + y);
  await page.mouse('mouseReleased', ox + x, oy + y);
}

/** A drag with the left button (orbits; with shift held it pans). */
async function drag(from, to, modifiers = 0) {
  const [ox, oy] = await canvasOrigin();
  await page.mouse('mousePressed', ox + from[0], oy + from[1], modifiers);
  for (let step = 1; step <= 4; step++) {
    await page.mouse('mouseMoved', ox + from[0] + ((to[0] - from[0]) * step) / 4, oy + from[1] + ((to[1] - from[1]) * step) / 4, modifiers);
  }
  await page.mouse('mouseReleased', ox + to[0], oy + to[1], modifiers);
}

before(async () => {
  page = await launch({ width: 900, height: 640 });
  await page.goto(writePage('index3d.html'));
  await until('harness.sent.some((m) => m.type === "ready")', 'the page to say it is ready');
  await page.evaluate('document.getElementById("mode-3d").click()');
  await load('demo_mill.preview.json', 'demo_mill.mpf', 28);
});

after(async () => {
  await page?.close();
});

test('the 3D view draws the toolpath in the plane view\'s colours, arcs as arcs', async () => {
  const state = await page.evaluate(`({ failure: toolpathDebug.mode3d.failure, active: toolpathDebug.mode3d.active,
    plane: document.getElementById("canvas").style.display, gl: document.getElementById("canvas3d").style.display,
    pressed: document.getElementById("mode-3d").getAttribute("aria-pressed") })`);
  assert.deepEqual(state, { failure: '', active: true, plane: 'none', gl: 'block', pressed: 'true' });
  assert.match(await status(), /^demo_mill\.mpf: 23 moves · 3D · mm · 1 not drawn \(position unknown\)$/);
  // N100 G1 X10 along Y50 at Z-2 (line 11): feed.
  for (const t of [0.2, 0.5, 0.8]) {
    const [sx, sy] = await screen(60 - 50 * t, 50, -2);
    assert.ok(await hasColour(sx, sy, FEED), `feed colour on N100 at ${t}`);
  }
  // N170, the full circle around X35 Y25 with radius 15 at Z-1: on the circle, not on its chords.
  for (const angle of [0.3, 1.9, 3.4, 5.0]) {
    const [sx, sy] = await screen(35 + 15 * Math.cos(angle), 25 + 15 * Math.sin(angle), -1);
    assert.ok(await hasColour(sx, sy, FEED), `circle at ${angle} rad`);
  }
  const [cx, cy] = await screen(35, 25, -1);
  assert.ok((await colours(cx + 3, cy + 30, 2)).every((c) => near(c, BACKGROUND, 30)), 'inside the circle, away from other moves: empty');
  // N150 G0 from X10 Y0 to X35 Y10 at Z5: rapid, dashed.
  const { marked, gaps } = await dashes([10, 0, 5], [35, 10, 5], RAPID);
  assert.ok(marked >= 5 && gaps >= 5, `dashed rapid colour on N150: ${marked} samples, ${gaps} gaps`);
});

test('the cursor\'s block is highlighted: the pixels of its segments have the highlight colour', async () => {
  await page.evaluate('harness.setCursor(8)');
  await until('toolpathDebug.state.cursorLine === 8', 'the cursor message');
  // N70 G3 X70 Y10 CR=10 from X60 Y0: the quarter around X60 Y10, drawn as an arc.
  for (const angle of [-Math.PI / 3, -Math.PI / 4, -Math.PI / 6]) {
    const [hx, hy] = await screen(60 + 10 * Math.cos(angle), 10 + 10 * Math.sin(angle), -2);
    assert.ok(await hasColour(hx, hy, HIGHLIGHT, 1), `the arc of line 8 at ${angle.toFixed(2)} rad is highlighted`);
  }
  const [fx, fy] = await screen(30, 0, -2);
  assert.ok(!(await hasColour(fx, fy, HIGHLIGHT, 2)), 'line 7 is not highlighted');
  await page.evaluate('harness.setCursor(11)');
  await until('toolpathDebug.state.cursorLine === 11', 'the cursor message');
  const [nx, ny] = await screen(35, 50, -2);
  assert.ok(await hasColour(nx, ny, HIGHLIGHT, 1), 'line 11 is highlighted');
  const [ax, ay] = await screen(60 + 10 * Math.SQRT1_2, 10 - 10 * Math.SQRT1_2, -2);
  assert.ok(!(await hasColour(ax, ay, HIGHLIGHT, 1)), 'line 8 no longer is');
  assert.match(await status(), / · line 11$/);
  const shot = await page.screenshot();
  fs.writeFileSync(path.join(root, 'out', 'page', 'toolpath3d.png'), shot);
  if (update || !fs.existsSync(docsScreenshot)) fs.writeFileSync(docsScreenshot, shot);
});

test('a click on a segment posts the message that selects its line, and the tooltip names the move', async () => {
  await page.evaluate('harness.setCursor(1)');
  const [sx, sy] = await screen(70, 25, -2); // N80 G1 Y40 along X70, line 9
  const [ox, oy] = await canvasOrigin();
  await page.hover(ox + sx, oy + sy);
  await until('document.getElementById("tip").style.display === "block"', 'the tooltip');
  assert.match(await page.evaluate('document.getElementById("tip").textContent'), /^N80, line 9 {2}G1 {2}→ X70 Y40 Z-2 F500$/);
  const before = (await reveals()).length;
  await click(sx, sy);
  await until(`harness.sent.filter((m) => m.type === "reveal").length > ${before}`, 'a reveal message');
  assert.deepEqual((await reveals()).at(-1), { type: 'reveal', line: 9 });
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.ok(await hasColour(sx, sy, HIGHLIGHT, 1), 'the clicked move is highlighted');
  assert.match(await status(), / · N80, line 9$/);
});

test('in 3D too, the cursor in a called program highlights its moves, and a click on one selects its file\'s line', async () => {
  const slot = 'file:///work/SLOT.SPF';
  await load('calls_mill.preview.json', 'calls_mill.mpf', 19);
  await page.evaluate(`harness.setCursor(4, '${slot}')`);
  await until('toolpathDebug.state.cursorFile !== undefined', 'the cursor in SLOT.SPF');
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.match(await status(), / · SLOT\.SPF line 4: 3 moves$/);
  // The cut of SLOT.SPF line 4 in its third run: X30 to X50 at Y30 (Z-2).
  const [sx, sy] = await screen(42, 30, -2);
  assert.ok(await hasColour(sx, sy, HIGHLIGHT, 1), 'the third run is highlighted');
  await page.evaluate('harness.setCursor(1)');
  await until('toolpathDebug.state.cursorLine === 1', 'the cursor message');
  const before = (await reveals()).length;
  await click(sx, sy);
  await until(`harness.sent.filter((m) => m.type === "reveal").length > ${before}`, 'a reveal message');
  assert.deepEqual((await reveals()).at(-1), { type: 'reveal', line: 4, file: slot });
  await page.evaluate('toolpathDebug.redrawNow()');
  assert.match(await status(), / · N20, pass 3 of 3, SLOT\.SPF line 4$/);
  await load('demo_mill.preview.json', 'demo_mill.mpf', 28);
});

test('a drag orbits, a shift-drag pans, the wheel zooms, and Fit or F brings the whole toolpath back', async () => {
  const camera = () => page.evaluate(`(() => { const v = toolpathDebug.mode3d.view; return { position: v.camera.position.toArray(),
    target: v.controls.target.toArray(), zoom: v.camera.zoom, moved: v.userMoved }; })()`);
  const fitted = await camera();
  const before = (await reveals()).length;
  await drag([450, 300], [560, 260]);
  const orbited = await camera();
  assert.ok(Math.hypot(...orbited.position.map((v, k) => v - fitted.position[k])) > 1, 'the camera moved round the target');
  assert.ok(Math.hypot(...orbited.target.map((v, k) => v - fitted.target[k])) < 1e-9, 'orbiting keeps the target');
  assert.ok(orbited.moved);
  assert.equal((await reveals()).length, before, 'a drag selects no line');
  // After orbiting, drawing and picking still agree: the segment's pixels and a click on them.
  const [sx, sy] = await screen(35, 50, -2);
  assert.ok(await hasColour(sx, sy, FEED, 1), 'N100 is drawn where the camera now sees it');
  await click(sx, sy);
  await until(`harness.sent.filter((m) => m.type === "reveal").length > ${before}`, 'a reveal message');
  assert.deepEqual((await reveals()).at(-1), { type: 'reveal', line: 11 });
  await drag([300, 300], [360, 340], 8);
  const panned = await camera();
  assert.ok(Math.hypot(...panned.target.map((v, k) => v - orbited.target[k])) > 1, 'a shift-drag moves the target');
  const [ox, oy] = await canvasOrigin();
  await page.wheel(ox + 450, oy + 300, -600);
  await until(`toolpathDebug.mode3d.view.camera.zoom > ${panned.zoom * 1.2}`, 'the zoom');
  // A resize keeps the user's view.
  const zoom = (await camera()).zoom;
  await page.evaluate('document.body.style.height = "560px"');
  await until(`toolpathDebug.state.height < 500`, 'the smaller canvas');
  assert.equal((await camera()).zoom, zoom, 'no refit after the user zoomed');
  await page.evaluate('document.getElementById("fit").click()');
  const refitted = await camera();
  assert.ok(!refitted.moved && refitted.zoom === 1);
  assert.ok(Math.hypot(...refitted.position.map((v, k) => v - fitted.position[k])) < 1e-6, 'Fit looks from where it first did');
  // With a fitted view a resize (the panel below opening) fits again: every end point of the
  // toolpath's segments stays on the smaller canvas.
  const corners = () => page.evaluate(`(() => {
    const { points, origin } = toolpathDebug.mode3d.paths;
    const out = [];
    for (let i = 0; i < points.length; i += 3) out.push(toolpathDebug.mode3d.view.toScreen(points[i] + origin[0], points[i + 1] + origin[1], points[i + 2] + origin[2]));
    return out;
  })()`);
  await page.evaluate('document.body.style.height = ""');
  await until(`toolpathDebug.state.height > 500`, 'the canvas at its full size');
  const tall = await page.evaluate('toolpathDebug.mode3d.view.camera.top');
  await page.evaluate('document.body.style.height = "360px"');
  await until(`toolpathDebug.state.height < 300`, 'the lower canvas');
  const height = await page.evaluate('toolpathDebug.state.height');
  assert.ok((await page.evaluate('toolpathDebug.mode3d.view.camera.top')) !== tall, 'the camera fitted the new size');
  const ends = await corners();
  assert.ok(ends.length > 100);
  for (const [x, y] of ends) assert.ok(x >= 0 && x <= 900 && y >= 0 && y <= height, `end point at ${x}, ${y} on the ${height}-pixel canvas`);
  assert.ok(!(await camera()).moved);
  await page.evaluate('document.body.style.height = ""');
  await until(`toolpathDebug.state.height > 500`, 'the canvas at its size again');
  assert.equal(await page.evaluate('toolpathDebug.mode3d.view.camera.top'), tall, 'and fitted again when it grew');
  await drag([450, 300], [500, 300]);
  await page.key('f');
  const again = await camera();
  assert.ok(!again.moved && Math.hypot(...again.position.map((v, k) => v - fitted.position[k])) < 1e-6, 'F fits');
});

test('holes are rings that select their line, and a circle that cannot exist is dashed and marked', async () => {
  await load('contours_drill.preview.json', 'contours_drill.mpf', 17);
  assert.match(await status(), /^contours_drill\.mpf: \d+ moves · 3D · mm · 4 holes/);
  const [hx, hy] = await screen(45, 10, await page.evaluate('toolpathDebug.state.packed.start[toolpathDebug.mode3d.paths.holeMove[1] * 3 + 2]'));
  assert.ok(await hasColour(hx, hy - 4, FEED, 1), 'the ring of the hole at X45 Y10');
  const before = (await reveals()).length;
  await click(hx + 3, hy - 3);
  await until(`harness.sent.filter((m) => m.type === "reveal").length > ${before}`, 'a reveal message');
  assert.deepEqual((await reveals()).at(-1), { type: 'reveal', line: 15 });

  await load('circle_cr.preview.json', 'circle_cr.mpf', 10);
  assert.match(await status(), /^circle_cr\.mpf: 6 moves · 3D · mm · 1 not drawn \(position unknown\) · 1 circle that cannot exist \(dashed, ✕\)/);
  assert.doesNotMatch(await status(), /thinned/);
  // The cross on the middle of N60 (X50 Y20 to X60 Y40), off the line itself.
  const [mx, my] = await screen(55, 30, -2);
  let arms = 0;
  for (const [dx, dy] of [[-4, -4], [4, 4], [-4, 4], [4, -4]]) if (await hasColour(mx + dx, my + dy, ERROR, 1)) arms++;
  assert.ok(arms >= 3, `${arms} arms of the cross in the error colour`);
  const { marked, gaps } = await dashes([50, 20, -2], [55, 30, -2], ERROR);
  assert.ok(marked >= 5 && gaps >= 3, `dashed: ${marked} error-coloured and ${gaps} background samples`);
});

test('a million moves load and draw in 3D within a usable time (figures printed)', async () => {
  const started = Date.now();
  await page.evaluate('harness.loadSynthetic(1000000)');
  await until('toolpathDebug.state.packed.count === 1000000 && toolpathDebug.state.done', 'a million moves', 120000);
  const figures = await page.evaluate(`(() => {
    const gl = toolpathDebug.mode3d.view.renderer.getContext();
    const pixel = new Uint8Array(4);
    const sync = () => gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    let t = performance.now();
    toolpathDebug.redrawNow();
    sync();
    const first = performance.now() - t;
    const view = toolpathDebug.mode3d.view;
    // Frames while orbiting (between the controls' start and end), then still frames from other angles.
    const orbit = (frames) => {
      view.camera.position.sub(view.controls.target).applyAxisAngle(view.camera.up, 0.2).add(view.controls.target);
      view.controls.update();
      t = performance.now();
      toolpathDebug.redrawNow();
      sync();
      frames.push(performance.now() - t);
    };
    const moving = [];
    view.controls.dispatchEvent({ type: 'start' });
    for (let i = 0; i < 5; i++) orbit(moving);
    const coarse = view.stats.coarse;
    view.controls.dispatchEvent({ type: 'end' });
    const frames = [];
    for (let i = 0; i < 3; i++) orbit(frames);
    moving.sort((a, b) => a - b);
    frames.sort((a, b) => a - b);
    t = performance.now();
    const picked = view.pick(toolpathDebug.state.width / 2, toolpathDebug.state.height / 2, 200);
    const pickMs = performance.now() - t;
    return { first, build: toolpathDebug.mode3d.buildMs, moving, coarse, frames, stats: view.stats, pickMs, picked, status: document.getElementById('status').textContent };
  })()`);
  console.log(`1,000,000 moves in 3D in Chromium (software WebGL): loaded and first frame ${((Date.now() - started) / 1000).toFixed(1)} s ` +
    `(paths ${figures.build.toFixed(0)} ms, first frame ${figures.first.toFixed(0)} ms), frame while orbiting median ${figures.moving[2].toFixed(0)} ms, ` +
    `still frame median ${figures.frames[1].toFixed(0)} ms, ${figures.stats.drawn} drawn, ${figures.stats.thinned} thinned, pick ${figures.pickMs.toFixed(0)} ms`);
  assert.ok(figures.coarse, 'frames while orbiting draw the coarse drawing');
  assert.ok(!figures.stats.coarse, 'the full drawing returns when the user lets go');
  assert.ok(figures.stats.thinned > 0 && figures.stats.drawn > 1000, 'thinned like the plane view');
  assert.ok(figures.picked >= 0, 'a click finds a move');
  assert.match(figures.status, /1,000,000 moves · 3D · mm · [\d,]+ thinned at this zoom/);
});

test('without WebGL the 3D switch is disabled, says why, and the plane view stays', async () => {
  const plain = await launch({ width: 600, height: 400, args: ['--disable-webgl', '--disable-3d-apis'] });
  try {
    await plain.goto(writePage('index3d-nowebgl.html'));
    await untilIn(plain, 'harness.sent.some((m) => m.type === "ready")', 'the page to say it is ready');
    await plain.evaluate('document.getElementById("mode-3d").click()');
    const state = await plain.evaluate(`({ disabled: document.getElementById("mode-3d").disabled, title: document.getElementById("mode-3d").title,
      plane: document.getElementById("canvas").style.display, pressed: document.getElementById("mode-2d").getAttribute("aria-pressed") })`);
    assert.equal(state.disabled, true);
    assert.match(state.title, /^3D view unavailable: /);
    assert.deepEqual([state.plane, state.pressed], ['block', 'true']);
  } finally {
    await plain.close();
  }
});
