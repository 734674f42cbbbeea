// The commands of the extension against the real server binary, as VS Code runs them: renumbering
// and formatting through workspace/executeCommand with the requests the extension builds, the
// server's workspace/applyEdit answered by applying the edit and sending the new text back (as the
// language client does), and what the editor asks on its own: go to definition, completion and
// semantic tokens, read through the legend and the scopes of package.json.

import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { after, before, test } from 'node:test';
import { formatRequest, renumberRequest, type ExecuteCommandParams } from '../../src/core/programCommands';
import { EXTENSION_ROOT } from '../unit/fixtures';
import { KNOWN_TOKEN_MODIFIERS, KNOWN_TOKEN_TYPES, scopeOf, TOKEN_SCOPES } from '../unit/semanticLegend';
import { applyTextEdits, decodeSemanticTokens, definition, editsFor, startServer, type TestServer, type TextEdit } from './harness';

/** The client's copy of one open document, kept in step with the server like VS Code does. */
interface ClientDocument {
  uri: string;
  text: string;
  version: number;
}

const documents = new Map<string, ClientDocument>();
/** Whether the client applies the next workspace edits (VS Code refuses one for a changed document). */
let applyEdits = true;
const appliedEdits: string[] = [];
let server: TestServer;

async function open(name: string, text: string): Promise<ClientDocument> {
  const document = { uri: `file:///sinumerik-test/${name}`, text, version: 1 };
  documents.set(document.uri, document);
  await server.open(document.uri, text);
  return document;
}

before(async () => {
  const register = (connection: TestServer['connection']) => {
    connection.onRequest('workspace/applyEdit', async (params: { edit: Parameters<typeof editsFor>[0] }) => {
      if (!applyEdits) return { applied: false, failureReason: 'the test refuses the edit' };
      for (const document of documents.values()) {
        const edits = editsFor(params.edit, document.uri);
        if (edits.length === 0) continue;
        document.text = applyTextEdits(document.text, edits);
        document.version += 1;
        appliedEdits.push(document.uri);
        await connection.sendNotification('textDocument/didChange', {
          textDocument: { uri: document.uri, version: document.version },
          contentChanges: [{ text: document.text }],
        });
      }
      return { applied: true };
    });
  };
  server = await startServer({ register });
});

after(async () => {
  await server?.stop();
});

function execute(request: ExecuteCommandParams): Promise<unknown> {
  return server.connection.sendRequest('workspace/executeCommand', request);
}

const NUMBERED = ['N1 G90 G71 G17 G0 X0 Y0', 'N2 IF R1 > 0 GOTOF N9', 'N3 G1 X10 F100', 'N9 G0 X20', 'M30', ''].join('\n');

test('renumbering through the extension\'s request edits the program, jumps included', async () => {
  const document = await open('renumber.mpf', NUMBERED);
  const edits = appliedEdits.length;
  const answer = await execute(renumberRequest(document.uri, { start: 100, step: 5, mode: 'all' }));
  assert.deepEqual(document.text.split('\n'), ['N100 G90 G71 G17 G0 X0 Y0', 'N105 IF R1 > 0 GOTOF N115', 'N110 G1 X10 F100', 'N115 G0 X20', 'N120 M30', '']);
  assert.equal((answer as { applied: boolean }).applied, true);
  assert.ok((answer as { edits: number }).edits > 0, JSON.stringify(answer));

  assert.equal(appliedEdits.length - edits, 1, 'one workspace edit, so one undo takes it back');

  // The server saw the applied edit: the same numbers again change nothing, and nothing is sent.
  const again = await execute(renumberRequest(document.uri, { start: 100, step: 5, mode: 'all' }));
  assert.equal((again as { edits: number }).edits, 0, JSON.stringify(again));
  assert.equal(appliedEdits.length - edits, 1);

  const dropped = await execute(renumberRequest(document.uri, { start: 10, step: 10, mode: 'drop' }));
  assert.equal((dropped as { applied: boolean }).applied, true);
  assert.deepEqual(document.text.split('\n'), ['G90 G71 G17 G0 X0 Y0', 'IF R1 > 0 GOTOF N10', 'G1 X10 F100', 'N10 G0 X20', 'M30', '']);
});

