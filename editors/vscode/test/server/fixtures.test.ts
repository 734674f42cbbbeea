// The toolpath view's preview fixtures are the server's own answer: each `NAME.preview.json` in
// test/fixtures is, byte for byte, what `sinumerik-lsp preview --format json NAME.mpf` prints when run
// in that folder (SINUMERIK_LSP_BIN, default ../../target/release/sinumerik-lsp). To write one again:
//   cd editors/vscode/test/fixtures && sinumerik-lsp preview --format json NAME.mpf > NAME.preview.json
// demo_mill.preview.json is older and kept as it is (its uncertain moves after a label are what the
// page test draws); lsp.test.ts compares its lines, arcs and end points with the server.

import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { test } from 'node:test';
import { EXTENSION_ROOT } from '../unit/fixtures';
import { SERVER_BINARY } from './harness';

const FIXTURES = path.join(EXTENSION_ROOT, 'test', 'fixtures');

function preview(name: string): string {
  assert.ok(fs.existsSync(SERVER_BINARY), `no server binary at ${SERVER_BINARY}: build it with cargo build --release, or set SINUMERIK_LSP_BIN`);
  // A program with an error finding makes the command exit with 1 after printing the whole answer.
  const run = spawnSync(SERVER_BINARY, ['preview', '--format', 'json', `${name}.mpf`], { cwd: FIXTURES, encoding: 'utf8' });
  assert.ok(run.status === 0 || run.status === 1, `preview of ${name}.mpf failed (${run.status}): ${run.stderr}`);
  return run.stdout;
}

function committed(name: string): string {
  return fs.readFileSync(path.join(FIXTURES, `${name}.preview.json`), 'utf8');
}

const REGENERATE = (name: string) =>
  `regenerate it: cd editors/vscode/test/fixtures && sinumerik-lsp preview --format json ${name}.mpf > ${name}.preview.json`;

test('calls_mill.preview.json is the server\'s answer', () => {
  assert.equal(preview('calls_mill'), committed('calls_mill'), REGENERATE('calls_mill'));
});

// The reference's cases T106, T107 and T125: a rounding, two chamfers and a row of holes under a
// modal drilling cycle (first written by hand from the reference's figures; the server's answer
// agreed with them to the third decimal).
test('contours_drill.preview.json is the server\'s answer', () => {
  assert.equal(preview('contours_drill'), committed('contours_drill'), REGENERATE('contours_drill'));
});

// A circle the control rejects (CR too small for its end point): the move keeps its end point but
// has no arc, which the toolpath view draws dashed in the error colour with a cross.
test('circle_cr.preview.json is the server\'s answer', () => {
  assert.equal(preview('circle_cr'), committed('circle_cr'), REGENERATE('circle_cr'));
  const answer = JSON.parse(committed('circle_cr'));
  const circle = answer.moves.find((move: { line: number }) => move.line === 8);
  assert.equal(circle.motion, 'G2');
  assert.equal(circle.arc, null);
  assert.ok(answer.diagnostics.some((d: { line: number; code: string }) => d.line === 8 && d.code === 'A207'));
});
