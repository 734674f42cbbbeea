// The status-bar item with the modal state at the cursor, asked from the server as the cursor moves.

import * as vscode from 'vscode';
import { formatModalState, MODAL_STATE_REQUEST, parseModalState } from '../core/modalState';
import { LANGUAGE_ID } from '../core/language';
import type { ServerHandle } from './serverHandle';

export class ModalStatusBar implements vscode.Disposable {
  private readonly item = vscode.window.createStatusBarItem('sinumerik.modalState', vscode.StatusBarAlignment.Right, 100);
  private readonly subscriptions: vscode.Disposable[] = [];
  private timer: NodeJS.Timeout | undefined;
  private asked = 0;

  constructor(private readonly server: ServerHandle) {
    this.item.name = 'SINUMERIK modal state';
    this.subscriptions.push(
      vscode.window.onDidChangeTextEditorSelection(() => this.schedule()),
      vscode.window.onDidChangeActiveTextEditor(() => this.schedule()),
      vscode.workspace.onDidChangeTextDocument(() => this.schedule()),
      server.onDidChangeClient(() => this.schedule()),
    );
    this.schedule();
  }

  private schedule(): void {
    if (this.timer) clearTimeout(this.timer);
    this.timer = setTimeout(() => void this.update(), 120);
  }

  private async update(): Promise<void> {
    const editor = vscode.window.activeTextEditor;
    const client = this.server.client;
    if (!editor || editor.document.languageId !== LANGUAGE_ID || !client) {
      this.item.hide();
      return;
    }
    const line = editor.selection.active.line;
    const ticket = ++this.asked;
    try {
      const answer = await client.sendRequest(MODAL_STATE_REQUEST, { uri: editor.document.uri.toString(), line });
      if (ticket !== this.asked) return;
      const state = parseModalState(answer);
      if (!state) {
        this.item.hide();
        return;
      }
      const status = formatModalState(state, line);
      this.item.text = status.text;
      this.item.tooltip = status.tooltip;
      this.item.show();
    } catch {
      // A server without the request, or one busy with an older document version: show nothing rather
      // than a stale state.
      if (ticket === this.asked) this.item.hide();
    }
  }

  dispose(): void {
    if (this.timer) clearTimeout(this.timer);
    this.subscriptions.forEach((subscription) => subscription.dispose());
    this.item.dispose();
  }
}
