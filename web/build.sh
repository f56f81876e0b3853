#!/usr/bin/env bash
# Builds the path-tool engine for wasm32-unknown-unknown and puts it beside the page
# (web/www/kappa_web.wasm).
set -euo pipefail
cd "$(dirname "$0")"
if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
fi
cargo build --release --locked --target wasm32-unknown-unknown
# The target directory may be moved by CARGO_TARGET_DIR or a cargo config: ask cargo.
target=$(cargo metadata --format-version 1 --no-deps --locked |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
cp "$target/wasm32-unknown-unknown/release/kappa_web.wasm" www/kappa_web.wasm
echo "web/www/kappa_web.wasm: $(wc -c < www/kappa_web.wasm) bytes"
