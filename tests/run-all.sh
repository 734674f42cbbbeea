#!/usr/bin/env bash
# Runs the whole test suite of the repository; this is the README's test command and what CI runs.
# Today that is the Rust suite: unit tests, end-to-end tests of the CLI, the data-driven fixtures and
# the real-program corpus (which skips with a message when ../shared/corpus/real is absent).
set -euo pipefail
cd "$(dirname "$0")/.."
# Release mode matches the shipped binary and keeps the hostile-input tests fast.
cargo test --release
