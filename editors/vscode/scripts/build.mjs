// Bundles the extension (Node, `vscode` external) and the toolpath page (browser) with esbuild.
import { build } from 'esbuild';

const common = { bundle: true, sourcemap: true, minify: false, logLevel: 'warning' };
await build({
  ...common,
  entryPoints: ['src/extension.ts'],
  outfile: 'dist/extension.js',
  platform: 'node',
  format: 'cjs',
  target: 'node18',
  external: ['vscode'],
});
await build({
  ...common,
  entryPoints: ['src/webview/main.ts'],
  outfile: 'dist/webview.js',
  platform: 'browser',
  format: 'iife',
  target: 'chrome114',
});
await build({
  ...common,
  entryPoints: ['test/page/harness.ts'],
  outfile: 'out/page/harness.js',
  platform: 'browser',
  format: 'iife',
  target: 'chrome114',
});
console.log('built dist/extension.js, dist/webview.js, out/page/harness.js');
