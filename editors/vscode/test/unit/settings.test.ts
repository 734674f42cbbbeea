import assert from 'node:assert/strict';
import * as path from 'node:path';
import { test } from 'node:test';
import { formatModalState, parseModalState } from '../../src/core/modalState';
import { bundledServerPath, locateServer } from '../../src/core/serverPath';
import { changeNeeds, serverSettings } from '../../src/core/settings';

const lookup = (files: string[], configured = '', searchPath = '/usr/local/bin:/opt/nc/bin') => ({
  configured, extensionPath: '/ext', platform: 'linux', arch: 'x64', searchPath, isExecutable: (f: string) => files.includes(f),
});

test('the server is the configured path, then the bundled binary, then the one on PATH', () => {
  const bundled = path.join('/ext', 'server', 'linux-x64', 'sinumerik-lsp');
  assert.equal(bundledServerPath('/ext', 'linux', 'x64'), bundled);
  assert.deepEqual(locateServer(lookup(['/my/lsp', bundled, '/opt/nc/bin/sinumerik-lsp'], '/my/lsp')), { found: true, path: '/my/lsp', source: 'setting' });
  assert.deepEqual(locateServer(lookup([bundled, '/opt/nc/bin/sinumerik-lsp'])), { found: true, path: bundled, source: 'bundled' });
  assert.deepEqual(locateServer(lookup(['/opt/nc/bin/sinumerik-lsp'])), { found: true, path: '/opt/nc/bin/sinumerik-lsp', source: 'PATH' });
  const windows = locateServer({ ...lookup([path.join('C:\\nc', 'sinumerik-lsp.exe')], '', 'C:\\nc;C:\\other'), platform: 'win32' });
  assert.equal(windows.found, true);
});

test('when no server exists the message says what was tried and how to fix it', () => {
  const missing = locateServer(lookup([]));
  assert.equal(missing.found, false);
  assert.match(!missing.found ? missing.message : '', /no bundled server for linux-x64, and it is not on PATH.*`cargo install --locked --path \.`.*Restart Language Server.*sinumerik\.server\.path/);
  const wrong = locateServer(lookup(['/opt/nc/bin/sinumerik-lsp'], '/typo/lsp'));
  assert.equal(wrong.found, false, 'a wrong configured path is not silently replaced by another binary');
  assert.match(!wrong.found ? wrong.message : '', /not found at "\/typo\/lsp"/);
});

test('settings are passed with their defaults and invalid values replaced', () => {
  const values: Record<string, unknown> = {
    inlayHints: 'all', machineKind: 'lathe', configFile: ' /m/sinumerik.toml ', cycleFolders: [' /nc/cycles ', '', 7, 'cst'], maxDiagnostics: 0, 'trace.server': 'verbose',
  };
  assert.deepEqual(serverSettings((key) => values[key]), {
    inlayHints: 'all', machineKind: 'mill', configFile: '/m/sinumerik.toml', cycleFolders: ['/nc/cycles', 'cst'], maxDiagnostics: 0, trace: { server: 'verbose' },
  });
  assert.deepEqual(serverSettings(() => undefined), { inlayHints: 'notPlain', machineKind: 'mill', configFile: '', cycleFolders: [], maxDiagnostics: 1000, trace: { server: 'off' } });
  for (const bad of [-1, 2.5, '500', null]) {
    assert.equal(serverSettings((key) => (key === 'maxDiagnostics' ? bad : undefined)).maxDiagnostics, 1000, `${bad}`);
  }
  assert.deepEqual(serverSettings((key) => (key === 'cycleFolders' ? '/nc/cycles' : undefined)).cycleFolders, [], 'not a list');
});

test('only a new server path needs a restart; other settings are sent to the running server', () => {
  assert.equal(changeNeeds((key) => key === 'sinumerik.server.path'), 'restart');
  assert.equal(changeNeeds((key) => key === 'sinumerik.machineKind'), 'notify');
  assert.equal(changeNeeds((key) => key === 'sinumerik.inlayHints'), 'notify');
  assert.equal(changeNeeds((key) => key === 'sinumerik.cycleFolders'), 'notify');
  assert.equal(changeNeeds((key) => key === 'sinumerik.maxDiagnostics'), 'notify');
  assert.equal(changeNeeds((key) => key === 'editor.fontSize'), 'nothing');
});

test('the status bar reads the modal state, with ? where the server does not know it', () => {
  const state = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null })!;
  assert.deepEqual(formatModalState(state, 4).text, 'G90 G71 G17 G1');
  const lathe = parseModalState({ motion: null, plane: 'G18', units: 'G71', distance: 'G91', diameter: 'DIAMON' })!;
  const status = formatModalState(lathe, 0);
  assert.equal(status.text, 'G91 G71 G18 ? DIAMON');
  assert.match(status.tooltip, /motion: unknown/);
  assert.match(status.tooltip, /at line 1/);
  assert.equal(parseModalState(null), null);
  assert.equal(parseModalState('G1'), null);
});

test('the status bar shows the diameter mode on a lathe only, unknown there as ?', () => {
  const mill = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: 'DIAMOF', diameterAxis: false })!;
  const millStatus = formatModalState(mill, 0);
  assert.equal(millStatus.text, 'G90 G71 G17 G1');
  assert.doesNotMatch(millStatus.tooltip, /diameter/);
  const lathe = parseModalState({ motion: 'G1', plane: 'G18', units: 'G71', distance: 'G90', diameter: 'DIAMOF', diameterAxis: true })!;
  assert.equal(formatModalState(lathe, 0).text, 'G90 G71 G18 G1 DIAMOF');
  const unknownOnLathe = parseModalState({ motion: 'G1', plane: 'G18', units: 'G71', distance: 'G90', diameter: null, diameterAxis: true })!;
  const status = formatModalState(unknownOnLathe, 0);
  assert.equal(status.text, 'G90 G71 G18 G1 ?');
  assert.match(status.tooltip, /diameter programming: unknown/);
});

test('the status bar shows the first pass of a block that runs several times, with the pass count', () => {
  const looped = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null, passes: 6 })!;
  const status = formatModalState(looped, 2);
  assert.equal(status.text, 'G90 G71 G17 G1 · pass 1 of 6');
  assert.match(status.tooltip, /runs 6 times: this is the state of its first pass/);
  const once = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null, passes: 1 })!;
  assert.equal(formatModalState(once, 2).text, 'G90 G71 G17 G1');
  const never = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null, passes: 0 })!;
  assert.equal(formatModalState(never, 2).text, 'G90 G71 G17 G1 · not run');
  const inOrder = parseModalState({ motion: 'G1', plane: 'G17', units: 'G71', distance: 'G90', diameter: null, passes: 'x' })!;
  assert.equal(inOrder.passes, null);
});
