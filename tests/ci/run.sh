#!/usr/bin/env bash
# The CI-integration tests: the check formats against their validators (SARIF multitool and schema,
# GitLab's fields, GitHub's command syntax), the pre-commit hooks through the real pre-commit, the
# release workflow and the CI snippets through actionlint, `cargo install`, and the dist build.
# Installs its tools into a cache (setup-tools.sh); SINUMERIK_LSP_BIN names the binary under test.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
tools="$(bash "$here/setup-tools.sh")"
export SINUMERIK_CI_TOOLS_DIR="$tools"
export PATH="$tools/venv/bin:$PATH"
cd "$here"
exec "$tools/venv/bin/pytest" -q -p no:cacheprovider "$@" .
