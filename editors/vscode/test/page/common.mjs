// What the page tests share: the test page (the view's HTML with the harness), waiting for the page,
// reading colours off a canvas (the plane view's 2D canvas or the 3D view's WebGL canvas) and the
// palette's colours.
import * as fs from 'node:fs';
import { createRequire } from 'node:module';
import * as path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
export const root = path.resolve(here, '..', '..');
const require = createRequire(import.meta.url);
const { toolpathHtml } = require(path.join(root, 'out', 'src', 'webview', 'html.js'));

/** Writes the view's page with the harness as out/page/`name` and returns its URL. */
export function writePage(name = 'index.html') {
  const nonce = 'test-nonce';
  let html = toolpathHtml({ scriptUri: '../../dist/webview.js', cspSource: 'file:', nonce, title: 'demo_mill.mpf' });
  html = html.replace(`<script nonce="${nonce}"`, `<script nonce="${nonce}" src="harness.js"></script>\n<script nonce="${nonce}"`);
  const file = path.join(root, 'out', 'page', name);
  fs.writeFileSync(file, html);
  return pathToFileURL(file).href;
}

export async function until(page, expression, what, timeoutMs = 20000) {
  const started = Date.now();
  while (Date.now() - started < timeoutMs) {
    if (await page.evaluate(expression)) return;
    await new Promise((resolve) => setTimeout(resolve, 25));
  }
  throw new Error(`timed out waiting for ${what}; page said: ${page.consoleMessages.join(' | ')}`);
}

/** Colours (as [r, g, b]) in a square of `radius` pixels around a position on canvas `id`. A WebGL
 * canvas is drawn again and copied in the same task, so its picture is still there to be read. */
export async function canvasColours(page, id, x, y, radius = 2) {
  return page.evaluate(`(() => {
    const source = document.getElementById('${id}');
    let ctx = source.getContext('2d');
    if (!ctx) {
      toolpathDebug.redrawNow();
      const copy = document.createElement('canvas');
      copy.width = source.width;
      copy.height = source.height;
      ctx = copy.getContext('2d');
      ctx.drawImage(source, 0, 0);
    }
    const data = ctx.getImageData(${Math.round(x)} - ${radius}, ${Math.round(y)} - ${radius}, ${2 * radius + 1}, ${2 * radius + 1}).data;
    const out = [];
    for (let i = 0; i < data.length; i += 4) out.push([data[i], data[i + 1], data[i + 2]]);
    return out;
  })()`);
}

export function hex(colour) {
  const n = parseInt(colour.slice(1), 16);
  return [(n >> 16) & 255, (n >> 8) & 255, n & 255];
}

export function near(a, b, tolerance = 40) {
  return Math.abs(a[0] - b[0]) + Math.abs(a[1] - b[1]) + Math.abs(a[2] - b[2]) <= tolerance;
}

export const FEED = hex('#3b8eea');
export const RAPID = hex('#e05252');
export const UNCERTAIN = hex('#d7a600');
export const HIGHLIGHT = hex('#ffd500');
export const ERROR = hex('#f14c4c');
export const BACKGROUND = hex('#1e1e1e');

/** Whether a pixel shows `colour` over the background `under`, covering at least 60% of the pixel: a
 * line of one or 1.5 pixels on a pixel boundary is blended into its neighbours by antialiasing. */
export function covers(pixel, colour, under = BACKGROUND) {
  for (let a = 1; a >= 0.6; a -= 0.05) {
    if (near(pixel, colour.map((c, k) => under[k] + a * (c - under[k])), 30)) return true;
  }
  return false;
}
