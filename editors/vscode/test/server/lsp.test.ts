// The extension's side of the protocol against the real server binary (SINUMERIK_LSP_BIN, default
// ../../target/release/sinumerik-lsp): the settings it sends, the toolpath loaded range by range
// with the extension's own loader, the modal-state request of the status bar, and a settings change
// without a restart. tests/run-all.sh builds the binary first.

import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { after, before, test } from 'node:test';
import { pathToFileURL } from 'node:url';
import type { MessageConnection } from 'vscode-jsonrpc/node';
import { ToolpathLoader } from '../../src/core/loader';
import type { ToPage } from '../../src/core/messages';
import { MODAL_STATE_REQUEST, formatModalState, parseModalState } from '../../src/core/modalState';
import { concatPacked, packMoves, type PackedToolpath } from '../../src/core/packed';
import { parsePreview } from '../../src/core/preview';
import { serverSettings } from '../../src/core/settings';
import { EXTENSION_ROOT, readFixture } from '../unit/fixtures';
import { startServer, type TestServer } from './harness';

const demoPath = path.join(EXTENSION_ROOT, 'test', 'fixtures', 'demo_mill.mpf');
const demoUri = pathToFileURL(demoPath).toString();

let server: TestServer;
let connection: MessageConnection;

before(async () => {
  server = await startServer();
  connection = server.connection;
  await server.open(demoUri, fs.readFileSync(demoPath, 'utf8'));
});

after(async () => {
  await server?.stop();
});

test('the toolpath loaded range by range equals the CLI preview of the same program', async () => {
  const messages: ToPage[] = [];
  const loader = new ToolpathLoader({
    executePreview: (args) => connection.sendRequest('workspace/executeCommand', { command: 'sinumerik.endpointPreview', arguments: args }),
    post: (message) => messages.push(message),
    chunkLines: 5,
  });
  const lineCount = fs.readFileSync(demoPath, 'utf8').split('\n').length;
  await loader.load({ uri: demoUri, title: 'demo_mill.mpf', lineCount, plane: null });
  const error = messages.find((m) => m.type === 'error');
  assert.equal(error, undefined, JSON.stringify(error));
  const parts = messages.filter((m): m is Extract<ToPage, { type: 'append' }> => m.type === 'append').map((m) => m.packed);
  assert.ok(parts.length > 1, 'several ranges were asked for');
  const packed: PackedToolpath = concatPacked(parts);
  const expected = parsePreview(readFixture('demo_mill.preview.json')).moves;
  assert.deepEqual([...packed.line], expected.map((m) => m.line), 'every move once, in order');
  const arcs = expected.filter((m) => m.arc);
  assert.deepEqual([...packed.arcRadius], arcs.map((m) => m.arc!.radius));
  const ends = (p: PackedToolpath) => [...p.end].map((v) => (Number.isNaN(v) ? null : v));
  const whole = await connection.sendRequest('workspace/executeCommand', { command: 'sinumerik.endpointPreview', arguments: [{ uri: demoUri }] });
  assert.equal(parsePreview(whole).moves.length, expected.length, 'without lines, the whole program');
  assert.deepEqual(ends(packed), ends(packMoves(expected)), 'the end points of the CLI');
});

test('the status bar request gives the modal state at a line', async (t) => {
  let answer: unknown;
  try {
    // Line 6 is "N60 G1 X60" after "N50 G1 X10 Y0 F500": G1 before and after the block.
    answer = await connection.sendRequest(MODAL_STATE_REQUEST, { uri: demoUri, line: 6 });
  } catch (error) {
    if ((error as { code?: number }).code === -32601) {
      t.skip('the server does not implement sinumerik/modalState yet: the status bar stays hidden');
      return;
    }
    throw error;
  }
  const state = parseModalState(answer);
  assert.ok(state, `answer ${JSON.stringify(answer)}`);
  // A mill starts in DIAMOF (the Siemens reset state of group 29), which the server reports, but it
  // has no transverse axis, so the status bar leaves the diameter mode out; the program's machining
  // time follows (at least: the first move starts from an unknown position).
  assert.equal(state.diameter, 'DIAMOF');
  assert.equal(state.diameterAxis, false);
  assert.match(formatModalState(state, 6).text, /^G90 G71 G17 G1 · ⏱ ≥ \d/);
});

async function inlayHintCount(): Promise<number> {
  const hints = (await connection.sendRequest('textDocument/inlayHint', {
    textDocument: { uri: demoUri },
    range: { start: { line: 0, character: 0 }, end: { line: 40, character: 0 } },
  })) as unknown[] | null;
  return hints?.length ?? 0;
}

test('a settings change reaches the running server', async () => {
  server.settings = serverSettings((key) => ({ inlayHints: 'all' })[key]);
  await connection.sendNotification('workspace/didChangeConfiguration', { settings: { sinumerik: server.settings } });
  let all = 0;
  for (let i = 0; i < 100 && all === 0; i++) {
    all = await inlayHintCount();
    if (all === 0) await new Promise((resolve) => setTimeout(resolve, 50));
  }
  assert.ok(all >= 20, `${all} hints with inlayHints = all`);
  server.settings = serverSettings((key) => ({ inlayHints: 'off' })[key]);
  await connection.sendNotification('workspace/didChangeConfiguration', { settings: { sinumerik: server.settings } });
  let off = all;
  for (let i = 0; i < 100 && off !== 0; i++) {
    off = await inlayHintCount();
    if (off !== 0) await new Promise((resolve) => setTimeout(resolve, 50));
  }
  assert.equal(off, 0, 'no hints with inlayHints = off');
});
