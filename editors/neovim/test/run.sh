#!/usr/bin/env bash
# Runs the Neovim plugin's headless end-to-end test; installs Debian's Neovim with apt-get when nvim
# is missing. The server is SINUMERIK_LSP_BIN, default target/release/sinumerik-lsp of the repository.
set -euo pipefail
cd "$(dirname "$0")/../../.."
bash editors/install-tool.sh nvim neovim
echo "$(nvim --version | head -n 1), server ${SINUMERIK_LSP_BIN:-target/release/sinumerik-lsp}"
# The test stops itself after its waits; the timeout only guards against a Neovim that never starts.
timeout 300 nvim --headless -u NONE -i NONE -n --cmd 'set rtp+=editors/neovim' \
  -c 'luafile editors/neovim/test/e2e.lua'
# The help, the health check and :SinumerikToolpath (with the viewer stubbed).
timeout 300 nvim --headless -u NONE -i NONE -n --cmd 'set rtp+=editors/neovim' \
  -c 'luafile editors/neovim/test/ecosystem.lua'
