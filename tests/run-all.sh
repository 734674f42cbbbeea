#!/usr/bin/env bash
# Runs the whole test suite of the repository; this is the README's test command and what CI runs.
# First the Rust suite: unit tests, end-to-end tests of the CLI, the data-driven fixtures and the
# real-program corpus (which skips with a message when ../shared/corpus/real is absent). Then the
# editor clients against the release binary: the VS Code extension (unit, grammar, headless-Chromium
# page and server-protocol tests, packaging, the package in a real VS Code) and the Neovim plugin
# (headless end-to-end tests), and the Emacs setup of docs/editors.md. Last the CI integrations
# (tests/ci): the check formats against their validators, the pre-commit hooks, the release workflow
# through actionlint, `cargo install` and the dist build.
set -euo pipefail
cd "$(dirname "$0")/.."
# Release mode matches the shipped binary and keeps the hostile-input tests fast.
cargo test --release
cargo build --release
export SINUMERIK_LSP_BIN="$PWD/target/release/sinumerik-lsp"

# The page test installs Debian's chromium and the Neovim test Debian's neovim when they are missing.
echo "== VS Code extension (editors/vscode)"
(
  cd editors/vscode
  npm ci --no-audit --no-fund
  npm run build
  npm test
  npm run test:server
  npm run package
)

# The package just made, installed into a real VS Code (code-server) and driven with headless Chromium;
# its setup is cached in ~/.cache/sinumerik-e2e (several minutes once, then about half a minute).
echo "== VS Code extension in a real VS Code (editors/vscode/test/e2e)"
bash editors/vscode/test/e2e/run.sh

echo "== Neovim plugin (editors/neovim)"
bash editors/neovim/test/run.sh

# The Emacs setup of docs/editors.md (eglot), evaluated from the document itself; the other editors'
# snippets there cannot run headless on this machine.
echo "== Emacs eglot setup (editors/emacs)"
bash editors/emacs/test/run.sh

echo "== CI integrations (tests/ci)"
bash tests/ci/run.sh
