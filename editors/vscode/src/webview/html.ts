// The toolpath page: a toolbar (2D or 3D, the plane, fit, the legend), a canvas for each view and a
// status line. The same HTML is served by the webview
// panel and by the headless-browser test, with a content security policy that allows only the
// bundled script.

export interface PageOptions {
  /** Where the bundled webview script is (a webview URI or a file URL). */
  scriptUri: string;
  /** The webview's `cspSource`, or "file:" for the test page. */
  cspSource: string;
  nonce: string;
  title: string;
}

function escapeHtml(text: string): string {
  return text.replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]!);
}

export function toolpathHtml(options: PageOptions): string {
  const csp = [
    "default-src 'none'",
    `img-src ${options.cspSource} data:`,
    `style-src ${options.cspSource} 'unsafe-inline'`,
    `script-src 'nonce-${options.nonce}'`,
  ].join('; ');
  return `<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="UTF-8">
<meta http-equiv="Content-Security-Policy" content="${csp}">
<meta name="viewport" content="width=device-width, initial-scale=1.0">
<title>${escapeHtml(options.title)}</title>
<style>
  html, body { margin: 0; padding: 0; height: 100%; overflow: hidden;
    background: var(--vscode-editor-background, #1e1e1e); color: var(--vscode-foreground, #cccccc);
    font-family: var(--vscode-font-family, sans-serif); font-size: var(--vscode-font-size, 13px); }
  body { display: flex; flex-direction: column; }
  #toolbar { display: flex; flex-wrap: wrap; gap: 4px 8px; align-items: center; padding: 4px 8px; flex: none;
    border-bottom: 1px solid var(--vscode-panel-border, #444); }
  #toolbar select, #toolbar button { font: inherit; color: inherit; background: var(--vscode-dropdown-background, #3c3c3c);
    border: 1px solid var(--vscode-dropdown-border, #555); padding: 1px 6px; }
  #toolbar button[aria-pressed="true"] { background: var(--vscode-button-background, #0e639c); color: var(--vscode-button-foreground, #ffffff); }
  .modes { display: inline-flex; }
  #toolbar select:disabled { opacity: 0.5; }
  .legend { display: inline-flex; align-items: center; gap: 4px; }
  .swatch { display: inline-block; width: 18px; height: 0; }
  .swatch.feed { border-top: 2px solid #3b8eea; } .swatch.rapid { border-top: 2px dashed #e05252; }
  .swatch.uncertain { border-top: 2px dotted #d7a600; } .swatch.cursor { border-top: 3px solid #ffd500; }
  body.vscode-light .swatch.feed { border-top-color: #0b5cad; } body.vscode-light .swatch.rapid { border-top-color: #c62828; }
  body.vscode-light .swatch.uncertain { border-top-color: #9a6b00; } body.vscode-light .swatch.cursor { border-top-color: #e07000; }
  .swatch.conditional { border-top: 2px solid #3b8eea; opacity: 0.5; }
  body.vscode-light .swatch.conditional { border-top-color: #0b5cad; }
  .swatch.inserted { border-top: 3px solid #3b8eea; } body.vscode-light .swatch.inserted { border-top-color: #0b5cad; }
  .ring { display: inline-block; width: 6px; height: 6px; border: 1.5px solid #3b8eea; border-radius: 50%; }
  body.vscode-light .ring { border-color: #0b5cad; }
  .swatch.impossible { border-top: 2px dashed #f14c4c; } body.vscode-light .swatch.impossible { border-top-color: #e51400; }
  #canvas-box { position: relative; flex: 1; min-height: 0; }
  canvas { position: absolute; inset: 0; width: 100%; height: 100%; cursor: crosshair; }
  #status { flex: none; padding: 2px 8px; border-top: 1px solid var(--vscode-panel-border, #444); line-height: 1.4em;
    height: 4.2em; overflow: hidden; }
  #status .part { display: inline-block; max-width: 100%; white-space: nowrap; overflow: hidden; text-overflow: ellipsis; vertical-align: bottom; }
  #status .part.long { display: inline; white-space: normal; }
  #tip { position: absolute; pointer-events: none; display: none; padding: 2px 6px; white-space: pre;
    background: var(--vscode-editorHoverWidget-background, #252526); border: 1px solid var(--vscode-editorHoverWidget-border, #454545); }
</style>
</head>
<body>
<div id="toolbar">
  <span class="modes" title="the moves in the working plane, or in space (drag to orbit, shift-drag or right-drag to pan, wheel to zoom)">
    <button id="mode-2d" aria-pressed="true">2D</button><button id="mode-3d" aria-pressed="false">3D</button></span>
  <label>Plane <select id="plane">
    <option value="auto">auto</option><option value="G17">G17 X/Y</option><option value="G18">G18 Z/X</option><option value="G19">G19 Y/Z</option>
  </select></label>
  <button id="fit" title="Fit the whole toolpath (F)">Fit</button>
  <span class="legend"><span class="swatch feed"></span>feed</span>
  <span class="legend"><span class="swatch rapid"></span>rapid</span>
  <span class="legend" title="after a label, jump or loop the control may take another path"><span class="swatch uncertain"></span>uncertain</span>
  <span class="legend" title="a rounding or chamfer the control inserts at a corner (RND, CHF, CHR): drawn wider"><span class="swatch inserted"></span>inserted</span>
  <span class="legend" title="a hole a drilling cycle makes along the tool axis, in the plane across that axis; click it for its line"><span class="ring"></span>hole</span>
  <span class="legend" title="a circle that cannot exist (radius too small, numbers that fit no circle): dashed with a cross, see the problem on its line"><span class="swatch impossible"></span>no circle</span>
  <span class="legend" title="faded: on a way whose condition the analysis could not decide"><span class="swatch conditional"></span>conditional</span>
  <span class="legend" title="every move of the cursor's line: each pass, and for a call every move of the called program"><span class="swatch cursor"></span>cursor</span>
</div>
<div id="canvas-box"><canvas id="canvas"></canvas><canvas id="canvas3d" style="display: none"></canvas><div id="tip"></div></div>
<div id="status">Waiting for the language server…</div>
<script nonce="${options.nonce}" src="${options.scriptUri}"></script>
</body>
</html>`;
}
