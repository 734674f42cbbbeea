// The settings the extension reads and what the server receives: initializationOptions at start and
// the `sinumerik` section on workspace/configuration and didChangeConfiguration.

export type InlayHints = 'off' | 'notPlain' | 'all';
export type MachineKind = 'mill' | 'turn';
export type Trace = 'off' | 'messages' | 'verbose';

export interface ServerSettings {
  inlayHints: InlayHints;
  machineKind: MachineKind;
  /** Empty: the server looks for sinumerik.toml next to each program. */
  configFile: string;
  /** Folders of cycles and subprograms outside the workspace that the server indexes too. */
  cycleFolders: string[];
  /** Diagnostics published per document; 0: all of them. */
  maxDiagnostics: number;
  trace: { server: Trace };
}

/** Reads one setting of the `sinumerik` section. */
export type SettingReader = (key: string) => unknown;

function oneOf<T extends string>(value: unknown, allowed: readonly T[], fallback: T): T {
  return typeof value === 'string' && (allowed as readonly string[]).includes(value) ? (value as T) : fallback;
}

/** VS Code shows at most this many problems of one file and drops the rest itself, errors first. */
export const VSCODE_PROBLEMS_PER_FILE = 1000;

function wholeNumber(value: unknown, fallback: number): number {
  return typeof value === 'number' && Number.isInteger(value) && value >= 0 ? value : fallback;
}

export function serverSettings(read: SettingReader): ServerSettings {
  const configFile = read('configFile');
  const cycleFolders = read('cycleFolders');
  return {
    inlayHints: oneOf(read('inlayHints'), ['off', 'notPlain', 'all'] as const, 'notPlain'),
    machineKind: oneOf(read('machineKind'), ['mill', 'turn'] as const, 'mill'),
    configFile: typeof configFile === 'string' ? configFile.trim() : '',
    cycleFolders: Array.isArray(cycleFolders)
      ? cycleFolders.filter((folder): folder is string => typeof folder === 'string').map((folder) => folder.trim()).filter((folder) => folder !== '')
      : [],
    maxDiagnostics: wholeNumber(read('maxDiagnostics'), VSCODE_PROBLEMS_PER_FILE),
    trace: { server: oneOf(read('trace.server'), ['off', 'messages', 'verbose'] as const, 'off') },
  };
}

/** What a change of settings needs: a new server process (another binary) or just a notification. */
export function changeNeeds(affects: (key: string) => boolean): 'restart' | 'notify' | 'nothing' {
  if (affects('sinumerik.server.path')) return 'restart';
  if (['inlayHints', 'machineKind', 'configFile', 'cycleFolders', 'maxDiagnostics', 'trace.server'].some((key) => affects(`sinumerik.${key}`))) {
    return 'notify';
  }
  return 'nothing';
}
