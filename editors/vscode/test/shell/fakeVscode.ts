// A stand-in for the `vscode` module with just what the extension's shell uses (status bar, webview
// panel, editors, documents, settings), recording what the shell does. Loaded with
// `node --require out/test/shell/fakeVscode.js`, which makes `require('vscode')` return it.

import Module from 'node:module';
import * as path from 'node:path';

type Listener<T> = (value: T) => unknown;

export class EventEmitter<T> {
  private listeners: Listener<T>[] = [];
  event = (listener: Listener<T>) => {
    this.listeners.push(listener);
    return { dispose: () => (this.listeners = this.listeners.filter((l) => l !== listener)) };
  };
  fire(value: T): void {
    for (const listener of [...this.listeners]) listener(value);
  }
  dispose(): void {
    this.listeners = [];
  }
}

export const ViewColumn = { One: 1, Two: 2, Beside: -2 };
export const StatusBarAlignment = { Left: 1, Right: 2 };
export const TextEditorRevealType = { Default: 0, InCenter: 1, InCenterIfOutsideViewport: 2, AtTop: 3 };

export class Uri {
  constructor(readonly fsPath: string) {}
  static file(file: string): Uri {
    return new Uri(file);
  }
  /** Only `file:` URIs, which are all the tests use. */
  static parse(text: string): Uri {
    if (!text.startsWith('file://')) throw new Error(`the stand-in reads file: URIs only, not ${text}`);
    return new Uri(decodeURIComponent(text.slice('file://'.length)));
  }
  static joinPath(base: Uri, ...parts: string[]): Uri {
    return new Uri(path.join(base.fsPath, ...parts));
  }
  toString(): string {
    return `file://${this.fsPath}`;
  }
}

export class Position {
  constructor(readonly line: number, readonly character: number) {}
}

export class Range {
  constructor(readonly start: Position, readonly end: Position) {}
}

export class Selection extends Range {
  constructor(readonly anchor: Position, readonly active: Position) {
    super(anchor, active);
  }
}

export class FakeDocument {
  readonly uri: Uri;
  constructor(readonly fileName: string, public lines: string[], readonly languageId = 'sinumerik') {
    this.uri = Uri.file(fileName);
  }
  get lineCount(): number {
    return this.lines.length;
  }
  lineAt(line: number) {
    return { range: new Range(new Position(line, 0), new Position(line, this.lines[line].length)) };
  }
}

export class FakeEditor {
  selection: Selection = new Selection(new Position(0, 0), new Position(0, 0));
  revealed: Range[] = [];
  constructor(readonly document: FakeDocument, readonly viewColumn = ViewColumn.One) {}
  revealRange(range: Range): void {
    this.revealed.push(range);
  }
}

export class FakeStatusBarItem {
  text = '';
  tooltip: string | undefined;
  name = '';
  visible = false;
  show(): void {
    this.visible = true;
  }
  hide(): void {
    this.visible = false;
  }
  dispose(): void {}
}

export class FakePanel {
  title: string;
  readonly toPage: unknown[] = [];
  readonly fromPage = new EventEmitter<unknown>();
  readonly disposed = new EventEmitter<void>();
  readonly webview = {
    html: '',
    cspSource: 'vscode-webview:',
    asWebviewUri: (uri: Uri) => uri,
    postMessage: async (message: unknown) => {
      this.toPage.push(message);
      return true;
    },
    onDidReceiveMessage: this.fromPage.event,
  };
  onDidDispose = this.disposed.event;
  constructor(readonly viewType: string, title: string, readonly options: unknown) {
    this.title = title;
  }
  reveal(): void {}
  dispose(): void {
    this.disposed.fire();
  }
}

export const recorded = {
  panels: [] as FakePanel[],
  statusItems: [] as FakeStatusBarItem[],
  information: [] as string[],
  errors: [] as string[],
  statusMessages: [] as string[],
  /** The options of every input box shown, and the answers the next ones give (`undefined`: cancelled). */
  inputBoxes: [] as { value?: string; validateInput?: (value: string) => string | undefined }[],
  inputAnswers: [] as (string | undefined)[],
  /** The items of every quick pick shown, and the labels the next ones pick (`undefined`: cancelled). */
  quickPicks: [] as { label: string }[][],
  quickPickAnswers: [] as (string | undefined)[],
  shownDocuments: [] as FakeDocument[],
  shownEditors: [] as FakeEditor[],
  /** The files `workspace.openTextDocument` finds (by path), and the URIs it was asked for. */
  files: new Map<string, FakeDocument>(),
  opened: [] as string[],
  settings: {} as Record<string, unknown>,
  activeEditorChanged: new EventEmitter<FakeEditor | undefined>(),
  selectionChanged: new EventEmitter<{ textEditor: FakeEditor; selections: Selection[] }>(),
  documentChanged: new EventEmitter<{ document: FakeDocument }>(),
};

export const window = {
  activeTextEditor: undefined as FakeEditor | undefined,
  visibleTextEditors: [] as FakeEditor[],
  createWebviewPanel(viewType: string, title: string, _column: unknown, options: unknown) {
    const panel = new FakePanel(viewType, title, options);
    recorded.panels.push(panel);
    return panel;
  },
  createStatusBarItem() {
    const item = new FakeStatusBarItem();
    recorded.statusItems.push(item);
    return item;
  },
  async showTextDocument(document: FakeDocument, options?: { viewColumn?: number }) {
    recorded.shownDocuments.push(document);
    const editor = window.visibleTextEditors.find((candidate) => candidate.document === document) ?? new FakeEditor(document, options?.viewColumn);
    recorded.shownEditors.push(editor);
    return editor;
  },
  async showInformationMessage(message: string) {
    recorded.information.push(message);
    return undefined;
  },
  async showErrorMessage(message: string) {
    recorded.errors.push(message);
    return undefined;
  },
  setStatusBarMessage(message: string) {
    recorded.statusMessages.push(message);
    return { dispose: () => undefined };
  },
  async showInputBox(options: { value?: string; validateInput?: (value: string) => string | undefined }) {
    recorded.inputBoxes.push(options);
    return recorded.inputAnswers.shift();
  },
  async showQuickPick<T extends { label: string }>(items: T[]) {
    recorded.quickPicks.push(items);
    const label = recorded.quickPickAnswers.shift();
    return items.find((item) => item.label === label);
  },
  onDidChangeActiveTextEditor: recorded.activeEditorChanged.event,
  onDidChangeTextEditorSelection: recorded.selectionChanged.event,
};

export const workspace = {
  onDidChangeTextDocument: recorded.documentChanged.event,
  async openTextDocument(uri: Uri) {
    recorded.opened.push(uri.toString());
    const document = recorded.files.get(uri.fsPath);
    if (!document) throw new Error(`cannot open ${uri.fsPath}: no such file`);
    return document;
  },
  getConfiguration(section: string) {
    return { get: (key: string) => recorded.settings[`${section}.${key}`] };
  },
};

// `require('vscode')` anywhere in the process gives this module.
const resolve = (Module as unknown as { _resolveFilename: (request: string, ...rest: unknown[]) => string })._resolveFilename;
(Module as unknown as { _resolveFilename: unknown })._resolveFilename = function (request: string, ...rest: unknown[]) {
  return request === 'vscode' ? __filename : resolve.call(this, request, ...rest);
};
