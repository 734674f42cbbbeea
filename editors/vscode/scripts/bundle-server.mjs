// Copies the server binary into the extension (server/<platform>-<arch>/), where the extension
// looks first. The binary shipped is the repository's dist build (Cargo.toml's [profile.dist]: no
// debug information, stripped, LTO), built here with cargo; SINUMERIK_LSP_BUNDLE names another
// binary instead (the release workflow's, built for its target), and SINUMERIK_LSP_BUNDLE=none
// builds a package without a server, which uses sinumerik-lsp on PATH.
// SINUMERIK_LSP_BUNDLE_TARGET sets the folder (`linux-arm64`) when the binary is not for the
// platform this runs on.
import * as fs from 'node:fs';
import * as path from 'node:path';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const repository = path.resolve(root, '..', '..');
const target = process.env.SINUMERIK_LSP_BUNDLE_TARGET ?? `${process.platform}-${process.arch}`;
const name = target.startsWith('win32') ? 'sinumerik-lsp.exe' : 'sinumerik-lsp';
fs.rmSync(path.join(root, 'server'), { recursive: true, force: true });

let source = process.env.SINUMERIK_LSP_BUNDLE;
if (source === 'none') {
  console.log('SINUMERIK_LSP_BUNDLE=none: the package will use sinumerik-lsp on PATH');
  process.exit(0);
}
if (!source) {
  const build = spawnSync('cargo', ['build', '--profile', 'dist', '--bin', 'sinumerik-lsp'], {
    cwd: repository,
    stdio: 'inherit',
  });
  if (build.error || build.status !== 0) {
    console.error('cargo build --profile dist failed: no server to bundle (SINUMERIK_LSP_BUNDLE=none packages without one)');
    process.exit(1);
  }
  const targetDir = process.env.CARGO_TARGET_DIR ?? path.join(repository, 'target');
  source = path.resolve(repository, targetDir, 'dist', name);
}
if (!fs.existsSync(source)) {
  console.error(`no server binary at ${source}`);
  process.exit(1);
}
const bundled = path.join(root, 'server', target, name);
fs.mkdirSync(path.dirname(bundled), { recursive: true });
fs.copyFileSync(source, bundled);
fs.chmodSync(bundled, 0o755);
console.log(`bundled ${source} (${(fs.statSync(source).size / 1e6).toFixed(1)} MB) as ${path.relative(root, bundled)}`);
