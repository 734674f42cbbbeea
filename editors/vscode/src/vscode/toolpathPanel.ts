// The "SINUMERIK: Show Toolpath" webview beside the editor: it shows the active program, follows its
// edits and the cursor, and reveals the line of a clicked segment.

import * as crypto from 'node:crypto';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { ToolpathLoader, PREVIEW_COMMAND } from '../core/loader';
import type { FromPage, PlaneName, ToPage } from '../core/messages';
import { MODAL_STATE_REQUEST, parseModalState } from '../core/modalState';
import { toolpathHtml } from '../webview/html';
import { LANGUAGE_ID } from '../core/language';
import type { ServerHandle } from './serverHandle';

const EDIT_DELAY_MS = 400;

export class ToolpathPanel implements vscode.Disposable {
  private static current: ToolpathPanel | undefined;
  private readonly subscriptions: vscode.Disposable[] = [];
  private document: vscode.TextDocument | undefined;
  private ready = false;
  private editTimer: NodeJS.Timeout | undefined;
  private readonly loader: ToolpathLoader;

  static show(context: vscode.ExtensionContext, server: ServerHandle): void {
    const editor = vscode.window.activeTextEditor;
    if (!editor || editor.document.languageId !== LANGUAGE_ID) {
      void vscode.window.showInformationMessage('Open a SINUMERIK program (.MPF, .SPF) to show its toolpath.');
      return;
    }
    if (!ToolpathPanel.current) ToolpathPanel.current = new ToolpathPanel(context, server);
    ToolpathPanel.current.panel.reveal(vscode.ViewColumn.Beside, true);
    ToolpathPanel.current.follow(editor.document);
  }

  private readonly panel: vscode.WebviewPanel;

  private constructor(context: vscode.ExtensionContext, private readonly server: ServerHandle) {
    const dist = vscode.Uri.file(path.join(context.extensionPath, 'dist'));
    this.panel = vscode.window.createWebviewPanel(
      'sinumerik.toolpath',
      'Toolpath',
      { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true },
      { enableScripts: true, retainContextWhenHidden: true, localResourceRoots: [dist] },
    );
    const webview = this.panel.webview;
    webview.html = toolpathHtml({
      scriptUri: webview.asWebviewUri(vscode.Uri.joinPath(dist, 'webview.js')).toString(),
      cspSource: webview.cspSource,
      nonce: crypto.randomBytes(16).toString('hex'),
      title: 'Toolpath',
    });
    this.loader = new ToolpathLoader({
      executePreview: (args) => {
        const client = this.server.client;
        if (!client) return Promise.reject(new Error('the language server is not running'));
        return client.sendRequest('workspace/executeCommand', { command: PREVIEW_COMMAND, arguments: args });
      },
      post: (message) => this.post(message),
    });
    this.subscriptions.push(
      webview.onDidReceiveMessage((message: FromPage) => this.receive(message)),
      this.panel.onDidDispose(() => this.dispose()),
      vscode.window.onDidChangeActiveTextEditor((editor) => {
        if (editor && editor.document.languageId === LANGUAGE_ID) this.follow(editor.document);
      }),
      vscode.workspace.onDidChangeTextDocument((event) => {
        if (event.document !== this.document || !this.followEdits()) return;
        if (this.editTimer) clearTimeout(this.editTimer);
        this.editTimer = setTimeout(() => void this.reload(), EDIT_DELAY_MS);
      }),
      vscode.window.onDidChangeTextEditorSelection((event) => {
        if (event.textEditor.document === this.document) {
          this.post({ type: 'cursor', line: event.selections[0].active.line + 1 });
        }
      }),
      server.onDidChangeClient((client) => {
        if (client) void this.reload();
      }),
    );
  }

  private followEdits(): boolean {
    return vscode.workspace.getConfiguration('sinumerik').get<boolean>('toolpath.followEdits') ?? true;
  }

  private follow(document: vscode.TextDocument): void {
    if (document === this.document) return;
    this.document = document;
    this.panel.title = `Toolpath: ${path.basename(document.fileName)}`;
    void this.reload();
  }

  private post(message: ToPage): void {
    if (this.ready) void this.panel.webview.postMessage(message);
  }

  /** The plane at the cursor, when the server knows it; otherwise the page guesses from the moves. */
  private async planeAtCursor(document: vscode.TextDocument): Promise<PlaneName | null> {
    const client = this.server.client;
    const editor = vscode.window.visibleTextEditors.find((candidate) => candidate.document === document);
    if (!client || !editor) return null;
    try {
      const state = parseModalState(
        await client.sendRequest(MODAL_STATE_REQUEST, { uri: document.uri.toString(), line: editor.selection.active.line }),
      );
      const plane = state?.plane;
      return plane === 'G17' || plane === 'G18' || plane === 'G19' ? plane : null;
    } catch {
      return null;
    }
  }

  private async reload(): Promise<void> {
    const document = this.document;
    if (!document || !this.ready || !this.server.client) return;
    await this.loader.load({
      uri: document.uri.toString(),
      title: path.basename(document.fileName),
      lineCount: document.lineCount,
      plane: await this.planeAtCursor(document),
    });
    const editor = vscode.window.visibleTextEditors.find((candidate) => candidate.document === document);
    if (editor) this.post({ type: 'cursor', line: editor.selection.active.line + 1 });
  }

  private receive(message: FromPage): void {
    if (message.type === 'ready') {
      this.ready = true;
      void this.reload();
    } else if (message.type === 'reveal' && this.document) {
      const line = Math.max(0, Math.min(message.line - 1, this.document.lineCount - 1));
      const range = this.document.lineAt(line).range;
      const visible = vscode.window.visibleTextEditors.find((editor) => editor.document === this.document);
      void vscode.window
        .showTextDocument(this.document, { viewColumn: visible?.viewColumn ?? vscode.ViewColumn.One, preserveFocus: false })
        .then((editor) => {
          editor.selection = new vscode.Selection(range.start, range.end);
          editor.revealRange(range, vscode.TextEditorRevealType.InCenterIfOutsideViewport);
        });
    }
  }

  private disposed = false;

  dispose(): void {
    if (this.disposed) return;
    this.disposed = true;
    ToolpathPanel.current = undefined;
    if (this.editTimer) clearTimeout(this.editTimer);
    this.subscriptions.forEach((subscription) => subscription.dispose());
    this.panel.dispose();
  }
}