test('a renumbering the server refuses comes back as an error with a message for the user', async () => {
  const document = await open('refused.mpf', NUMBERED);
  await assert.rejects(
    execute(renumberRequest(document.uri, { start: 10, step: 0, mode: 'keep' })),
    (error: { code?: number; message?: string }) => error.code === -32602 && /step/.test(error.message ?? ''),
  );
  await assert.rejects(
    execute(renumberRequest('file:///sinumerik-test/not-open.mpf', { start: 10, step: 10, mode: 'keep' })),
    (error: { code?: number }) => error.code === -32602,
  );
  assert.equal(document.text, NUMBERED, 'nothing was edited');
});

test('formatting through the extension\'s request edits the program; the formatting request gives the same text', async () => {
  const text = 'n10 g0x10  y5\nN20 g1 x=ic( 5 ) f100\nm30\n';
  const expected = 'N10 G0 X10 Y5\nN20 G1 X=IC(5) F100\nM30\n';
  const viaRequest = await open('format-request.mpf', text);
  const edits = (await server.connection.sendRequest('textDocument/formatting', {
    textDocument: { uri: viaRequest.uri },
    options: { tabSize: 4, insertSpaces: true },
  })) as TextEdit[];
  assert.equal(applyTextEdits(text, edits ?? []), expected, 'Format Document');

  const document = await open('format.mpf', text);
  const answer = await execute(formatRequest(document.uri));
  assert.equal(document.text, expected);
  assert.equal((answer as { applied: boolean }).applied, true);
  assert.equal(((await execute(formatRequest(document.uri))) as { edits: number }).edits, 0, 'formatted text stays');

  applyEdits = false;
  try {
    const refusing = await open('format-refused.mpf', text);
    const refused = (await execute(formatRequest(refusing.uri))) as { applied: boolean; edits: number };
    assert.equal(refused.applied, false, 'the client refused the edit');
    assert.ok(refused.edits > 0);
    assert.equal(refusing.text, text);
  } finally {
    applyEdits = true;
  }
});

// The program both editors' tests navigate: line 4 jumps forward to FINISH (line 7) and line 6
// backward to START (line 1); DEPTH is declared on line 0 and used on line 5.
const NAVIGATION = fs.readFileSync(path.join(EXTENSION_ROOT, '..', '..', 'fixtures', 'editors', 'navigation.mpf'), 'utf8');

test('go to definition finds the label of a jump and the DEF of a variable', async () => {
  const document = await open('navigation.mpf', NAVIGATION);
  const lines = NAVIGATION.split('\n');
  const finish = await definition(server, document.uri, 4, lines[4].indexOf('FINISH') + 2);
  assert.deepEqual(finish.map((l) => [l.uri, l.range.start.line]), [[document.uri, 7]]);
  const start = await definition(server, document.uri, 6, lines[6].indexOf('START') + 1);
  assert.deepEqual(start.map((l) => [l.uri, l.range.start.line]), [[document.uri, 1]]);
  const depth = await definition(server, document.uri, 5, lines[5].indexOf('DEPTH') + 1);
  assert.deepEqual(depth.map((l) => [l.uri, l.range.start.line, l.range.start.character]), [[document.uri, 0, lines[0].indexOf('DEPTH')]]);
});

interface CompletionItem {
  label: string;
  detail?: string;
}

async function completion(uri: string, line: number, character: number): Promise<CompletionItem[]> {
  const answer = (await server.connection.sendRequest('textDocument/completion', {
    textDocument: { uri },
    position: { line, character },
  })) as CompletionItem[] | { items: CompletionItem[] } | null;
  return answer === null ? [] : Array.isArray(answer) ? answer : answer.items;
}

