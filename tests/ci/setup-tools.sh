#!/usr/bin/env bash
# Installs the tools the CI-integration tests drive, once per set of pins, into a cache folder that
# survives fresh clones (CI clones the repository anew on every run): a Python virtual environment
# with pytest, jsonschema, pre-commit, actionlint and ShellCheck (requirements.txt, from PyPI) and
# Microsoft's SARIF multitool (npm/package-lock.json, from the npm registry).
# Prints the cache folder; the tools are in $TOOLS/venv/bin and $TOOLS/npm/node_modules.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cache_root="${SINUMERIK_CI_TOOLS:-${XDG_CACHE_HOME:-$HOME/.cache}/sinumerik-lsp/ci-tools}"
# A change of any pin makes a new folder, so an old cache never answers for new pins.
key="$(cat "$here/requirements.txt" "$here/npm/package-lock.json" | sha256sum | cut -c1-16)"
tools="$cache_root/$key"
if [[ ! -f "$tools/.complete" ]]; then
  rm -rf "$tools"
  mkdir -p "$tools"
  echo "setting up the CI test tools in $tools" >&2
  python3 -m venv "$tools/venv"
  "$tools/venv/bin/pip" install --quiet --disable-pip-version-check -r "$here/requirements.txt" >&2
  mkdir -p "$tools/npm"
  cp "$here/npm/package.json" "$here/npm/package-lock.json" "$tools/npm/"
  (cd "$tools/npm" && npm ci --no-audit --no-fund --ignore-scripts >&2)
  # The package's install script only makes the binary executable; npm here runs no install scripts.
  chmod u+x "$tools/npm/node_modules/@microsoft/sarif-multitool-linux/Sarif.Multitool"
  touch "$tools/.complete"
fi
echo "$tools"
