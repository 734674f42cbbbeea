"""What test_vscode.py reads and does in the VS Code workbench: the editor's lines, hovers and inlay hints,
the Problems panel, the status bar and the toolpath webview. Selectors are those of VS Code 1.96."""
import re
import time

LINES = ".editor-instance .view-lines .view-line"


def wait_for(fn, timeout, what):
    """The first truthy value of fn() within timeout seconds; a TimeoutError naming `what` otherwise."""
    deadline = time.time() + timeout
    last_error = None
    while time.time() < deadline:
        try:
            value = fn()
            if value:
                return value
        except Exception as error:  # noqa: BLE001 - the page may be between states; try again
            last_error = error
        time.sleep(0.2)
    raise TimeoutError(f"waited {timeout}s for {what}" + (f" (last error: {last_error})" if last_error else ""))


def status_item(page, item_id):
    """The text of the status bar item with this id, '' when it is absent or hidden."""
    return page.evaluate(
        """id => { const e = document.getElementById(id); return e && e.offsetParent !== null ? e.innerText.trim() : ''; }""",
        item_id,
    )


def problems(page):
    """The Problems panel's rows of single problems, as VS Code reads them to a screen reader."""
    if not page.query_selector(".markers-panel"):
        command(page, "View: Focus Problems")
        page.wait_for_selector(".markers-panel", timeout=10000)
    return page.eval_on_selector_all(
        ".markers-panel .monaco-list-row",
        "rows => rows.map(r => r.getAttribute('aria-label') || '')",
    )


def problem_matches(row, severity, message, line):
    """Whether a Problems row is the problem of `severity` with `message` on `line` (1-based)."""
    return row.startswith(severity) and message in row and re.search(rf" at line {line} and character ", row) is not None


def command(page, name):
    """Runs a command by its title from the command palette."""
    page.keyboard.press("Control+Shift+P")
    box = page.wait_for_selector(".quick-input-widget .quick-input-box input", state="visible", timeout=10000)
    box.fill(">" + name)
    page.wait_for_selector(f".quick-input-list .monaco-list-row[aria-label*='{name}']", timeout=10000)
    page.keyboard.press("Enter")


class Editor:
    """The active text editor."""

    def __init__(self, page):
        self.page = page

    def open(self, name):
        page = self.page
        page.wait_for_selector(".monaco-workbench .explorer-folders-view .monaco-list-row", timeout=90000)
        page.keyboard.press("Control+P")
        box = page.wait_for_selector(".quick-input-widget .quick-input-box input", state="visible", timeout=10000)
        box.fill(name)
        page.wait_for_selector(f".quick-input-list .monaco-list-row[aria-label*='{name}']", timeout=10000)
        page.keyboard.press("Enter")
        page.wait_for_selector(LINES, timeout=20000)
        wait_for(lambda: status_item(page, "status.editor.mode") == "SINUMERIK NC", 20, "the language mode")

    def lines(self):
        """The visible lines by number (1-based), with the text of inlay hints."""
        return self.page.evaluate(
            """() => {
              const numbers = [...document.querySelectorAll('.editor-instance .margin-view-overlays .line-numbers')];
              const lines = [...document.querySelectorAll('.editor-instance .view-lines .view-line')];
              const at = (el) => Math.round(el.getBoundingClientRect().top);
              const byTop = new Map(numbers.map(n => [at(n), Number(n.textContent)]));
              const out = {};
              for (const line of lines) {
                const n = byTop.get(at(line));
                if (n) out[n] = line.textContent.replace(/\\u00a0/g, ' ');
              }
              return out;
            }"""
        )

    def inlay_hints(self):
        """The inlay hints' text by line (1-based), the hints of a line joined with spaces."""
        return {
            int(line): text
            for line, text in self.page.evaluate(
                """() => {
                  const numbers = [...document.querySelectorAll('.editor-instance .margin-view-overlays .line-numbers')];
                  const at = (el) => Math.round(el.getBoundingClientRect().top);
                  const byTop = new Map(numbers.map(n => [at(n), Number(n.textContent)]));
                  const out = {};
                  for (const line of document.querySelectorAll('.editor-instance .view-lines .view-line')) {
                    const hints = [...line.querySelectorAll('span[class*="dyn-rule"], span[class*="inlay"]')]
                      .map(s => s.textContent.replace(/\\u00a0/g, ' ').trim()).filter(t => t);
                    const n = byTop.get(at(line));
                    if (n && hints.length) out[n] = hints.join(' ');
                  }
                  return out;
                }"""
            ).items()
        }

    def cursor_line(self):
        """The cursor's line from the status bar's `Ln 6, Col 1`; None when it is not shown."""
        match = re.search(r"Ln (\d+)", status_item(self.page, "status.editor.selection"))
        return int(match.group(1)) if match else None

    def _rect(self, line, needle, offset):
        """The screen rectangle of character `offset` of `needle` in the given line (1-based)."""
        return self.page.evaluate(
            """([number, needle, offset]) => {
              const numbers = [...document.querySelectorAll('.editor-instance .margin-view-overlays .line-numbers')];
              const label = numbers.find(n => Number(n.textContent) === number);
              if (!label) return null;
              const top = Math.round(label.getBoundingClientRect().top);
              const line = [...document.querySelectorAll('.editor-instance .view-lines .view-line')]
                .find(l => Math.round(l.getBoundingClientRect().top) === top);
              if (!line) return null;
              const walker = document.createTreeWalker(line, NodeFilter.SHOW_TEXT);
              const nodes = [];
              for (let node; (node = walker.nextNode());) {
                // The text of inlay hints is not part of the program's line.
                if (!node.parentElement.closest('span[class*="dyn-rule"]')) nodes.push(node);
              }
              const text = nodes.map(n => n.textContent).join('').replace(/\\u00a0/g, ' ');
              let target = text.indexOf(needle);
              if (target < 0) return null;
              target += offset;
              for (const node of nodes) {
                if (target < node.textContent.length) {
                  const range = document.createRange();
                  range.setStart(node, target);
                  range.setEnd(node, target + 1);
                  const r = range.getBoundingClientRect();
                  return {x: r.x + r.width / 2, y: r.y + r.height / 2};
                }
                target -= node.textContent.length;
              }
              return null;
            }""",
            [line, needle, offset],
        )

    def hover(self, line, needle, offset, expected):
        """The text of the hover over `needle` on `line`, once it contains `expected`."""
        page = self.page
        page.mouse.move(5, 5)
        point = wait_for(lambda: self._rect(line, needle, offset), 10, f"{needle!r} on line {line}")
        page.mouse.move(point["x"], point["y"])

        seen = []

        def shown():
            texts = page.eval_on_selector_all(
                ".monaco-hover:not(.hidden) .hover-contents", "els => els.map(e => e.innerText).join('\\n')"
            )
            seen.append(texts)
            return texts if expected in texts else None

        try:
            return wait_for(shown, 15, f"a hover with {expected!r}")
        except TimeoutError as error:
            raise TimeoutError(f"{error}; the last hover said {seen[-1] if seen else None!r}") from None
        finally:
            page.mouse.move(5, 5)

    def click_line(self, line):
        """Puts the cursor at the start of a line (1-based) with the mouse."""
        point = wait_for(lambda: self._rect(line, f"N{(line - 1) * 10}", 0), 10, f"line {line}")
        self.page.mouse.click(point["x"] - 3, point["y"])
        wait_for(lambda: self.cursor_line() == line, 10, f"the cursor on line {line}")

    def replace_line(self, line, text):
        """Replaces a line's text by typing, as a user would."""
        self.click_line(line)
        page = self.page
        page.keyboard.press("Home")
        page.keyboard.press("Shift+End")
        page.keyboard.type(text, delay=20)
        # Typing may have opened the completion list, which would cover the line and hold back hovers.
        page.keyboard.press("Escape")


