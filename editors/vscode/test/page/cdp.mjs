// A small Chrome DevTools Protocol client over --remote-debugging-pipe: enough to load a page, run
// script in it, send pointer events and take a screenshot, without downloading a browser.
import { spawn } from 'node:child_process';

export function findChromium() {
  return process.env.CHROMIUM_BIN || 'chromium';
}

/** `args`: more Chromium switches (e.g. `--disable-webgl`). */
export async function launch({ width = 900, height = 640, args = [] } = {}) {
  const browser = spawn(
    findChromium(),
    [
      '--headless=new', '--remote-debugging-pipe', '--no-sandbox', '--disable-gpu', '--no-first-run',
      '--disable-extensions', '--hide-scrollbars', '--mute-audio', '--allow-file-access-from-files',
      `--window-size=${width},${height}`, ...args, 'about:blank',
    ],
    { stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'] },
  );
  let stderr = '';
  browser.stderr.on('data', (chunk) => (stderr += chunk));
  const toBrowser = browser.stdio[3];
  const fromBrowser = browser.stdio[4];
  let nextId = 1;
  const pending = new Map();
  const listeners = [];
  let buffer = Buffer.alloc(0);
  fromBrowser.on('data', (chunk) => {
    buffer = Buffer.concat([buffer, chunk]);
    let end;
    while ((end = buffer.indexOf(0)) >= 0) {
      const message = JSON.parse(buffer.subarray(0, end).toString('utf8'));
      buffer = buffer.subarray(end + 1);
      if (message.id && pending.has(message.id)) {
        const { resolve, reject, method } = pending.get(message.id);
        pending.delete(message.id);
        if (message.error) reject(new Error(`${method}: ${message.error.message}`));
        else resolve(message.result);
      } else if (message.method) {
        for (const listener of listeners) listener(message);
      }
    }
  });
  const exited = new Promise((resolve) => browser.on('exit', resolve));
  browser.on('error', (error) => {
    const reason = error.code === 'ENOENT'
      ? new Error(`${findChromium()} was not found: install Debian's chromium (apt-get install chromium) or set CHROMIUM_BIN`)
      : error;
    for (const { reject } of pending.values()) reject(reason);
  });
  const send = (method, params = {}, sessionId) =>
    new Promise((resolve, reject) => {
      const id = nextId++;
      pending.set(id, { resolve, reject, method });
      toBrowser.write(JSON.stringify({ id, method, params, ...(sessionId ? { sessionId } : {}) }) + '\0');
    });
  const { targetInfos } = await send('Target.getTargets');
  const page = targetInfos.find((target) => target.type === 'page');
  const { sessionId } = await send('Target.attachToTarget', { targetId: page.targetId, flatten: true });
  const call = (method, params) => send(method, params, sessionId);
  const waitFor = (method) =>
    new Promise((resolve) => {
      const listener = (message) => {
        if (message.method === method && message.sessionId === sessionId) {
          listeners.splice(listeners.indexOf(listener), 1);
          resolve(message.params);
        }
      };
      listeners.push(listener);
    });
  const consoleMessages = [];
  listeners.push((message) => {
    if (message.method === 'Runtime.consoleAPICalled') consoleMessages.push(message.params.args.map((a) => a.value).join(' '));
    if (message.method === 'Runtime.exceptionThrown') consoleMessages.push(`exception: ${message.params.exceptionDetails.exception?.description}`);
  });
  await call('Page.enable');
  await call('Runtime.enable');
  await call('Emulation.setDeviceMetricsOverride', { width, height, deviceScaleFactor: 1, mobile: false });
  return {
    consoleMessages,
    get stderr() { return stderr; },
    async goto(url) {
      const loaded = waitFor('Page.loadEventFired');
      await call('Page.navigate', { url });
      await loaded;
    },
    async evaluate(expression) {
      const result = await call('Runtime.evaluate', { expression, awaitPromise: true, returnByValue: true });
      if (result.exceptionDetails) throw new Error(`in page: ${result.exceptionDetails.exception?.description ?? result.exceptionDetails.text}`);
      return result.result.value;
    },
    /** A left-button press, move with the button held, or release; `modifiers` as CDP has them (8: shift). */
    async mouse(type, x, y, modifiers = 0) {
      await call('Input.dispatchMouseEvent', { type, x, y, modifiers, button: 'left', clickCount: 1, buttons: type === 'mouseReleased' ? 0 : 1 });
    },
    async key(key) {
      await call('Input.dispatchKeyEvent', { type: 'keyDown', key, text: key });
      await call('Input.dispatchKeyEvent', { type: 'keyUp', key });
    },
    /** A move without a button, as when hovering. */
    async hover(x, y) {
      await call('Input.dispatchMouseEvent', { type: 'mouseMoved', x, y, button: 'none', buttons: 0 });
    },
    async wheel(x, y, deltaY) {
      await call('Input.dispatchMouseEvent', { type: 'mouseWheel', x, y, deltaX: 0, deltaY });
    },
    async screenshot() {
      const { data } = await call('Page.captureScreenshot', { format: 'png' });
      return Buffer.from(data, 'base64');
    },
    async close() {
      try {
        await send('Browser.close');
      } catch {
        browser.kill();
      }
      await exited;
    },
  };
}
