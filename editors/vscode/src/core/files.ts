// The files of a toolpath: the server names the file of a called program by its path or its URI;
// the extension keeps one key per file, a URI, so that the page and the editor speak of a file in
// the same words. Pure functions, used in the extension host and in the page.

/** A URI scheme of two or more characters: `C:` is a Windows drive, not a scheme. */
const URI_SCHEME = /^[a-zA-Z][a-zA-Z0-9+.-]+:/;

/** The URI of a file the server named: a URI stays as it is, an absolute path becomes a `file:` URI,
 * and a relative path is taken from the folder of `base` (the previewed file's URI). */
export function fileUri(name: string, base: string): string {
  if (URI_SCHEME.test(name)) return name;
  let path = name.replace(/\\/g, '/');
  if (/^[a-zA-Z]:/.test(path)) path = `/${path}`;
  // Each part is encoded on its own, except a drive's colon.
  const encoded = path
    .split('/')
    .map((part, index) => (index === 1 && /^[a-zA-Z]:$/.test(part) ? part : encodeURIComponent(part)))
    .join('/');
  try {
    return new URL(encoded, path.startsWith('/') ? 'file:///' : base).href;
  } catch {
    return name;
  }
}

/** The name of a file to show: the last part of its URI or path, decoded. */
export function fileLabel(uriOrPath: string): string {
  const last = uriOrPath.replace(/[?#].*$/, '').split(/[/\\]/).filter((part) => part !== '').pop() ?? uriOrPath;
  try {
    return decodeURIComponent(last);
  } catch {
    return last;
  }
}
