// The commands "SINUMERIK: Renumber blocks" and "SINUMERIK: Format program": they ask what is needed,
// send the server's command, and say what happened. The server changes the document itself with
// workspace/applyEdit, which the language client applies. The decisions live in core/programCommands.

import * as vscode from 'vscode';
import { LANGUAGE_ID } from '../core/language';
import {
  blockNumberProblem,
  commandOutcome,
  failureOutcome,
  formatRequest,
  modesInPickOrder,
  parseBlockNumber,
  rememberedChoice,
  RENUMBER_CHOICE_KEY,
  renumberRequest,
  type ExecuteCommandParams,
  type Outcome,
  type RenumberChoice,
} from '../core/programCommands';
import type { ServerHandle } from './serverHandle';

/** The SINUMERIK document of the active editor, or `undefined` after telling the user why not. */
function activeProgram(): vscode.TextDocument | undefined {
  const document = vscode.window.activeTextEditor?.document;
  if (!document || document.languageId !== LANGUAGE_ID) {
    void vscode.window.showInformationMessage('Open a SINUMERIK program (.mpf, .spf) first.');
    return undefined;
  }
  return document;
}

function show(outcome: Outcome): void {
  if (outcome.kind === 'error') void vscode.window.showErrorMessage(outcome.message);
  else vscode.window.setStatusBarMessage(outcome.message, 5000);
}

async function send(server: ServerHandle, what: string, request: ExecuteCommandParams): Promise<void> {
  const client = server.client;
  if (!client) {
    void vscode.window.showErrorMessage(`${what}: the SINUMERIK language server is not running.`);
    return;
  }
  try {
    show(commandOutcome(what, await client.sendRequest('workspace/executeCommand', request)));
  } catch (error) {
    show(failureOutcome(what, error));
  }
}

async function askNumber(what: 'start' | 'step', value: number): Promise<number | undefined> {
  const text = await vscode.window.showInputBox({
    title: 'Renumber blocks',
    prompt: what === 'start' ? 'The first block number' : 'The step between block numbers',
    value: String(value),
    validateInput: (input) => blockNumberProblem(input, what),
  });
  return text === undefined ? undefined : parseBlockNumber(text);
}

/** Asks start, step and mode, starting from the last choice; `undefined` when the user cancels. */
async function askRenumberChoice(last: RenumberChoice): Promise<RenumberChoice | undefined> {
  const start = await askNumber('start', last.start);
  if (start === undefined) return undefined;
  const step = await askNumber('step', last.step);
  if (step === undefined) return undefined;
  const items = modesInPickOrder(last.mode).map((item) => ({ label: item.label, detail: item.detail, mode: item.mode }));
  const picked = await vscode.window.showQuickPick(items, { title: 'Renumber blocks', placeHolder: 'Which blocks carry a number' });
  return picked ? { start, step, mode: picked.mode } : undefined;
}

export async function renumberBlocks(context: vscode.ExtensionContext, server: ServerHandle): Promise<void> {
  const document = activeProgram();
  if (!document) return;
  const choice = await askRenumberChoice(rememberedChoice(context.globalState.get(RENUMBER_CHOICE_KEY)));
  if (!choice) return;
  // Kept before sending, so that after a refusal the next attempt starts from the same numbers.
  await context.globalState.update(RENUMBER_CHOICE_KEY, choice);
  await send(server, 'Renumbering', renumberRequest(document.uri.toString(), choice));
}

export async function formatProgram(server: ServerHandle): Promise<void> {
  const document = activeProgram();
  if (!document) return;
  await send(server, 'Formatting', formatRequest(document.uri.toString()));
}
