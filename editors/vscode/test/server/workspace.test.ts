// The setting `sinumerik.cycleFolders` against the real server binary: a cycle in a folder outside
// the workspace is found by go to definition once the setting names its folder, and not before.

import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { after, before, test } from 'node:test';
import { pathToFileURL } from 'node:url';
import { serverSettings } from '../../src/core/settings';
import { definition, startServer, type TestServer } from './harness';

const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'sinumerik-workspace-'));
const workspace = path.join(scratch, 'workspace');
const cycles = path.join(scratch, 'cycles');
const mainPath = path.join(workspace, 'MAIN.MPF');
const cyclePath = path.join(cycles, 'POCKET_DEPTH.SPF');
const MAIN = 'N10 G90 G71 G17 G0 X0 Y0 Z10\nN20 POCKET_DEPTH(5)\nM30\n';

let server: TestServer;
/** Finished indexing runs, from the `end` reports of $/progress. */
let indexingRuns = 0;

before(async () => {
  fs.mkdirSync(workspace);
  fs.mkdirSync(cycles);
  fs.writeFileSync(mainPath, MAIN);
  fs.writeFileSync(cyclePath, 'PROC POCKET_DEPTH(REAL DEPTH)\nG1 Z=-DEPTH F100\nRET\n');
  server = await startServer({
    rootPath: workspace,
    register: (connection) =>
      connection.onNotification('$/progress', (params: { value?: { kind?: string } }) => {
        if (params.value?.kind === 'end') indexingRuns += 1;
      }),
  });
  await server.open(pathToFileURL(mainPath).toString(), MAIN);
});

after(async () => {
  await server?.stop();
  fs.rmSync(scratch, { recursive: true, force: true });
});

async function until<T>(what: string, probe: () => Promise<T | undefined>): Promise<T> {
  for (let attempt = 0; attempt < 200; attempt++) {
    const value = await probe();
    if (value !== undefined) return value;
    await new Promise((resolve) => setTimeout(resolve, 50));
  }
  throw new Error(`${what} did not happen within 10 s`);
}

test('a cycle outside the workspace is found once sinumerik.cycleFolders names its folder', async () => {
  const uri = pathToFileURL(mainPath).toString();
  const call = { line: 1, character: 'N20 POCK'.length };
  await until('the first indexing', async () => (indexingRuns > 0 ? true : undefined));
  assert.deepEqual(await definition(server, uri, call.line, call.character), [], 'not in the workspace');

  server.settings = serverSettings((key) => (key === 'cycleFolders' ? [cycles] : undefined));
  await server.connection.sendNotification('workspace/didChangeConfiguration', { settings: { sinumerik: server.settings } });
  const found = await until('the definition in the cycle folder', async () => {
    const locations = await definition(server, uri, call.line, call.character);
    return locations.length > 0 ? locations : undefined;
  });
  assert.deepEqual(found.map((location) => [decodeURIComponent(location.uri), location.range.start.line]), [[pathToFileURL(cyclePath).toString(), 0]]);
});
