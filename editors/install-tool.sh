#!/usr/bin/env bash
# `install-tool.sh COMMAND PACKAGE`: installs Debian's PACKAGE with apt-get when COMMAND is missing
# and this runs as root; otherwise says how to get it and fails. Used by the editor tests.
set -euo pipefail
command="$1"
package="$2"
if command -v "$command" >/dev/null; then
  exit 0
fi
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  echo "installing $package with apt-get (for $command)"
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q "$package"
else
  echo "$command is missing: run 'sudo apt-get install $package'" >&2
  exit 1
fi
