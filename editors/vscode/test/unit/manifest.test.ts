import assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { test } from 'node:test';
import { FORMAT_COMMAND, RENUMBER_COMMAND } from '../../src/core/programCommands';
import { serverSettings } from '../../src/core/settings';
import { DECLARED_TOKEN_MODIFIERS, DECLARED_TOKEN_TYPES, KNOWN_TOKEN_MODIFIERS, KNOWN_TOKEN_TYPES, STANDARD_TOKEN_MODIFIERS, STANDARD_TOKEN_TYPES, TOKEN_SCOPES } from './semanticLegend';
import { EXTENSION_ROOT } from './fixtures';

const read = (file: string) => JSON.parse(fs.readFileSync(path.join(EXTENSION_ROOT, file), 'utf8'));
const manifest = read('package.json');

test('the language, its files and its grammar are contributed consistently', () => {
  const [language] = manifest.contributes.languages;
  assert.equal(language.id, 'sinumerik');
  assert.deepEqual(language.extensions, ['.mpf', '.spf', '.MPF', '.SPF']);
  const [grammar] = manifest.contributes.grammars;
  assert.equal(grammar.language, 'sinumerik');
  assert.equal(read(grammar.path).scopeName, grammar.scopeName);
  for (const file of [manifest.icon, language.icon.light, language.configuration]) {
    assert.ok(fs.existsSync(path.join(EXTENSION_ROOT, file)), `${file} exists`);
  }
});

