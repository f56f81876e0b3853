#!/usr/bin/env bash
# The path tool in the browser, from a fresh clone: installs Debian's Chromium if it is
# missing, checks and unit-tests the wasm crate natively (fmt, clippy, cargo test), builds
# the wasm module and its npm package (www/pkg/; the first build installs wasm-bindgen-cli
# into the target directory), installs the test's npm packages (npm ci), checks the
# package's TypeScript types, serves the page on a free localhost port, runs the Playwright
# test in headless Chromium, and stops the server. Cargo's target directory is web/target,
# or CARGO_TARGET_DIR.
# KAPPA_BLESS=1 re-creates the golden screenshot and the user guide's picture (docs/path-tool.png).
set -euo pipefail
cd "$(dirname "$0")/.."
web=$(pwd)
t0=$(date +%s)
step() { echo "== web: $* ($(($(date +%s) - t0)) s)"; }

if [ ! -x /usr/bin/chromium ]; then
    step "installing chromium"
    sudo=""
    if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
    log=$(mktemp)
    if ! { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq chromium; } >"$log" 2>&1; then
        tail -n 30 "$log"
        exit 1
    fi
    rm -f "$log"
fi

step "wasm crate: fmt, clippy, unit tests"
cargo fmt -- --check
cargo clippy --locked --all-targets -- -D warnings
cargo test --locked

step "building the wasm module and its package"
./build.sh

step "npm ci"
(cd test && npm ci --no-audit --no-fund --loglevel=error)

step "the package's types"
(cd test && node --test --test-reporter=spec package.test.mjs)

step "serving the page"
tmp=$(mktemp -d)
python3 serve.py --port 0 --port-file "$tmp/port" >"$tmp/server.log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true; rm -rf "$tmp"' EXIT
for _ in $(seq 100); do
    [ -s "$tmp/port" ] && break
    if ! kill -0 "$server" 2>/dev/null; then
        cat "$tmp/server.log"
        exit 1
    fi
    sleep 0.1
done
port=$(cat "$tmp/port")

step "browser test on http://127.0.0.1:$port/"
(cd test && KAPPA_WEB_URL="http://127.0.0.1:$port/" node --test --test-reporter=spec browser.test.mjs)
step "done"