class ToolpathView:
    """The toolpath webview of the extension: a canvas in a frame of the workbench."""

    def __init__(self, page):
        self.page = page
        self.frame = None

    def open(self):
        command(self.page, "SINUMERIK: Show Toolpath")

        def found():
            for frame in self.page.frames:
                try:
                    if frame.query_selector("#canvas") is not None:
                        return frame
                except Exception:  # noqa: BLE001 - a frame that is going away
                    pass
            return None

        self.frame = wait_for(found, 30, "the toolpath webview")
        wait_for(lambda: self.frame.evaluate("window.toolpathDebug && window.toolpathDebug.state.done"), 30, "the toolpath loaded")
        wait_for(lambda: self.painted_pixels() > 0, 10, "a drawing")

    def status(self):
        return self.frame.eval_on_selector("#status", "e => e.textContent")

    def painted_pixels(self):
        """How many pixels of the canvas differ from the background (its corner pixel)."""
        return self.frame.evaluate(
            """() => {
              const c = document.getElementById('canvas');
              const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
              let n = 0;
              for (let i = 0; i < d.length; i += 4) {
                if (Math.abs(d[i] - d[0]) + Math.abs(d[i + 1] - d[1]) + Math.abs(d[i + 2] - d[2]) > 60) n++;
              }
              return n;
            }"""
        )

    def drawn_lines(self):
        """The program lines (1-based) of the segments on screen."""
        return self.frame.evaluate(
            """() => {
              const p = window.toolpathDebug.state.projected;
              const lines = new Set();
              for (let i = 0; i < p.count; i++) lines.add(p.line[i]);
              return [...lines].sort((a, b) => a - b);
            }"""
        )

    def click_line(self, line):
        """Clicks the middle of the first segment of `line` on the canvas."""
        point = self.frame.evaluate(
            """line => {
              const s = window.toolpathDebug.state;
              const p = s.projected, v = s.view;
              for (let i = 0; i < p.count; i++) {
                if (p.line[i] !== line) continue;
                const x = (p.x0[i] + p.x1[i]) / 2, y = (p.y0[i] + p.y1[i]) / 2;
                return {x: v.offsetX + x * v.scale, y: v.offsetY - y * v.scale};
              }
              return null;
            }""",
            line,
        )
        if point is None:
            raise AssertionError(f"no segment of line {line} on screen")
        box = self.frame.query_selector("#canvas").bounding_box()
        self.page.mouse.click(box["x"] + point["x"], box["y"] + point["y"])
