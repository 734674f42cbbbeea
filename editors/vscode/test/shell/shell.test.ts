// The extension's VS Code shell with a fake `vscode` module: the toolpath panel (loading through the
// server handle, following the cursor and edits, revealing a clicked line) and the status bar.

import assert from 'node:assert/strict';
import { test } from 'node:test';
import * as vscode from 'vscode';
import type { ToPage } from '../../src/core/messages';
import { formatProgram, renumberBlocks } from '../../src/vscode/programCommands';
import { ModalStatusBar } from '../../src/vscode/statusBar';
import { ToolpathPanel } from '../../src/vscode/toolpathPanel';
import type { RequestSender, ServerHandle } from '../../src/vscode/serverHandle';
import { readFixture } from '../unit/fixtures';
import { FakeDocument, FakeEditor, Position, recorded, Selection, EventEmitter, window } from './fakeVscode';

const fake = vscode as unknown as { window: typeof window };

function fakeServer(answer: (method: string, params: unknown) => unknown): ServerHandle & { requests: [string, unknown][] } {
  const requests: [string, unknown][] = [];
  const client: RequestSender = {
    sendRequest: async (method, params) => {
      requests.push([method, params]);
      const value = answer(method, params);
      if (value instanceof Error) throw value;
      return value;
    },
  };
  return { client, onDidChangeClient: new EventEmitter<RequestSender | undefined>().event, requests };
}

const wait = (ms: number) => new Promise((resolve) => setTimeout(resolve, ms));
const demo = readFixture('demo_mill.preview.json') as { moves: { line: number }[] };
const context = { extensionPath: '/ext' } as unknown as vscode.ExtensionContext;

test('the toolpath panel loads the program, follows the cursor and edits, and reveals a clicked line', async () => {
  const document = new FakeDocument('/work/demo_mill.mpf', new Array(28).fill('N10 G1 X1'));
  const editor = new FakeEditor(document);
  editor.selection = new Selection(new Position(7, 3), new Position(7, 3));
  fake.window.activeTextEditor = editor;
  fake.window.visibleTextEditors = [editor];
  const server = fakeServer((method, params) => {
    if (method === 'sinumerik/modalState') return { motion: 'G3', plane: 'G17', units: 'G71', distance: 'G90', diameter: null };
    const { startLine, endLine } = (params as { arguments: { startLine: number; endLine: number }[] }).arguments[0];
    return { ...demo, moves: demo.moves.filter((m) => m.line - 1 >= startLine && m.line - 1 <= endLine) };
  });
  ToolpathPanel.show(context, server);
  const panel = recorded.panels[0];
  assert.equal(panel.title, 'Toolpath: demo_mill.mpf');
  assert.match(panel.webview.html, /<script nonce="[0-9a-f]{32}" src="file:\/\/\/ext\/dist\/webview\.js"><\/script>/);
  assert.match(panel.webview.html, /script-src 'nonce-[0-9a-f]{32}'/);
  assert.equal(panel.toPage.length, 0, 'nothing is sent before the page is ready');

  panel.fromPage.fire({ type: 'ready' });
  await wait(50);
  const messages = panel.toPage as ToPage[];
  assert.deepEqual(messages.map((m) => m.type), ['reset', 'append', 'done', 'cursor']);
  assert.deepEqual(messages[0], { type: 'reset', generation: 1, title: 'demo_mill.mpf', units: 'mm', plane: 'G17' });
  assert.equal(messages[1].type === 'append' && messages[1].packed.count, 23);
  assert.deepEqual(messages[3], { type: 'cursor', line: 8 });
  const preview = server.requests.find(([method]) => method === 'workspace/executeCommand')!;
  assert.deepEqual(preview[1], { command: 'sinumerik.endpointPreview', arguments: [{ uri: 'file:///work/demo_mill.mpf', startLine: 0, endLine: 28 }] });

  recorded.selectionChanged.fire({ textEditor: editor, selections: [new Selection(new Position(10, 0), new Position(10, 0))] });
  assert.deepEqual(panel.toPage[panel.toPage.length - 1], { type: 'cursor', line: 11 });

  panel.fromPage.fire({ type: 'reveal', line: 11 });
  await wait(10);
  assert.equal(recorded.shownDocuments[0], document);
  assert.deepEqual([editor.selection.start.line, editor.selection.start.character, editor.selection.end.line, editor.selection.end.character], [10, 0, 10, 9]);
  assert.equal(editor.revealed.length, 1);

  const before = panel.toPage.length;
  recorded.documentChanged.fire({ document });
  recorded.documentChanged.fire({ document });
  await wait(100);
  assert.equal(panel.toPage.length, before, 'edits are waited for');
  await wait(500);
  const resets = (panel.toPage.slice(before) as ToPage[]).filter((m) => m.type === 'reset');
  assert.equal(resets.length, 1, 'two quick edits give one reload');
  assert.equal(resets[0].type === 'reset' && resets[0].generation, 2);

  recorded.settings['sinumerik.toolpath.followEdits'] = false;
  const quiet = panel.toPage.length;
  recorded.documentChanged.fire({ document });
  await wait(500);
  assert.equal(panel.toPage.length, quiet, 'followEdits = false stops redrawing on edits');
  delete recorded.settings['sinumerik.toolpath.followEdits'];
  panel.dispose();
});

