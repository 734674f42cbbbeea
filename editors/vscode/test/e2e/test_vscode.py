#!/usr/bin/env python3
"""The extension in a real VS Code (code-server, started by run.sh), driven with headless Chromium as a
user would: open POCKET.MPF, read the Problems panel, hover a coordinate, read the inlay hints and the
status bar, open the toolpath, click a segment, edit a line and watch problems, hints, hover and
toolpath follow. Prints `ok`/`FAILED` per check and `N passed, N failed`; exits 1 on a failure.

Environment: E2E_URL (the workbench with the workspace folder), E2E_RUN (a folder for screenshots),
E2E_VERBOSE=1 (what passing checks saw, too), CHROMIUM_BIN (default: Debian's Chromium).
"""
import os
import re
import sys
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

import workbench as wb

URL = os.environ["E2E_URL"]
SHOTS = Path(os.environ.get("E2E_RUN", "/tmp")) / "shots"
VERBOSE = os.environ.get("E2E_VERBOSE") == "1"
CHROMIUM = os.environ.get("CHROMIUM_BIN", "/usr/lib/chromium/chromium")
# The program's lines (1-based) that the checks below refer to.
N40, N50, N70, N80 = 5, 6, 8, 9


class Checks:
    def __init__(self, page):
        self.page = page
        self.passed = 0
        self.failed = 0

    def check(self, name, fn):
        """Runs fn, which returns (ok, detail); an exception is a failure with its message."""
        started = time.time()
        try:
            ok, detail = fn()
        except Exception as error:  # noqa: BLE001 - any failure of a step is reported, the rest still run
            ok, detail = False, f"{type(error).__name__}: {error}"
        took = f"{time.time() - started:.1f}s"
        if ok:
            self.passed += 1
            print(f"ok     {name} ({took})" + (f": {detail}" if VERBOSE else ""), flush=True)
        else:
            self.failed += 1
            print(f"FAILED {name} ({took}): {detail}", flush=True)
            self.page.screenshot(path=str(SHOTS / f"failed-{self.passed + self.failed:02d}.png"))
        return ok


