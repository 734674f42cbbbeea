// The extension's entry point: a thin shell that wires the language client, the status bar and the
// toolpath panel to VS Code. Everything that decides something lives in core/ and is unit-tested.

import * as vscode from 'vscode';
import { LanguageServer } from './vscode/languageServer';
import { formatProgram, renumberBlocks } from './vscode/programCommands';
import { ModalStatusBar } from './vscode/statusBar';
import { ToolpathPanel } from './vscode/toolpathPanel';

let server: LanguageServer | undefined;

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  const output = vscode.window.createOutputChannel('SINUMERIK Language Server');
  server = new LanguageServer(context, output);
  const statusBar = new ModalStatusBar(server);
  context.subscriptions.push(
    output,
    server,
    statusBar,
    vscode.commands.registerCommand('sinumerik.showToolpath', () => ToolpathPanel.show(context, server!)),
    vscode.commands.registerCommand('sinumerik.restartServer', () => server!.restart()),
    // Ids of their own: the language client registers the server's `sinumerik.renumber` and
    // `sinumerik.format` as VS Code commands itself.
    vscode.commands.registerCommand('sinumerik.renumberBlocks', () => renumberBlocks(context, server!)),
    vscode.commands.registerCommand('sinumerik.formatProgram', () => formatProgram(server!)),
  );
  await server.start();
}

export async function deactivate(): Promise<void> {
  await server?.stop();
}
