#!/bin/sh
# test/web_needs.sh -- make test's one line about the page (make test-web):
# which Debian packages it still needs, or how to run it.  make test does
# not run it (a browser and about 45 s); .ci/run does.
# Usage: sh test/web_needs.sh [CLANG]
cc=${1:-clang}
missing=
command -v "$cc" >/dev/null 2>&1 || missing="$missing clang"
command -v wasm-ld >/dev/null 2>&1 || missing="$missing lld"
[ -f /usr/lib/wasm32-wasi/libc.a ] || missing="$missing wasi-libc"
rt=$("$cc" --target=wasm32-wasi -print-libgcc-file-name 2>/dev/null)
[ -n "$rt" ] && [ -f "$rt" ] || missing="$missing libclang-rt-14-dev-wasm32"
command -v chromium >/dev/null 2>&1 || missing="$missing chromium"
if [ -n "$missing" ]; then
  echo "test-web: skipped, missing Debian packages:$missing (apt-get install$missing)"
else
  echo "test-web: not part of make test; make test-web runs the page in headless chromium against afv run"
fi
