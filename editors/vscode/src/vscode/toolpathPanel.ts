// The "SINUMERIK: Show Toolpath" webview beside the editor: it shows the active program, follows its
// edits and the cursor, and reveals the line of a clicked segment. The toolpath runs through the
// programs the shown one calls: their editors stay linked to it (their cursor highlights their
// moves, a click on one of their moves opens them) instead of becoming the program shown.

import * as crypto from 'node:crypto';
import * as path from 'node:path';
import * as vscode from 'vscode';
import { fileUri } from '../core/files';
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
      // The server may spell a URI differently from VS Code (an encoded drive colon): VS Code's own
      // spelling is the one editors and the page compare.
      fileKey: (name, base) => vscode.Uri.parse(fileUri(name, base)).toString(),
    });
    this.subscriptions.push(
      webview.onDidReceiveMessage((message: FromPage) => this.receive(message)),
      this.panel.onDidDispose(() => this.dispose()),
      vscode.window.onDidChangeActiveTextEditor((editor) => {
        if (!editor || editor.document.languageId !== LANGUAGE_ID) return;
        // A called program opened from the picture (or by hand) stays linked to the program shown.
        if (this.loader.isCalledFile(editor.document.uri.toString())) this.postCursor(editor.document, editor.selection.active.line);
        else this.follow(editor.document);
      }),
      vscode.workspace.onDidChangeTextDocument((event) => {
        if (!this.followEdits() || !this.shows(event.document)) return;
        if (this.editTimer) clearTimeout(this.editTimer);
        this.editTimer = setTimeout(() => void this.reload(), EDIT_DELAY_MS);
      }),
      vscode.window.onDidChangeTextEditorSelection((event) => {
        this.postCursor(event.textEditor.document, event.selections[0].active.line);
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

  /** Whether the toolpath runs through this document: the program shown or one it calls. */
  private shows(document: vscode.TextDocument): boolean {
    return document === this.document || this.loader.isCalledFile(document.uri.toString());
  }

  /** Tells the page the cursor's 0-based line in the program shown or in a program it calls. */
  private postCursor(document: vscode.TextDocument, line: number): void {
    if (document === this.document) this.post({ type: 'cursor', line: line + 1 });
    else if (this.loader.isCalledFile(document.uri.toString())) this.post({ type: 'cursor', line: line + 1, file: document.uri.toString() });
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
    // The cursor of the active editor when it is in the toolpath (a called program after its edit),
    // else the cursor of the program shown.
    const active = vscode.window.activeTextEditor;
    const editor =
      active && this.shows(active.document) ? active : vscode.window.visibleTextEditors.find((candidate) => candidate.document === document);
    if (editor) this.postCursor(editor.document, editor.selection.active.line);
  }

  private receive(message: FromPage): void {
    if (message.type === 'ready') {
      this.ready = true;
      void this.reload();
    } else if (message.type === 'reveal' && this.document) {
      void this.reveal(this.document, message.line, message.file);
    }
  }

  /** Selects a 1-based line of the program shown, or of `file` (a called program's URI), which is
   * opened when it is not yet. */
  private async reveal(shown: vscode.TextDocument, line: number, file: string | undefined): Promise<void> {
    let document = shown;
    if (file && file !== shown.uri.toString()) {
      try {
        document = await vscode.workspace.openTextDocument(vscode.Uri.parse(file));
      } catch (error) {
        const reason = error instanceof Error ? error.message : String(error);
        void vscode.window.showErrorMessage(`The toolpath's file ${file} could not be opened: ${reason}`);
        return;
      }
    }
    const index = Math.max(0, Math.min(line - 1, document.lineCount - 1));
    const range = document.lineAt(index).range;
    // The column of an editor that shows the file already, else the one of the program shown.
    const visible =
      vscode.window.visibleTextEditors.find((editor) => editor.document.uri.toString() === document.uri.toString()) ??
      vscode.window.visibleTextEditors.find((editor) => editor.document === shown);
    const editor = await vscode.window.showTextDocument(document, {
      viewColumn: visible?.viewColumn ?? vscode.ViewColumn.One,
      preserveFocus: false,
    });
    editor.selection = new vscode.Selection(range.start, range.end);
    editor.revealRange(range, vscode.TextEditorRevealType.InCenterIfOutsideViewport);
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
