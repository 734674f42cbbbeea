// What a real VS Code showed wrong in the plane view, in headless Chromium at a normal panel width
// (600 pixels): the status line of a six-move program fits and says nothing is thinned, and wraps
// between its parts when the panel is narrow; the drawing fits again when the panel below opens
// (unless the user zoomed); a circle that cannot exist (CR too small) is dashed in the error colour
// with a cross instead of a plain straight line.
import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { after, before, test } from 'node:test';
import { launch } from './cdp.mjs';
import { BACKGROUND, canvasColours, covers, ERROR, near, root, until as untilIn, writePage } from './common.mjs';

const fixture = (name) => fs.readFileSync(path.join(root, 'test', 'fixtures', name), 'utf8');

let page;
const until = (expression, what, timeoutMs) => untilIn(page, expression, what, timeoutMs);
const colours = (x, y, radius = 2) => canvasColours(page, 'canvas', x, y, radius);
const hasColour = async (x, y, colour, radius = 2) => (await colours(x, y, radius)).some((c) => covers(c, colour));
const status = () => page.evaluate('document.getElementById("status").textContent');

async function screen(x, y) {
  const view = await page.evaluate('toolpathDebug.state.view');
  return [view.offsetX + x * view.scale, view.offsetY - y * view.scale];
}

/** How the status line's parts sit in it: cut (ellipsized) parts and parts outside its box. */
function statusLayout() {
  return page.evaluate(`(() => {
    const line = document.getElementById('status');
    const box = line.getBoundingClientRect();
    const parts = [...line.querySelectorAll('.part')];
    return {
      parts: parts.length,
      cut: parts.filter((p) => p.scrollWidth > p.clientWidth + 1).map((p) => p.textContent),
      outside: parts.filter((p) => { const r = p.getBoundingClientRect(); return r.right > box.right + 0.5 || r.bottom > box.bottom + 0.5; }).map((p) => p.textContent),
      title: line.title,
      text: line.textContent,
    };
  })()`);
}

before(async () => {
  page = await launch({ width: 600, height: 480 });
  await page.goto(writePage('fixes.html'));
  await until('harness.sent.some((m) => m.type === "ready")', 'the page to say it is ready');
  await page.evaluate(`harness.loadPreview(${fixture('circle_cr.preview.json')}, 'circle_cr.mpf', 10, null, 4)`);
  await until('toolpathDebug.state.done && toolpathDebug.state.stats !== null', 'the drawing');
  await page.evaluate('toolpathDebug.redrawNow()');
});

after(async () => {
  await page?.close();
});

test('a six-move program thins nothing, and its status line fits a normal panel width', async () => {
  const text = await status();
  assert.match(text, /^circle_cr\.mpf: 6 moves · plane G17 X\/Y · mm · 1 not drawn \(position unknown in this plane\) · 1 circle that cannot exist \(dashed, ✕\)/);
  assert.doesNotMatch(text, /thinned/, 'N30 G1 Z-2 has no length in X/Y: nothing to thin');
  await page.evaluate('harness.setCursor(8)');
  await until('toolpathDebug.state.cursorLine === 8', 'the cursor message');
  await page.evaluate('toolpathDebug.redrawNow()');
  const layout = await statusLayout();
  assert.ok(layout.parts >= 6, `${layout.parts} parts`);
  assert.deepEqual(layout.cut, [], 'no part is cut at 600 pixels');
  assert.deepEqual(layout.outside, [], `every part is inside the status line: ${layout.text}`);
  assert.equal(layout.title, layout.text, 'the whole text is the tooltip');
  assert.match(layout.text, / · line 8: 1 moves?$| · line 8$/);
});

test('in a narrow panel the status line wraps between its parts and cuts a part only at its end', async () => {
  await page.evaluate('document.body.style.width = "300px"');
  await page.evaluate('toolpathDebug.redrawNow()');
  const layout = await statusLayout();
  // What does not fit in two lines is hidden below; what is shown is whole parts, each at most a line.
  const shown = await page.evaluate(`(() => {
    const line = document.getElementById('status');
    const box = line.getBoundingClientRect();
    return [...line.querySelectorAll('.part')].filter((p) => p.getBoundingClientRect().bottom <= box.bottom + 0.5)
      .map((p) => [p.textContent, p.getBoundingClientRect().right <= box.right + 0.5]);
  })()`);
  assert.ok(shown.length >= 2, `${shown.length} parts shown`);
  assert.ok(shown.every(([, inside]) => inside), `no part runs past the right edge: ${JSON.stringify(shown)}`);
  assert.equal(shown[0][0], 'circle_cr.mpf: 6 moves');
  assert.equal(layout.title, layout.text);
  await page.evaluate('document.body.style.width = ""');
  await until('toolpathDebug.state.width === 600', 'the canvas at its width again');
});

