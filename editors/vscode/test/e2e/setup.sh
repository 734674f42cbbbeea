#!/usr/bin/env bash
# Prepares what the end-to-end test needs, once per machine, in a cache folder the machine keeps
# between runs ($SINUMERIK_E2E_CACHE, default ~/.cache/sinumerik-e2e): code-server (VS Code in the
# browser) from the npm registry, Playwright for Python from PyPI in a virtual environment, and
# Debian's Chromium. A finished setup leaves a stamp with its versions; a run with the same versions
# does nothing. Prints the cache folder on its last line.
#
# code-server's own install step downloads a git dependency and ripgrep from the web, which a machine
# with access to the package registries only cannot do. The same steps are done here by hand: the
# dependency comes from the npm registry (the same package, published there as @vscode/proxy-agent),
# ripgrep from Debian, and the native modules are built against Debian's Node headers.
set -euo pipefail
CODE_SERVER_VERSION=4.96.4    # VS Code 1.96.4
PLAYWRIGHT_VERSION=1.65.2     # drives the system Chromium; its own browser download is not used
PROXY_AGENT_VERSION=0.27.0    # the commit VS Code 1.96.4 pins, as published on the npm registry
cache=${SINUMERIK_E2E_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/sinumerik-e2e}
stamp="$cache/ready-code-server-$CODE_SERVER_VERSION-playwright-$PLAYWRIGHT_VERSION"
if [ -f "$stamp" ]; then
  echo "$cache"
  exit 0
fi
here=$(cd "$(dirname "$0")" && pwd)
install_tool() { bash "$here/../../../install-tool.sh" "$@"; }

# Debian packages: the browser, ripgrep for VS Code's search, and the headers of the native modules.
install_tool chromium chromium
install_tool rg ripgrep
for header in krb5.h:libkrb5-dev X11/extensions/XKBfile.h:libxkbfile-dev libsecret-1/libsecret/secret.h:libsecret-1-dev; do
  [ -e "/usr/include/${header%%:*}" ] || { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${header##*:}"; }
done
[ -e /usr/include/node/node.h ] || { echo "Node's headers are missing (/usr/include/node): install Debian's nodejs" >&2; exit 1; }
export npm_config_nodedir=/usr
export npm_config_fund=false npm_config_audit=false

mkdir -p "$cache/code-server"
cd "$cache/code-server"
[ -f package.json ] || echo '{"name": "sinumerik-e2e-code-server", "private": true}' > package.json
npm install --ignore-scripts --save-exact "code-server@$CODE_SERVER_VERSION"
npm rebuild argon2 --foreground-scripts
vscode=node_modules/code-server/lib/vscode
sed -i "s#git+ssh://git@github.com/microsoft/vscode-proxy-agent.git\#[0-9a-f]*#https://registry.npmjs.org/@vscode/proxy-agent/-/proxy-agent-$PROXY_AGENT_VERSION.tgz#" \
  "$vscode/npm-shrinkwrap.json"
(
  cd "$vscode"
  npm install --omit=dev --ignore-scripts
  npm rebuild kerberos @parcel/watcher @vscode/deviceid @vscode/spdlog native-watchdog node-pty --foreground-scripts
  mkdir -p node_modules/@vscode/ripgrep/bin
  cp "$(command -v rg)" node_modules/@vscode/ripgrep/bin/rg
  # The release layout code-server expects: the modules as if packed, and the helper scripts by name.
  ln -sfn node_modules node_modules.asar
  ln -sfn code-linux.sh bin/remote-cli/code-server
  ln -sfn browser-linux.sh bin/helpers/browser.sh
  cd extensions && npm install --omit=dev
)
# With a config file of its own, so that asking for the version writes none into ~/.config.
printf 'auth: none\ncert: false\n' > config.yaml
node_modules/.bin/code-server --config config.yaml --version

python3 -m venv "$cache/venv"
"$cache/venv/bin/pip" install --quiet --disable-pip-version-check "playwright==$PLAYWRIGHT_VERSION"
touch "$stamp"
echo "$cache"
