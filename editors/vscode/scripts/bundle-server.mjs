// Copies the server binary into the extension (server/<platform>-<arch>/), where the extension
// looks first. The binary is SINUMERIK_LSP_BIN or the repository's target/release/sinumerik-lsp;
// without one the package is built without a bundled server and uses sinumerik-lsp on PATH.
import * as fs from 'node:fs';
import * as path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const name = process.platform === 'win32' ? 'sinumerik-lsp.exe' : 'sinumerik-lsp';
const source = process.env.SINUMERIK_LSP_BIN ?? path.resolve(root, '..', '..', 'target', 'release', name);
const target = path.join(root, 'server', `${process.platform}-${process.arch}`, name);
fs.rmSync(path.join(root, 'server'), { recursive: true, force: true });
if (fs.existsSync(source)) {
  fs.mkdirSync(path.dirname(target), { recursive: true });
  fs.copyFileSync(source, target);
  fs.chmodSync(target, 0o755);
  console.log(`bundled ${source} as ${path.relative(root, target)}`);
} else {
  console.log(`no server binary at ${source}: the package will use sinumerik-lsp on PATH`);
}