test('the drawing fits again when the panel below opens, unless the user zoomed', async () => {
  await page.evaluate('toolpathDebug.redrawNow()');
  const fitted = await page.evaluate('toolpathDebug.state.view');
  // The panel below opening makes the webview lower.
  await page.evaluate('document.body.style.height = "300px"');
  await until('toolpathDebug.state.height < 250', 'the lower canvas');
  await page.evaluate('toolpathDebug.redrawNow()');
  const refitted = await page.evaluate('toolpathDebug.state.view');
  assert.ok(refitted.scale < fitted.scale * 0.8, `smaller to fit: ${fitted.scale} -> ${refitted.scale}`);
  const { bounds, height, width } = await page.evaluate('({ bounds: toolpathDebug.state.projected.bounds, height: toolpathDebug.state.height, width: toolpathDebug.state.width })');
  for (const [x, y] of [[bounds.minX, bounds.minY], [bounds.maxX, bounds.maxY]]) {
    const [sx, sy] = await screen(x, y);
    assert.ok(sx >= 0 && sx <= width && sy >= 0 && sy <= height, `X${x} Y${y} on the canvas at ${sx}, ${sy}`);
  }
  // After the user zoomed, a resize keeps their view.
  const origin = await page.evaluate('(() => { const r = document.getElementById("canvas").getBoundingClientRect(); return [r.left, r.top]; })()');
  await page.wheel(origin[0] + 200, origin[1] + 100, -300);
  await until(`toolpathDebug.state.view.scale > ${refitted.scale * 1.2}`, 'the zoom');
  const zoomed = await page.evaluate('toolpathDebug.state.view');
  await page.evaluate('document.body.style.height = ""');
  await until('toolpathDebug.state.height > 300', 'the canvas at its size again');
  assert.deepEqual(await page.evaluate('toolpathDebug.state.view'), zoomed);
  await page.evaluate('document.getElementById("fit").click()');
  await page.evaluate('toolpathDebug.redrawNow()');
  const final = await page.evaluate('[toolpathDebug.state.view.scale, toolpathDebug.state.width, toolpathDebug.state.height]');
  assert.ok(Math.abs(final[0] - fitted.scale) < 1e-9, `Fit as before: ${fitted.scale} ${final}`);
});

test('a circle that cannot exist is dashed in the error colour with a cross, and its tooltip says why', async () => {
  await page.evaluate('harness.setCursor(1)');
  await until('toolpathDebug.state.cursorLine === 1', 'the cursor message');
  await page.evaluate('toolpathDebug.redrawNow()');
  // N60 G2 X60 Y40 CR=10 from X50 Y20.
  const [mx, my] = await screen(55, 30);
  let arms = 0;
  for (const [dx, dy] of [[-4, -4], [4, 4], [-4, 4], [4, -4]]) if (await hasColour(mx + dx, my + dy, ERROR, 1)) arms++;
  assert.equal(arms, 4, `the four arms of the cross: ${JSON.stringify(await colours(mx, my, 5))}`);
  let marked = 0;
  let gaps = 0;
  for (let t = 0.05; t < 0.4; t += 0.01) {
    const [sx, sy] = await screen(50 + 10 * t, 20 + 20 * t);
    const [centre] = await colours(sx, sy, 0);
    if (covers(centre, ERROR)) marked++;
    else if (near(centre, BACKGROUND, 30)) gaps++;
  }
  assert.ok(marked >= 5 && gaps >= 3, `dashed: ${marked} error-coloured and ${gaps} background samples`);
  const origin = await page.evaluate('(() => { const r = document.getElementById("canvas").getBoundingClientRect(); return [r.left, r.top]; })()');
  const [sx, sy] = await screen(52, 24);
  await page.hover(origin[0] + sx, origin[1] + sy);
  assert.match(await page.evaluate('document.getElementById("tip").textContent'),
    /^N60, line 8 {2}G2 {2}→ X60 Y40 Z-2 F300\nno circle fits these numbers \(see the problem on this line\)/);
});
