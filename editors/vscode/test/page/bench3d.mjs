// Load and frame times of the toolpath page for a large generated program, through the real server:
//   node test/page/bench3d.mjs [lines] [style]     (default 1000000 cam3d; after npm run test:page)
// It writes the program with ../shared/bench/gen_program.py, runs `sinumerik-lsp preview` on it
// (SINUMERIK_LSP_BIN, default ../../target/release/sinumerik-lsp), reads and packs the answer as the
// extension does, and hands the packed arrays to the page in headless Chromium: the time until the
// first complete frame in the plane view and in the 3D view, and the time of later frames. The
// figures go to docs/performance.md by hand.
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as http from 'node:http';
import { createRequire } from 'node:module';
import * as path from 'node:path';
import { launch } from './cdp.mjs';
import { root, until, writePage } from './common.mjs';

const require = createRequire(import.meta.url);
const { parsePreview } = require(path.join(root, 'out', 'src', 'core', 'preview.js'));
const { packMoves } = require(path.join(root, 'out', 'src', 'core', 'packed.js'));

const lines = Number(process.argv[2] ?? 1_000_000);
const style = process.argv[3] ?? 'cam3d';
const binary = process.env.SINUMERIK_LSP_BIN || path.resolve(root, '..', '..', 'target', 'release', 'sinumerik-lsp');
const work = path.join(root, 'out', 'bench');
fs.mkdirSync(work, { recursive: true });
const program = path.join(work, `${style}_${lines}.mpf`);
const seconds = (ms) => `${(ms / 1000).toFixed(2)} s`;

let started = performance.now();
const generated = spawnSync('python3', [path.resolve(root, '..', '..', '..', 'shared', 'bench', 'gen_program.py'), '--lines', String(lines), '--style', style], { maxBuffer: 2 ** 30 });
if (generated.status !== 0) throw new Error(`gen_program.py failed: ${generated.stderr}`);
fs.writeFileSync(program, generated.stdout);
started = performance.now();
const previewed = spawnSync(binary, ['preview', '--format', 'json', path.basename(program)], { cwd: work, maxBuffer: 2 ** 31, encoding: 'utf8' });
if (previewed.status !== 0 && previewed.status !== 1) throw new Error(`preview failed (${previewed.status}): ${previewed.stderr}`);
const previewMs = performance.now() - started;
started = performance.now();
const answer = parsePreview(JSON.parse(previewed.stdout));
const packed = packMoves(answer.moves);
const packMs = performance.now() - started;
console.log(`${lines.toLocaleString('en')} lines (${style}): ${packed.count.toLocaleString('en')} moves; server preview ${seconds(previewMs)}, ` +
  `JSON read and packed in Node ${seconds(packMs)} (${(previewed.stdout.length / 1e6).toFixed(0)} MB of JSON)`);

// The typed arrays as one file, the rest as JSON: the page reads both from disk.
const arrays = [];
const blobs = [];
let offset = 0;
const meta = {};
for (const [name, value] of Object.entries(packed)) {
  if (ArrayBuffer.isView(value)) {
    const bytes = new Uint8Array(value.buffer, value.byteOffset, value.byteLength);
    const padded = Math.ceil(bytes.length / 8) * 8;
    arrays.push({ name, type: value.constructor.name, offset, length: value.length });
    blobs.push(bytes, new Uint8Array(padded - bytes.length));
    offset += padded;
  } else {
    meta[name] = value;
  }
}
fs.writeFileSync(path.join(work, 'packed.bin'), Buffer.concat(blobs));
fs.writeFileSync(path.join(work, 'packed.json'), JSON.stringify({ meta, arrays }));

