#!/usr/bin/env bash
# Builds the wasm engine and serves the path-tool page on http://127.0.0.1:${PORT:-8000}/.
set -euo pipefail
cd "$(dirname "$0")"
./build.sh
exec python3 serve.py --port "${PORT:-8000}"
