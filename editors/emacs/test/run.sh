#!/usr/bin/env bash
# Runs the Emacs setup of docs/editors.md (eglot) headless against the real server; installs Debian's
# emacs-nox and elpa-eglot with apt-get when Emacs is missing. The server is SINUMERIK_LSP_BIN, default
# target/release/sinumerik-lsp of the repository.
set -euo pipefail
cd "$(dirname "$0")/../../.."
bash editors/install-tool.sh emacs emacs-nox
# Emacs 28 has no eglot of its own; Debian packages the one of ELPA.
[ -d /usr/share/emacs/site-lisp/elpa/eglot-1.9 ] || emacs --batch -Q --eval '(progn (package-initialize) (require (quote eglot)))' 2>/dev/null \
  || bash editors/install-tool.sh /usr/share/emacs/site-lisp/elpa/eglot-1.9/eglot.el elpa-eglot
echo "$(emacs --version | head -n 1), server ${SINUMERIK_LSP_BIN:-target/release/sinumerik-lsp}"
timeout 300 emacs --batch -Q -l editors/emacs/test/eglot-test.el