// The page reads both files from a local server (a file: page may not read other files).
const files = { '/packed.json': path.join(work, 'packed.json'), '/packed.bin': path.join(work, 'packed.bin') };
const server = http.createServer((request, response) => {
  response.setHeader('Access-Control-Allow-Origin', '*');
  if (!files[request.url]) {
    response.writeHead(404).end();
    return;
  }
  fs.createReadStream(files[request.url]).pipe(response);
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const base = `http://127.0.0.1:${server.address().port}`;
const page = await launch({ width: 900, height: 640 });
try {
  // The view's content security policy lets it fetch nothing: the bench page may fetch from the local server.
  const url = writePage('bench.html');
  const file = path.join(root, 'out', 'page', 'bench.html');
  fs.writeFileSync(file, fs.readFileSync(file, 'utf8').replace("default-src 'none'", `default-src 'none'; connect-src ${base}`));
  await page.goto(url);
  await until(page, 'harness.sent.some((m) => m.type === "ready")', 'the page');
  await page.evaluate(`(async () => {
    const read = (url, type) => new Promise((resolve, reject) => {
      const request = new XMLHttpRequest();
      request.open('GET', url);
      request.responseType = type;
      request.onload = () => resolve(request.response);
      request.onerror = reject;
      request.send();
    });
    const { meta, arrays } = await read('${base}/packed.json', 'json');
    const buffer = await read('${base}/packed.bin', 'arraybuffer');
    window.benchPacked = { ...meta };
    for (const a of arrays) window.benchPacked[a.name] = new self[a.type](buffer, a.offset, a.length).slice(); // own buffers, as the extension sends them
  })()`);
  for (const mode of ['2d', '3d']) {
    const figures = await page.evaluate(`(async () => {
      document.getElementById('mode-${mode}').click();
      const marks = [];
      window.addEventListener('message', (event) => marks.push(event.data.type + ' ' + (performance.now() - t0).toFixed(0)));
      const t0 = performance.now();
      harness.loadPacked(benchPacked, 'bench-${mode}.mpf');
      await new Promise((resolve) => { const check = () => (toolpathDebug.state.done && toolpathDebug.state.title === 'bench-${mode}.mpf' ? resolve() : setTimeout(check, 5)); check(); });
      const sync = () => {
        const gl = toolpathDebug.mode3d.view?.renderer.getContext();
        if ('${mode}' === '3d') gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
      };
      toolpathDebug.redrawNow();
      sync();
      const first = performance.now() - t0;
      const frames = [];
      const moving = [];
      const view = toolpathDebug.mode3d.view;
      for (let i = 0; i < 5; i++) {
        if ('${mode}' === '3d') {
          view.controls.dispatchEvent({ type: 'start' });
          view.camera.position.sub(view.controls.target).applyAxisAngle(view.camera.up, 0.2).add(view.controls.target);
          view.controls.update();
          let t = performance.now();
          toolpathDebug.redrawNow();
          sync();
          moving.push(performance.now() - t);
          view.controls.dispatchEvent({ type: 'end' });
        }
        const t = performance.now();
        toolpathDebug.redrawNow();
        sync();
        frames.push(performance.now() - t);
      }
      frames.sort((a, b) => a - b);
      moving.sort((a, b) => a - b);
      const stats = '${mode}' === '3d' ? view.stats : toolpathDebug.state.stats;
      console.log(marks.join(', '), 'paths', toolpathDebug.mode3d.buildMs, 'thin', toolpathDebug.mode3d.view?.stats.thinMs);
      return { first, frame: frames[2], moving: moving[2], drawn: stats.drawn, thinned: stats.thinned, status: document.getElementById('status').textContent };
    })()`);
    console.log(`${mode.toUpperCase()}: first complete frame ${seconds(figures.first)} after the page got the moves, frame ${figures.frame.toFixed(0)} ms` +
      (figures.moving !== null && figures.moving !== undefined ? `, frame while orbiting ${figures.moving.toFixed(0)} ms` : '') +
      `; ${figures.drawn.toLocaleString('en')} segments drawn, ${figures.thinned.toLocaleString('en')} thinned\n  ${figures.status}`);
  }
} finally {
  if (process.env.BENCH_TRACE) console.log(page.consoleMessages.join('\n'));
  await page.close();
  server.close();
}
