// What the status bar and the toolpath panel need of the language server: a way to send requests
// to the running client, and news when it starts or stops. LanguageServer provides it; tests fake it.

import type * as vscode from 'vscode';

export interface RequestSender {
  sendRequest(method: string, params: unknown): Promise<unknown>;
}

export interface ServerHandle {
  readonly client: RequestSender | undefined;
  readonly onDidChangeClient: vscode.Event<RequestSender | undefined>;
}