const calls = readFixture('calls_mill.preview.json') as { moves: { line: number; stack?: { line: number }[] }[] };

/** A server that answers the toolpath of calls_mill.mpf by outermost line, as the server does. */
function callsServer() {
  return fakeServer((method, params) => {
    if (method === 'sinumerik/modalState') return null;
    const { startLine, endLine } = (params as { arguments: { startLine: number; endLine: number }[] }).arguments[0];
    const outer = (m: (typeof calls.moves)[number]) => (m.stack?.length ? m.stack[0].line : m.line) - 1;
    return { ...calls, moves: calls.moves.filter((m) => outer(m) >= startLine && outer(m) <= endLine) };
  });
}

test('a click on a move of a called program opens that program at its line, which stays linked to the toolpath', async () => {
  const program = new FakeDocument('/work/calls_mill.mpf', new Array(19).fill('N10 G1 X1'));
  const editor = new FakeEditor(program);
  const slot = new FakeDocument('/work/SLOT.SPF', ['; slot', 'PROC SLOT', 'N10 G91 G1 Z-7 F200', 'N20 X20 F400', 'N30 G0 Z7', 'N40 G90', 'N50 M17']);
  recorded.files.set(slot.fileName, slot);
  fake.window.activeTextEditor = editor;
  fake.window.visibleTextEditors = [editor];
  ToolpathPanel.show(context, callsServer());
  const panel = recorded.panels[recorded.panels.length - 1];
  panel.fromPage.fire({ type: 'ready' });
  await wait(50);
  const append = (panel.toPage as ToPage[]).find((m) => m.type === 'append');
  assert.ok(append && append.type === 'append');
  assert.deepEqual(append.packed.files, ['file:///work/calls_mill.mpf', 'file:///work/SLOT.SPF']);

  // The page asks for line 4 of SLOT.SPF (N20, the slot's cut).
  const shown = recorded.shownDocuments.length;
  panel.fromPage.fire({ type: 'reveal', line: 4, file: 'file:///work/SLOT.SPF' });
  await wait(10);
  assert.deepEqual(recorded.opened.slice(-1), ['file:///work/SLOT.SPF'], 'the file is opened by its URI');
  assert.equal(recorded.shownDocuments.length, shown + 1);
  assert.equal(recorded.shownDocuments[shown], slot);
  const slotEditor = recorded.shownEditors[recorded.shownEditors.length - 1];
  assert.equal(slotEditor.viewColumn, editor.viewColumn, 'in the column of the program shown');
  const { start, end } = slotEditor.selection;
  assert.deepEqual([start.line, start.character, end.line, end.character], [3, 0, 3, 12]);
  assert.equal(slotEditor.revealed.length, 1);

  // The called program becomes the active editor: the panel keeps the program it shows, and the
  // cursor in SLOT.SPF is sent with its file.
  const before = panel.toPage.length;
  fake.window.activeTextEditor = slotEditor;
  fake.window.visibleTextEditors = [slotEditor];
  recorded.activeEditorChanged.fire(slotEditor);
  slotEditor.selection = new Selection(new Position(4, 0), new Position(4, 0));
  recorded.selectionChanged.fire({ textEditor: slotEditor, selections: [slotEditor.selection] });
  await wait(10);
  assert.equal(panel.title, 'Toolpath: calls_mill.mpf');
  const sent = panel.toPage.slice(before) as ToPage[];
  assert.ok(!sent.some((m) => m.type === 'reset'), 'no reload for the called program');
  assert.deepEqual(sent[sent.length - 1], { type: 'cursor', line: 5, file: 'file:///work/SLOT.SPF' });

  // An edit of the called program redraws the toolpath that runs through it.
  recorded.documentChanged.fire({ document: slot });
  await wait(500);
  assert.ok((panel.toPage.slice(before) as ToPage[]).some((m) => m.type === 'reset'), 'an edit of SLOT.SPF reloads');
  assert.deepEqual(panel.toPage[panel.toPage.length - 1], { type: 'cursor', line: 5, file: 'file:///work/SLOT.SPF' }, 'the cursor stays in SLOT.SPF');

  // A file that cannot be opened is said so.
  panel.fromPage.fire({ type: 'reveal', line: 2, file: 'file:///work/GONE.SPF' });
  await wait(10);
  assert.match(recorded.errors[recorded.errors.length - 1], /file:\/\/\/work\/GONE\.SPF could not be opened: cannot open \/work\/GONE\.SPF/);

  // A program that is not part of the toolpath becomes the one shown.
  const other = new FakeEditor(new FakeDocument('/work/OTHER.SPF', ['N10 G0 X0']));
  recorded.activeEditorChanged.fire(other);
  assert.equal(panel.title, 'Toolpath: OTHER.SPF');
  panel.dispose();
});