test('every contributed command is registered by the extension, and the other way round', () => {
  const source = fs.readFileSync(path.join(EXTENSION_ROOT, 'src', 'extension.ts'), 'utf8');
  const registered = [...source.matchAll(/registerCommand\('([^']+)'/g)].map((m) => m[1]).sort();
  const contributed = manifest.contributes.commands.map((c: { command: string }) => c.command).sort();
  assert.deepEqual(registered, contributed);
  assert.ok(contributed.includes('sinumerik.showToolpath'));
  assert.equal(manifest.contributes.commands.find((c: { command: string }) => c.command === 'sinumerik.showToolpath').title, 'Show Toolpath');
});

test('renumbering and formatting are in the palette and the context menu of SINUMERIK programs', () => {
  const commands = ['sinumerik.renumberBlocks', 'sinumerik.formatProgram'];
  const titles = commands.map((id) => manifest.contributes.commands.find((c: { command: string }) => c.command === id)?.title);
  assert.deepEqual(titles, ['Renumber blocks', 'Format program']);
  for (const menu of ['commandPalette', 'editor/context']) {
    for (const id of commands) {
      const entry = manifest.contributes.menus[menu].find((item: { command: string }) => item.command === id);
      assert.equal(entry?.when, 'editorLangId == sinumerik', `${id} in ${menu}`);
    }
  }
  // The language client registers the server's command ids itself; a second registration would fail.
  const contributed = manifest.contributes.commands.map((c: { command: string }) => c.command);
  assert.ok(!contributed.includes(RENUMBER_COMMAND) && !contributed.includes(FORMAT_COMMAND));
});

test('the settings the server receives are the ones VS Code offers, with the same values', () => {
  const properties = manifest.contributes.configuration.properties;
  for (const key of ['inlayHints', 'machineKind', 'trace.server']) {
    const property = properties[`sinumerik.${key}`];
    assert.ok(property, key);
    for (const value of property.enum) {
      const settings = serverSettings((k) => (k === key ? value : undefined));
      const read = key === 'trace.server' ? settings.trace.server : settings[key as 'inlayHints' | 'machineKind'];
      assert.equal(read, value, `${key} = ${value} reaches the server`);
    }
    const defaults = serverSettings(() => undefined);
    const fallback = key === 'trace.server' ? defaults.trace.server : defaults[key as 'inlayHints' | 'machineKind'];
    assert.equal(property.default, fallback, `${key}: same default`);
  }
  assert.ok(properties['sinumerik.configFile'] && properties['sinumerik.server.path']);
  const folders = properties['sinumerik.cycleFolders'];
  assert.deepEqual([folders.type, folders.items.type, folders.default], ['array', 'string', []]);
  assert.deepEqual(serverSettings((k) => (k === 'cycleFolders' ? folders.default : undefined)).cycleFolders, []);
  const limit = properties['sinumerik.maxDiagnostics'];
  assert.deepEqual([limit.type, limit.minimum, limit.default], ['integer', 0, serverSettings(() => undefined).maxDiagnostics]);
});

test('comments, folding and indentation follow the control structures', () => {
  const config = read('language-configuration.json');
  assert.equal(config.comments.lineComment, ';');
  const start = new RegExp(config.folding.markers.start);
  const end = new RegExp(config.folding.markers.end);
  const indent = new RegExp(config.indentationRules.increaseIndentPattern);
  const dedent = new RegExp(config.indentationRules.decreaseIndentPattern);
  const opens = ['IF R1 > 0', 'N10 if (R1==1) AND (R2==2)', 'WHILE $AA_IM[X] < 10', '  FOR R1=1 TO 10', 'REPEAT', 'N20 LOOP ; forever', '/1 N30 IF R2'];
  const notOpens = ['IF R1 > 0 GOTOF END_LABEL', 'REPEAT START END P=3', 'IFR1=3', 'N10 G0 X10', '; IF in a comment', 'CASE R1 OF 1 GOTOF A DEFAULT GOTOF B'];
  const closes = ['ENDIF', 'N40 endwhile', '  ENDFOR', 'UNTIL R1 > 5', 'ENDLOOP ; done'];
  for (const line of opens) assert.ok(start.test(line) && indent.test(line), `opens: ${line}`);
  for (const line of notOpens) assert.ok(!start.test(line) && !indent.test(line), `does not open: ${line}`);
  for (const line of closes) assert.ok(end.test(line) && dedent.test(line), `closes: ${line}`);
  assert.ok(indent.test('ELSE') && dedent.test('N50 ELSE'), 'ELSE closes and opens');
  assert.ok(!end.test('ENDIFX=1') && !end.test('N10 X10'));
});

function grammarScopes(): Set<string> {
  const names = new Set<string>();
  const walk = (value: unknown): void => {
    if (Array.isArray(value)) value.forEach(walk);
    else if (typeof value === 'object' && value !== null) {
      for (const [key, inner] of Object.entries(value)) {
        if (key === 'name' && typeof inner === 'string') names.add(inner);
        else walk(inner);
      }
    }
  };
  walk(read(manifest.contributes.grammars[0].path));
  return names;
}

test('semantic token kinds are declared and mapped to the scopes the grammar gives the same words', () => {
  for (const [selector, scopes] of Object.entries(TOKEN_SCOPES)) {
    const [type, ...modifiers] = selector.split('.');
    assert.ok(KNOWN_TOKEN_TYPES.has(type), `${selector}: the type is standard or declared`);
    for (const modifier of modifiers) assert.ok(KNOWN_TOKEN_MODIFIERS.has(modifier), `${selector}: the modifier is standard or declared`);
    assert.ok(scopes.length > 0 && scopes.every((scope) => /^(comment|constant|entity|invalid|keyword|storage|string|support|variable)\..*\.sinumerik$/.test(scope)), `${selector}: ${scopes}`);
  }
  for (const type of DECLARED_TOKEN_TYPES) {
    assert.ok(!STANDARD_TOKEN_TYPES.has(type.id), `${type.id} is not declared twice`);
    assert.ok(TOKEN_SCOPES[type.id], `${type.id} has a scope`);
    if (type.superType) assert.ok(STANDARD_TOKEN_TYPES.has(type.superType), `${type.id}: super type ${type.superType}`);
  }
  for (const modifier of DECLARED_TOKEN_MODIFIERS) assert.ok(!STANDARD_TOKEN_MODIFIERS.has(modifier), modifier);
  // The words the grammar colours too get its scopes, so that a theme shows them alike before the
  // server answers and after.
  const grammar = grammarScopes();
  for (const type of ['comment', 'string', 'number', 'gcode', 'axis', 'address', 'modifier', 'variable', 'rParameter', 'systemVariable', 'label', 'blockNumber', 'function']) {
    assert.ok(grammar.has(TOKEN_SCOPES[type]?.[0]), `${type}: ${TOKEN_SCOPES[type]} is a scope of the grammar`);
  }
});
