#!/usr/bin/env bash
# Runs the whole test suite of the repository; this is the README's test command and what CI runs.
# First the Rust suite: unit tests, end-to-end tests of the CLI, the data-driven fixtures and the
# real-program corpus (which skips with a message when ../shared/corpus/real is absent). Then the
# editor clients against the release binary: the VS Code extension (unit, grammar, headless-Chromium
# page and server-protocol tests, packaging) and the Neovim plugin (headless end-to-end test). Last the
# CI integrations (tests/ci): the check formats against their validators, the pre-commit hooks, the
# release workflow through actionlint, `cargo install` and the dist build.
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

echo "== Neovim plugin (editors/neovim)"
bash editors/neovim/test/run.sh

echo "== CI integrations (tests/ci)"
bash tests/ci/run.sh
