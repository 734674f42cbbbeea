// Test helpers for semantic highlighting: the token types and modifiers VS Code knows without a
// declaration (its standard legend), and what package.json declares and maps to TextMate scopes.

import * as fs from 'node:fs';
import * as path from 'node:path';
import { EXTENSION_ROOT } from './fixtures';

export const STANDARD_TOKEN_TYPES: ReadonlySet<string> = new Set([
  'namespace', 'class', 'enum', 'interface', 'struct', 'typeParameter', 'type', 'parameter', 'variable', 'property',
  'enumMember', 'decorator', 'event', 'function', 'method', 'macro', 'label', 'comment', 'string', 'keyword', 'number',
  'regexp', 'operator',
]);

export const STANDARD_TOKEN_MODIFIERS: ReadonlySet<string> = new Set([
  'declaration', 'definition', 'readonly', 'static', 'deprecated', 'abstract', 'async', 'modification', 'documentation',
  'defaultLibrary',
]);

interface Manifest {
  contributes: {
    semanticTokenTypes: { id: string; superType?: string }[];
    semanticTokenModifiers: { id: string }[];
    semanticTokenScopes: { language: string; scopes: Record<string, string[]> }[];
  };
}

const manifest: Manifest = JSON.parse(fs.readFileSync(path.join(EXTENSION_ROOT, 'package.json'), 'utf8'));

/** The types VS Code knows for SINUMERIK documents: its standard ones and the declared ones. */
export const KNOWN_TOKEN_TYPES = new Set([...STANDARD_TOKEN_TYPES, ...manifest.contributes.semanticTokenTypes.map((type) => type.id)]);
export const KNOWN_TOKEN_MODIFIERS = new Set([...STANDARD_TOKEN_MODIFIERS, ...manifest.contributes.semanticTokenModifiers.map((modifier) => modifier.id)]);
export const DECLARED_TOKEN_TYPES = manifest.contributes.semanticTokenTypes;
export const DECLARED_TOKEN_MODIFIERS = manifest.contributes.semanticTokenModifiers.map((modifier) => modifier.id);

/** The TextMate scopes of the language's semantic token selectors (`type` or `type.modifier`). */
export const TOKEN_SCOPES: Record<string, string[]> = manifest.contributes.semanticTokenScopes.find((entry) => entry.language === 'sinumerik')?.scopes ?? {};

/** The scope VS Code gives a token: its most specific selector (a modifier's), else its type's. */
export function scopeOf(type: string, modifiers: string[]): string | undefined {
  for (const modifier of modifiers) {
    const scopes = TOKEN_SCOPES[`${type}.${modifier}`];
    if (scopes) return scopes[0];
  }
  return TOKEN_SCOPES[type]?.[0];
}