test('the panel asks for a SINUMERIK program when another file is active', () => {
  const other = new FakeEditor(new FakeDocument('/work/notes.txt', ['x'], 'plaintext'));
  fake.window.activeTextEditor = other;
  const panels = recorded.panels.length;
  ToolpathPanel.show(context, fakeServer(() => null));
  assert.equal(recorded.panels.length, panels);
  assert.match(recorded.information[recorded.information.length - 1], /Open a SINUMERIK program/);
});

test('the status bar shows the modal state at the cursor and hides when the server cannot say', async () => {
  const document = new FakeDocument('/work/a.mpf', ['G90 G71 G17 G1 X1 F100', 'X2']);
  const editor = new FakeEditor(document);
  editor.selection = new Selection(new Position(1, 0), new Position(1, 0));
  fake.window.activeTextEditor = editor;
  let fail = false;
  let timed = false;
  const time = { total_s: 75, feed_s: 70, rapid_s: 5, dwell_s: 0, unknown_moves: 2 };
  const server = fakeServer((method) => (fail ? Object.assign(new Error('no such method'), { code: -32601 }) : method === 'sinumerik/modalState'
    ? { motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null, ...(timed ? { time } : {}) } : null));
  const bar = new ModalStatusBar(server);
  await wait(200);
  const item = recorded.statusItems[recorded.statusItems.length - 1];
  assert.equal(item.text, 'G90 G71 G17 G1');
  assert.ok(item.visible);
  assert.deepEqual(server.requests[server.requests.length - 1], ['sinumerik/modalState', { uri: 'file:///work/a.mpf', line: 1 }]);
  // A server that estimates the machining time adds the program's total.
  timed = true;
  recorded.selectionChanged.fire({ textEditor: editor, selections: [editor.selection] });
  await wait(200);
  assert.equal(item.text, 'G90 G71 G17 G1 · ⏱ ≥ 1 min 15 s');
  timed = false;
  fail = true;
  recorded.selectionChanged.fire({ textEditor: editor, selections: [editor.selection] });
  await wait(200);
  assert.equal(item.visible, false);
  fake.window.activeTextEditor = new FakeEditor(new FakeDocument('/work/b.txt', ['x'], 'plaintext'));
  fail = false;
  recorded.activeEditorChanged.fire(fake.window.activeTextEditor);
  await wait(200);
  assert.equal(item.visible, false, 'hidden for other languages');
  bar.dispose();
});

function fakeContext(): vscode.ExtensionContext & { stored: Map<string, unknown> } {
  const stored = new Map<string, unknown>();
  const globalState = { get: (key: string) => stored.get(key), update: async (key: string, value: unknown) => void stored.set(key, value) };
  return { extensionPath: '/ext', globalState, stored } as unknown as vscode.ExtensionContext & { stored: Map<string, unknown> };
}

