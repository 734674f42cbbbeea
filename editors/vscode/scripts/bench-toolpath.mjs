// Benchmark (prints figures, asserts nothing): how long the toolpath of a generated program takes to
// reach the page through the real server, range by range, as the extension loads it; then the
// page's projection and one full redraw with a recording canvas.
//   node scripts/bench-toolpath.mjs [--lines 1000000] [--style cam3d]     (after npm run test:unit)
import { spawn, execFileSync } from 'node:child_process';
import * as path from 'node:path';
import { createRequire } from 'node:module';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const require = createRequire(import.meta.url);
const { createMessageConnection, StreamMessageReader, StreamMessageWriter } = require('vscode-jsonrpc/node');
const { ToolpathLoader } = require(path.join(root, 'out/src/core/loader.js'));
const { concatPacked } = require(path.join(root, 'out/src/core/packed.js'));
const { project, fitView } = require(path.join(root, 'out/src/webview/geometry.js'));
const { render } = require(path.join(root, 'out/src/webview/render.js'));

const argument = (name, fallback) => {
  const index = process.argv.indexOf(name);
  return index > 0 ? process.argv[index + 1] : fallback;
};
const lines = Number(argument('--lines', '1000000'));
const style = argument('--style', 'cam3d');
const generator = path.resolve(root, '..', '..', '..', 'shared', 'bench', 'gen_program.py');
const binary = process.env.SINUMERIK_LSP_BIN ?? path.resolve(root, '..', '..', 'target', 'release', 'sinumerik-lsp');

const text = execFileSync('python3', [generator, '--lines', String(lines), '--style', style], { maxBuffer: 1 << 30 }).toString();
const uri = pathToFileURL(path.join(root, 'out', `bench-${style}.mpf`)).toString();
const server = spawn(binary, ['serve'], { stdio: ['pipe', 'pipe', 'inherit'] });
const connection = createMessageConnection(new StreamMessageReader(server.stdout), new StreamMessageWriter(server.stdin));
connection.onRequest('workspace/configuration', (params) => params.items.map(() => null));
connection.onRequest('client/registerCapability', () => null);
connection.listen();
await connection.sendRequest('initialize', { processId: process.pid, rootUri: null, capabilities: {} });
connection.sendNotification('initialized', {});
let started = performance.now();
connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'sinumerik', version: 1, text } });

const parts = [];
let firstPartMs = 0;
const loader = new ToolpathLoader({
  executePreview: (args) => connection.sendRequest('workspace/executeCommand', { command: 'sinumerik.endpointPreview', arguments: args }),
  post: (message) => {
    if (message.type === 'append') {
      if (!parts.length) firstPartMs = performance.now() - started;
      parts.push(message.packed);
    }
    if (message.type === 'error') console.log(message.message);
  },
});
await loader.load({ uri, title: 'bench', lineCount: text.split('\n').length, plane: null });
const loadMs = performance.now() - started;
const packed = concatPacked(parts);
started = performance.now();
const projected = project(packed, 'G17');
const projectMs = performance.now() - started;
const noop = { moveTo() {}, lineTo() {}, ellipse() {} };
const canvas = { strokeStyle: '', fillStyle: '', lineWidth: 1, setLineDash() {}, stroke() {}, fillRect() {}, clearRect() {} };
started = performance.now();
const stats = render(canvas, () => noop, projected, fitView(projected.bounds, 1200, 800), 1200, 800, '#000');
const renderMs = performance.now() - started;
console.log(`${lines.toLocaleString('en')} lines (${style}): ${packed.count.toLocaleString('en')} moves in ${parts.length} ranges; ` +
  `first range on the page after ${firstPartMs.toFixed(0)} ms (from didOpen), all after ${loadMs.toFixed(0)} ms; ` +
  `projection ${projectMs.toFixed(0)} ms; full redraw ${renderMs.toFixed(0)} ms (${stats.drawn.toLocaleString('en')} drawn, ${stats.thinned.toLocaleString('en')} thinned)`);
await connection.sendRequest('shutdown');
connection.sendNotification('exit');
setTimeout(() => process.exit(0), 200);
