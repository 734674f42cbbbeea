// The real server binary (SINUMERIK_LSP_BIN, default ../../target/release/sinumerik-lsp) over stdio,
// initialized the way vscode-languageclient does it: the settings as initializationOptions and as
// the answer to workspace/configuration, and the client capabilities the tests rely on.

import assert from 'node:assert/strict';
import { spawn, type ChildProcess } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { pathToFileURL } from 'node:url';
import { createMessageConnection, StreamMessageReader, StreamMessageWriter, type MessageConnection } from 'vscode-jsonrpc/node';
import { serverSettings, type ServerSettings } from '../../src/core/settings';
import { EXTENSION_ROOT } from '../unit/fixtures';

export const SERVER_BINARY = process.env.SINUMERIK_LSP_BIN ?? path.resolve(EXTENSION_ROOT, '..', '..', 'target', 'release', 'sinumerik-lsp');

export interface TestServer {
  connection: MessageConnection;
  /** The server's answer to initialize. */
  initialized: { capabilities: Record<string, unknown> };
  /** The last diagnostics published per URI. */
  diagnostics: Map<string, unknown[]>;
  /** The settings answered to workspace/configuration; tests change them. */
  settings: ServerSettings;
  open(uri: string, text: string): Promise<void>;
  stop(): Promise<void>;
}

export interface ServerOptions {
  /** Adds the test's own handlers (workspace/applyEdit, $/progress, ...) before the connection listens. */
  register?: (connection: MessageConnection) => void;
  /** The workspace folder; default the extension's folder. */
  rootPath?: string;
  /** The settings at start; default the extension's defaults. */
  settings?: ServerSettings;
}

export async function startServer(options: ServerOptions = {}): Promise<TestServer> {
  assert.ok(fs.existsSync(SERVER_BINARY), `no server binary at ${SERVER_BINARY}: build it with cargo build --release, or set SINUMERIK_LSP_BIN`);
  const child: ChildProcess = spawn(SERVER_BINARY, ['serve'], { stdio: ['pipe', 'pipe', 'inherit'] });
  const connection = createMessageConnection(new StreamMessageReader(child.stdout!), new StreamMessageWriter(child.stdin!));
  const diagnostics = new Map<string, unknown[]>();
  const server = { settings: options.settings ?? serverSettings(() => undefined) } as TestServer;
  let stopping = false;
  // A server that ends early fails the requests still waiting for it instead of leaving them hanging.
  child.on('exit', (code, signal) => {
    if (!stopping) process.stderr.write(`the server ended early (exit code ${code}, signal ${signal})\n`);
    connection.dispose();
  });
  // What vscode-languageclient answers for workspace/configuration: the section from the settings.
  connection.onRequest('workspace/configuration', (params: { items: { section?: string }[] }) =>
    params.items.map((item) => (item.section === 'sinumerik' ? server.settings : null)),
  );
  connection.onRequest('workspace/inlayHint/refresh', () => null);
  connection.onRequest('workspace/semanticTokens/refresh', () => null);
  connection.onRequest('client/registerCapability', () => null);
  connection.onRequest('window/workDoneProgress/create', () => null);
  connection.onNotification('$/progress', () => undefined);
  connection.onNotification('textDocument/publishDiagnostics', (params: { uri: string; diagnostics: unknown[] }) => {
    diagnostics.set(params.uri, params.diagnostics);
  });
  options.register?.(connection);
  connection.listen();
  const initialized = (await connection.sendRequest('initialize', {
    processId: process.pid,
    rootUri: pathToFileURL(options.rootPath ?? EXTENSION_ROOT).toString(),
    capabilities: {
      workspace: {
        configuration: true,
        applyEdit: true,
        workspaceEdit: { documentChanges: true },
        didChangeConfiguration: { dynamicRegistration: true },
        inlayHint: { refreshSupport: true },
      },
      window: { workDoneProgress: true },
      textDocument: {
        inlayHint: {},
        hover: { contentFormat: ['markdown', 'plaintext'] },
        completion: { completionItem: { snippetSupport: true } },
      },
    },
    initializationOptions: server.settings,
  })) as TestServer['initialized'];
  await connection.sendNotification('initialized', {});
  return Object.assign(server, {
    connection,
    initialized,
    diagnostics,
    open: (uri: string, text: string) =>
      connection.sendNotification('textDocument/didOpen', { textDocument: { uri, languageId: 'sinumerik', version: 1, text } }),
    stop: async () => {
      stopping = true;
      const shutdown = connection.sendRequest('shutdown').catch(() => undefined);
      await Promise.race([shutdown, new Promise((resolve) => setTimeout(resolve, 5000).unref())]);
      await connection.sendNotification('exit').catch(() => undefined);
      connection.dispose();
      child.kill();
    },
  });
}

