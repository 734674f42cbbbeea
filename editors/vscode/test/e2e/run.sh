#!/usr/bin/env bash
# The extension in a real VS Code: installs the package (default dist/sinumerik-lsp.vsix, made by
# `npm run package`) into code-server with a fresh profile, opens test/e2e/workspace, and lets
# test_vscode.py check with headless Chromium what a user sees. The setup (setup.sh) is cached in
# ~/.cache/sinumerik-e2e; its first run takes several minutes, later runs under a minute or two.
# Screenshots and the logs of VS Code and the server are kept in the printed folder on failure.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
vsix=$(cd "$here/../.." && realpath "${1:-dist/sinumerik-lsp.vsix}")
[ -f "$vsix" ] || { echo "no extension package at $vsix: run 'npm run package' first" >&2; exit 1; }
started=$(date +%s)
cache=$(bash "$here/setup.sh" | tail -n 1)
code_server="$cache/code-server/node_modules/.bin/code-server"

run=$(mktemp -d "${TMPDIR:-/tmp}/sinumerik-e2e.XXXXXX")
mkdir -p "$run/user/User" "$run/workspace"
cp "$here/settings.json" "$run/user/User/settings.json"
cp "$here"/workspace/* "$run/workspace/"
printf 'bind-addr: 127.0.0.1:0\nauth: none\ncert: false\n' > "$run/config.yaml"
common=(--config "$run/config.yaml" --user-data-dir "$run/user" --extensions-dir "$run/extensions")
"$code_server" "${common[@]}" --install-extension "$vsix" >"$run/install.log" 2>&1 \
  || { cat "$run/install.log" >&2; exit 1; }

port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
# A session of its own, so that stopping it reaches the extension host and the language server too.
setsid "$code_server" "${common[@]}" --bind-addr "127.0.0.1:$port" --auth none --disable-telemetry \
  --disable-update-check --disable-workspace-trust --disable-getting-started-override "$run/workspace" \
  >"$run/code-server.log" 2>&1 &
server_pid=$!
stop() {
  kill -- "-$server_pid" 2>/dev/null || true
  for _ in 1 2 3 4 5 6 7 8 9 10; do kill -0 "$server_pid" 2>/dev/null || break; sleep 0.5; done
  kill -9 -- "-$server_pid" 2>/dev/null || true
}
trap stop EXIT
for _ in $(seq 60); do
  curl -sf -o /dev/null "http://127.0.0.1:$port/healthz" && break
  kill -0 "$server_pid" 2>/dev/null || { cat "$run/code-server.log" >&2; exit 1; }
  sleep 0.5
done

status=0
E2E_URL="http://127.0.0.1:$port/?folder=$run/workspace" E2E_RUN="$run" PYTHONDONTWRITEBYTECODE=1 \
  "$cache/venv/bin/python" "$here/test_vscode.py" || status=$?
stop
trap - EXIT
if [ "$status" = 0 ]; then
  rm -rf "$run"
else
  echo "screenshots and logs: $run (code-server.log, shots/, user/logs/)" >&2
fi
echo "real VS Code test: $(($(date +%s) - started)) s"
exit "$status"