test('renumbering asks start, step and mode, validates them, sends the server command and remembers the choice', async () => {
  fake.window.activeTextEditor = new FakeEditor(new FakeDocument('/work/part.mpf', ['N1 G0 X0']));
  const context = fakeContext();
  const server = fakeServer(() => ({ applied: true, edits: 2 }));
  recorded.inputAnswers.push('100', '5');
  recorded.quickPickAnswers.push('Drop');
  const boxes = recorded.inputBoxes.length;
  await renumberBlocks(context, server);
  const [startBox, stepBox] = recorded.inputBoxes.slice(boxes);
  assert.deepEqual([startBox.value, stepBox.value], ['10', '10'], 'the defaults at first');
  assert.match(startBox.validateInput!('abc') ?? '', /whole number/);
  assert.equal(startBox.validateInput!('0'), undefined);
  assert.match(stepBox.validateInput!('0') ?? '', /at least 1/);
  assert.deepEqual(recorded.quickPicks[recorded.quickPicks.length - 1].map((item) => item.label), ['Keep', 'All', 'Drop']);
  assert.deepEqual(server.requests, [['workspace/executeCommand', {
    command: 'sinumerik.renumber', arguments: [{ uri: 'file:///work/part.mpf', start: 100, step: 5, mode: 'drop' }],
  }]]);
  assert.equal(recorded.statusMessages[recorded.statusMessages.length - 1], 'Renumbering: 2 changes applied.');

  // The next run starts from the last choice; cancelling the step box sends nothing.
  recorded.inputAnswers.push('100', undefined);
  await renumberBlocks(context, server);
  assert.deepEqual(recorded.inputBoxes.slice(-2).map((box) => box.value), ['100', '5']);
  assert.equal(server.requests.length, 1, 'cancelled');
  recorded.inputAnswers.push('20', '20');
  recorded.quickPickAnswers.push(undefined);
  await renumberBlocks(context, server);
  assert.deepEqual(recorded.quickPicks[recorded.quickPicks.length - 1].map((item) => item.label), ['Drop', 'Keep', 'All']);
  assert.equal(server.requests.length, 1, 'no mode picked');
  assert.deepEqual(context.stored.get('sinumerik.renumber.lastChoice'), { start: 100, step: 5, mode: 'drop' });
});

test('a refusal of the server is shown as an error, and the commands need a SINUMERIK program', async () => {
  fake.window.activeTextEditor = new FakeEditor(new FakeDocument('/work/part.spf', ['N1 G0 X0']));
  const refusing = fakeServer(() => Object.assign(new Error('line 3: the jump to N30 has no target now'), { code: -32602 }));
  recorded.inputAnswers.push('10', '10');
  recorded.quickPickAnswers.push('Keep');
  await renumberBlocks(fakeContext(), refusing);
  assert.equal(recorded.errors[recorded.errors.length - 1], 'Renumbering failed: line 3: the jump to N30 has no target now');

  const formatting = fakeServer(() => ({ applied: true, edits: 0 }));
  await formatProgram(formatting);
  assert.deepEqual(formatting.requests, [['workspace/executeCommand', { command: 'sinumerik.format', arguments: [{ uri: 'file:///work/part.spf' }] }]]);
  assert.equal(recorded.statusMessages[recorded.statusMessages.length - 1], 'Formatting: nothing to change.');
  await formatProgram(fakeServer(() => ({ applied: false, edits: 3 })));
  assert.match(recorded.errors[recorded.errors.length - 1], /^Formatting: the editor did not apply the changes/);
  await formatProgram({ client: undefined, onDidChangeClient: new EventEmitter<RequestSender | undefined>().event });
  assert.match(recorded.errors[recorded.errors.length - 1], /language server is not running/);

  fake.window.activeTextEditor = new FakeEditor(new FakeDocument('/work/notes.txt', ['x'], 'plaintext'));
  const other = fakeServer(() => ({ applied: true, edits: 1 }));
  const boxes = recorded.inputBoxes.length;
  await renumberBlocks(fakeContext(), other);
  await formatProgram(other);
  assert.equal(other.requests.length, 0);
  assert.equal(recorded.inputBoxes.length, boxes, 'nothing is asked');
  assert.match(recorded.information[recorded.information.length - 1], /Open a SINUMERIK program/);
});
