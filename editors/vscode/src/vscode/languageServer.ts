// Starting, restarting and configuring the language client; the decisions (which binary, which
// settings, whether a change needs a restart) are made by the pure modules in core/.

import * as fs from 'node:fs';
import * as vscode from 'vscode';
import { LanguageClient, type LanguageClientOptions, type ServerOptions } from 'vscode-languageclient/node';
import { locateServer } from '../core/serverPath';
import { LANGUAGE_ID } from '../core/language';
import { changeNeeds, serverSettings, type ServerSettings } from '../core/settings';
import type { ServerHandle } from './serverHandle';


function isExecutable(file: string): boolean {
  try {
    fs.accessSync(file, fs.constants.X_OK);
    return fs.statSync(file).isFile();
  } catch {
    return false;
  }
}

function currentSettings(): ServerSettings {
  const section = vscode.workspace.getConfiguration('sinumerik');
  return serverSettings((key) => section.get(key));
}

export class LanguageServer implements vscode.Disposable, ServerHandle {
  client: LanguageClient | undefined;
  private readonly changed = new vscode.EventEmitter<LanguageClient | undefined>();
  /** Fires when a client started or stopped. */
  readonly onDidChangeClient = this.changed.event;
  private readonly watcher: vscode.Disposable;

  constructor(private readonly context: vscode.ExtensionContext, private readonly output: vscode.OutputChannel) {
    this.watcher = vscode.workspace.onDidChangeConfiguration((event) => {
      const needs = changeNeeds((key) => event.affectsConfiguration(key));
      if (needs === 'restart') void this.restart();
      else if (needs === 'notify' && this.client) {
        // The server re-reads its section; settings take effect without a restart.
        void this.client.sendNotification('workspace/didChangeConfiguration', { settings: { sinumerik: currentSettings() } });
      }
    });
  }

  async start(): Promise<void> {
    const location = locateServer({
      configured: vscode.workspace.getConfiguration('sinumerik').get<string>('server.path') ?? '',
      extensionPath: this.context.extensionPath,
      platform: process.platform,
      arch: process.arch,
      searchPath: process.env.PATH ?? '',
      isExecutable,
    });
    if (!location.found) {
      this.output.appendLine(location.message);
      const choice = await vscode.window.showErrorMessage(location.message, 'Open Settings');
      if (choice === 'Open Settings') {
        await vscode.commands.executeCommand('workbench.action.openSettings', 'sinumerik.server.path');
      }
      return;
    }
    this.output.appendLine(`Starting ${location.path} (${location.source})`);
    const serverOptions: ServerOptions = { command: location.path, args: ['serve'] };
    const clientOptions: LanguageClientOptions = {
      documentSelector: [
        { scheme: 'file', language: LANGUAGE_ID },
        { scheme: 'untitled', language: LANGUAGE_ID },
      ],
      initializationOptions: currentSettings(),
      outputChannel: this.output,
    };
    const client = new LanguageClient(LANGUAGE_ID, 'SINUMERIK Language Server', serverOptions, clientOptions);
    try {
      await client.start();
      this.client = client;
      this.changed.fire(client);
    } catch (error) {
      const message = `The SINUMERIK language server at ${location.path} did not start: ${String(error)}`;
      this.output.appendLine(message);
      void vscode.window.showErrorMessage(message, 'Open Settings').then((choice) => {
        if (choice) void vscode.commands.executeCommand('workbench.action.openSettings', 'sinumerik.server.path');
      });
    }
  }

  async restart(): Promise<void> {
    await this.stop();
    await this.start();
  }

  async stop(): Promise<void> {
    const client = this.client;
    this.client = undefined;
    this.changed.fire(undefined);
    if (client) await client.stop().catch(() => undefined);
  }

  dispose(): void {
    this.watcher.dispose();
    this.changed.dispose();
    void this.stop();
  }
}