def run(page, checks):
    editor = wb.Editor(page)

    def opens():
        editor.open("POCKET.MPF")
        mode = wb.status_item(page, "status.editor.mode")
        return mode == "SINUMERIK NC", f"language mode {mode!r}"

    if not checks.check("POCKET.MPF opens as a SINUMERIK NC program", opens):
        return

    def problems():
        # VS Code lists errors, warnings and infos; hints (A202 here) are only dotted in the editor.
        rows = wb.wait_for(lambda: wb.problems(page) if len(wb.problems(page)) >= 3 else None, 30, "the problems")
        wanted = [("Error", "the value of AC must be in parentheses", N70), ("Warning", "CR does nothing on a G1 line", N80)]
        missing = [w for w in wanted if not any(wb.problem_matches(row, *w) for row in rows)]
        return not missing and rows[0].startswith("2 problems in file POCKET.MPF"), f"missing {missing} in {rows}"

    checks.check("the Problems panel lists the error on line 8 and the warning on line 9", problems)

    def hover():
        text = editor.hover(N40, "Y=IC(10)", 0, "Y = ")
        return "Y = 0.000 + 10.000 = 10.000 mm" in text, f"hover {text!r}"

    checks.check("the hover of Y=IC(10) shows the incremental sum Y = 0.000 + 10.000 = 10.000 mm", hover)

    def inlay_hints():
        hints = wb.wait_for(lambda: editor.inlay_hints() or None, 20, "inlay hints")
        on = {line: hints.get(line, "") for line in (N40, N50)}
        ok = "X40 Y10 Z-2" in on[N40] and "X50 Y20 Z-2" in on[N50]
        return ok, f"hints by line {hints}"

    checks.check("inlay hints give the resolved end points of N40 and N50", inlay_hints)

    def modal_state():
        return wb.status_item(page, "sinumerik-lsp.sinumerik-lsp.sinumerik.modalState")

    def status_bar():
        editor.click_line(N40)
        text = wb.wait_for(modal_state, 20, "the modal state")
        return text.startswith("G90 G71 G17 G1") and "DIAM" not in text, f"status bar {text!r}"

    checks.check("the status bar shows the modal state at the cursor, without a diameter mode on a mill", status_bar)

    view = wb.ToolpathView(page)

    def toolpath():
        view.open()
        painted = view.painted_pixels()
        lines = view.drawn_lines()
        # N20 starts where the machine stands (unknown); N70 leaves X unknown, so N80 starts unknown too.
        wanted = [4, N40, N50, 7, 10]
        ok = painted > 200 and lines == wanted
        return ok, f"{painted} painted pixels, lines drawn {lines}, status {view.status()!r}"

    if not checks.check("the toolpath view draws the program's moves (not the unknown X of line 8)", toolpath):
        return

    def click_selects():
        view.click_line(N50)
        wb.wait_for(lambda: editor.cursor_line() == N50, 10, "the cursor on line 6")
        # The status bar follows the cursor: N50 switches to G91.
        state = wb.wait_for(lambda: modal_state() if modal_state().startswith("G91") else None, 10, "G91 at N50")
        return True, f"status bar {state!r}"

    checks.check("a click on the segment of N50 in the toolpath selects line 6 (the status bar says G91)", click_selects)

    def edit():
        editor.replace_line(N70, "N70 G1 X=AC(5)")

        # The line is typed a key at a time, and the panel shows the findings of the states in
        # between for a moment (`N70 G` leaves N80 under the G3 of N60): wait for the final state
        # rather than for the first moment with one problem. VS Code says "1 problems".
        def final_rows():
            rows = wb.problems(page)
            settled = (
                len(rows) == 2
                and re.match(r"1 problems? in file POCKET.MPF", rows[0]) is not None
                and wb.problem_matches(rows[1], "Warning", "CR does nothing", N80)
            )
            return rows if settled else None

        try:
            rows = wb.wait_for(final_rows, 30, "only the warning of line 9")
        except TimeoutError as error:
            return False, f"{error}; problems after the edit {wb.problems(page)}"
        return True, f"problems after the edit {rows}"

    checks.check("an edit that adds the parentheses removes the error from the Problems panel", edit)

    def edit_hover():
        text = editor.hover(N70, "X=AC(5)", 0, "X = ")
        return "X = 5.000 mm (AC: absolute for this block only" in text, f"hover {text!r}"

    checks.check("after the edit, the hover of X=AC(5) says X = 5.000 mm (AC: absolute for this block only ...)", edit_hover)

    def edit_toolpath():
        lines = wb.wait_for(lambda: view.drawn_lines() if N70 in view.drawn_lines() else None, 20, "line 8 drawn")
        return lines == [4, N40, N50, 7, N70, N80, 10], f"lines drawn {lines}"

    checks.check("after the edit, the toolpath draws the moves of lines 8 and 9 as well", edit_toolpath)

    def edit_hints():
        hints = wb.wait_for(lambda: editor.inlay_hints() if "X5 " in editor.inlay_hints().get(N70, "") else None, 20, "hint on N70")
        return "X?" not in hints[N70], f"hints by line {hints}"

    checks.check("after the edit, an inlay hint gives the end point of line 8", edit_hints)


def main():
    SHOTS.mkdir(parents=True, exist_ok=True)
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=CHROMIUM, headless=True, args=["--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage"]
        )
        page = browser.new_context(viewport={"width": 1400, "height": 900}).new_page()
        page.goto(URL)
        checks = Checks(page)
        try:
            run(page, checks)
        except Exception as error:  # noqa: BLE001 - reported as a failed check, then the summary
            checks.check("the test ran to its end", lambda: (False, f"{type(error).__name__}: {error}"))
        page.screenshot(path=str(SHOTS / "last.png"))
        browser.close()
    print(f"{checks.passed} passed, {checks.failed} failed", flush=True)
    return 1 if checks.failed else 0


if __name__ == "__main__":
    sys.exit(main())