test('completion offers the labels a jump can reach and G functions with their group', async () => {
  const document = await open('completion.mpf', NAVIGATION);
  const lines = NAVIGATION.split('\n');
  const forward = await completion(document.uri, 4, lines[4].indexOf('FINISH'));
  assert.deepEqual(forward.map((item) => item.label), ['FINISH'], 'GOTOF reaches only the labels below');
  const backward = await completion(document.uri, 6, lines[6].indexOf('START'));
  assert.deepEqual(backward.map((item) => item.label), ['START'], 'GOTOB reaches only the labels above');
  const gCodes = await completion(document.uri, 5, 'N30 G1'.length);
  const g17 = gCodes.find((item) => item.label === 'G17');
  assert.ok(g17, `G17 among ${gCodes.map((item) => item.label).join(' ')}`);
  assert.match(g17.detail ?? '', /group 6/i);
  assert.ok(!gCodes.some((item) => item.label === 'G0'), 'only what starts with the typed G1');
});

interface Legend {
  tokenTypes: string[];
  tokenModifiers: string[];
}

test('every semantic token kind of the server is known to VS Code and has a scope', () => {
  const provider = server.initialized.capabilities.semanticTokensProvider as { legend: Legend; range?: boolean } | undefined;
  assert.ok(provider, 'the server offers semantic tokens');
  assert.ok(provider.range, 'also for a range');
  for (const type of provider.legend.tokenTypes) {
    assert.ok(KNOWN_TOKEN_TYPES.has(type), `${type}: declared in package.json semanticTokenTypes`);
    assert.ok(TOKEN_SCOPES[type], `${type}: mapped in package.json semanticTokenScopes`);
  }
  for (const modifier of provider.legend.tokenModifiers) {
    assert.ok(KNOWN_TOKEN_MODIFIERS.has(modifier), `${modifier}: declared in package.json semanticTokenModifiers`);
  }
});

test('semantic tokens give block numbers, G groups, axes, labels and variables their scopes', async () => {
  const document = await open('tokens.mpf', NAVIGATION);
  const lines = NAVIGATION.split('\n');
  const legend = (server.initialized.capabilities.semanticTokensProvider as { legend: Legend }).legend;
  const full = (await server.connection.sendRequest('textDocument/semanticTokens/full', { textDocument: { uri: document.uri } })) as { data: number[] };
  const tokens = decodeSemanticTokens(full.data, legend);
  const scopeAt = (line: number, word: string) => {
    const character = lines[line].indexOf(word);
    const token = tokens.find((t) => t.line === line && t.character <= character && character < t.character + t.length);
    return token ? scopeOf(token.type, token.modifiers) : `no token at ${line}:${character}`;
  };
  assert.deepEqual(
    [scopeAt(2, 'N10'), scopeAt(2, 'G90'), scopeAt(2, 'G17'), scopeAt(2, 'G0'), scopeAt(2, 'X0'), scopeAt(4, 'FINISH'), scopeAt(7, 'FINISH'), scopeAt(5, 'DEPTH'), scopeAt(0, 'DEPTH'), scopeAt(4, 'R1')],
    [
      'constant.other.block-number.sinumerik',
      'keyword.other.g-code.distance.sinumerik',
      'keyword.other.g-code.plane.sinumerik',
      'keyword.other.g-code.motion.sinumerik',
      'variable.other.axis.sinumerik',
      'entity.name.label.sinumerik',
      'entity.name.label.sinumerik',
      'variable.other.name.sinumerik',
      'variable.other.name.sinumerik',
      'variable.parameter.r-parameter.sinumerik',
    ],
  );
  const range = (await server.connection.sendRequest('textDocument/semanticTokens/range', {
    textDocument: { uri: document.uri },
    range: { start: { line: 4, character: 0 }, end: { line: 4, character: lines[4].length } },
  })) as { data: number[] };
  const inRange = decodeSemanticTokens(range.data, legend);
  assert.ok(inRange.length > 0 && inRange.every((t) => t.line === 4), JSON.stringify(inRange));
  assert.deepEqual(inRange, tokens.filter((t) => t.line === 4), 'the same tokens as in the whole document');
});