interface Position {
  line: number;
  character: number;
}

export interface TextEdit {
  range: { start: Position; end: Position };
  newText: string;
}

function offsetOf(text: string, position: Position): number {
  let offset = 0;
  for (let line = 0; line < position.line; line++) {
    const next = text.indexOf('\n', offset);
    if (next < 0) return text.length;
    offset = next + 1;
  }
  const lineEnd = text.indexOf('\n', offset);
  return Math.min(offset + position.character, lineEnd < 0 ? text.length : lineEnd);
}

/** `text` with `edits` applied as the protocol defines them: all ranges refer to the original text. */
export function applyTextEdits(text: string, edits: TextEdit[]): string {
  const located = edits.map((edit) => ({ start: offsetOf(text, edit.range.start), end: offsetOf(text, edit.range.end), newText: edit.newText }));
  located.sort((a, b) => b.start - a.start || b.end - a.end);
  for (const edit of located) text = text.slice(0, edit.start) + edit.newText + text.slice(edit.end);
  return text;
}

/** The edits of a WorkspaceEdit for `uri`, from `changes` or `documentChanges`. */
export function editsFor(edit: { changes?: Record<string, TextEdit[]>; documentChanges?: { textDocument: { uri: string }; edits: TextEdit[] }[] }, uri: string): TextEdit[] {
  const fromChanges = edit.changes?.[uri] ?? [];
  const fromDocumentChanges = (edit.documentChanges ?? []).filter((change) => change.textDocument?.uri === uri).flatMap((change) => change.edits);
  return [...fromChanges, ...fromDocumentChanges];
}

export interface DecodedToken {
  line: number;
  character: number;
  length: number;
  type: string;
  modifiers: string[];
}

/** The tokens of `data` (five numbers per token, line and start relative to the previous token). */
export function decodeSemanticTokens(data: readonly number[], legend: { tokenTypes: string[]; tokenModifiers: string[] }): DecodedToken[] {
  const tokens: DecodedToken[] = [];
  let line = 0;
  let character = 0;
  for (let index = 0; index + 4 < data.length; index += 5) {
    const [deltaLine, deltaStart, length, type, bits] = data.slice(index, index + 5);
    line += deltaLine;
    character = deltaLine === 0 ? character + deltaStart : deltaStart;
    const modifiers = legend.tokenModifiers.filter((_, bit) => (bits >> bit) & 1);
    tokens.push({ line, character, length, type: legend.tokenTypes[type] ?? `#${type}`, modifiers });
  }
  return tokens;
}

export interface Location {
  uri: string;
  range: { start: { line: number; character: number } };
}

/** The locations of go to definition, whichever form the server answers in. */
export async function definition(server: TestServer, uri: string, line: number, character: number): Promise<Location[]> {
  const answer = (await server.connection.sendRequest('textDocument/definition', {
    textDocument: { uri },
    position: { line, character },
  })) as Location | Location[] | { targetUri: string; targetSelectionRange: Location['range'] }[] | null;
  const list = answer === null ? [] : Array.isArray(answer) ? answer : [answer];
  return list.map((item) => ('targetUri' in item ? { uri: item.targetUri, range: item.targetSelectionRange } : item));
}
