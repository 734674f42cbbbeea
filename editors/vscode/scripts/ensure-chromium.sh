#!/usr/bin/env bash
# Makes sure Debian's Chromium is there for the page test: installs it with apt-get when it is
# missing and this runs as root; otherwise says how to get it. CHROMIUM_BIN overrides the name.
set -euo pipefail
browser="${CHROMIUM_BIN:-chromium}"
if command -v "$browser" >/dev/null; then
  exit 0
fi
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  echo "installing chromium with apt-get for the page test"
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium
else
  echo "the page test needs Debian's chromium: run 'sudo apt-get install chromium', or set CHROMIUM_BIN" >&2
  exit 1
fi
