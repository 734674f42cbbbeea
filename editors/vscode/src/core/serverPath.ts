// Where the language server binary is: the configured path, else the binary shipped inside the
// extension for this platform, else `sinumerik-lsp` on PATH. When none exists the user gets a
// message that says what was tried and how to fix it.

import * as path from 'node:path';

export interface ServerLookup {
  /** `sinumerik.server.path`, empty when not set. */
  configured: string;
  extensionPath: string;
  platform: string;
  arch: string;
  /** The PATH variable. */
  searchPath: string;
  /** Whether an executable file exists at this path. */
  isExecutable: (file: string) => boolean;
}

export type ServerLocation =
  | { found: true; path: string; source: 'setting' | 'bundled' | 'PATH' }
  | { found: false; message: string };

export const SERVER_NAME = 'sinumerik-lsp';

export function executableName(platform: string): string {
  return platform === 'win32' ? `${SERVER_NAME}.exe` : SERVER_NAME;
}

/** The folder name of a bundled binary, as `npm run bundle-server` writes it: `server/linux-x64/`. */
export function bundledServerPath(extensionPath: string, platform: string, arch: string): string {
  return path.join(extensionPath, 'server', `${platform}-${arch}`, executableName(platform));
}

export function locateServer(lookup: ServerLookup): ServerLocation {
  const configured = lookup.configured.trim();
  if (configured) {
    if (lookup.isExecutable(configured)) return { found: true, path: configured, source: 'setting' };
    return {
      found: false,
      message:
        `The SINUMERIK language server was not found at "${configured}" (setting sinumerik.server.path). ` +
        'Correct the path, or clear the setting to use the bundled server or sinumerik-lsp on PATH.',
    };
  }
  const bundled = bundledServerPath(lookup.extensionPath, lookup.platform, lookup.arch);
  if (lookup.isExecutable(bundled)) return { found: true, path: bundled, source: 'bundled' };
  const separator = lookup.platform === 'win32' ? ';' : ':';
  for (const folder of lookup.searchPath.split(separator)) {
    if (!folder) continue;
    const candidate = path.join(folder, executableName(lookup.platform));
    if (lookup.isExecutable(candidate)) return { found: true, path: candidate, source: 'PATH' };
  }
  return {
    found: false,
    message:
      `The SINUMERIK language server (${executableName(lookup.platform)}) was not found: this extension has no ` +
      `bundled server for ${lookup.platform}-${lookup.arch}, and it is not on PATH. To install it, run ` +
      '`cargo install --locked --path .` in a checkout of the sinumerik-lsp repository (Rust 1.85 or newer; ' +
      'it puts sinumerik-lsp in ~/.cargo/bin, on PATH), then run "SINUMERIK: Restart Language Server"; ' +
      'or set sinumerik.server.path to a sinumerik-lsp binary you have.',
  };
}
