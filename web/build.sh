#!/usr/bin/env bash
# Builds the path-tool engine for wasm32-unknown-unknown and makes it an npm-style package
# beside the page, web/www/pkg/: the wasm-bindgen JavaScript module (`--target web`), its
# TypeScript types and a package.json. wasm-bindgen-cli is installed from crates.io at the
# version of the wasm-bindgen crate in Cargo.lock (the two must match), into the target
# directory, when it is not there yet.
set -euo pipefail
cd "$(dirname "$0")"
if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
fi
cargo build --release --locked --target wasm32-unknown-unknown
# The target directory may be moved by CARGO_TARGET_DIR or a cargo config: ask cargo.
target=$(cargo metadata --format-version 1 --no-deps --locked |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')

version=$(python3 - <<'EOF'
import tomllib
with open("Cargo.lock", "rb") as f:
    lock = tomllib.load(f)
print(next(p["version"] for p in lock["package"] if p["name"] == "wasm-bindgen"))
EOF
)
root="$target/wasm-bindgen-cli/$version"
bindgen="$root/bin/wasm-bindgen"
if ! [ -x "$bindgen" ] || [ "$("$bindgen" --version)" != "wasm-bindgen $version" ]; then
    echo "installing wasm-bindgen-cli $version into $root"
    CARGO_TARGET_DIR="$target/wasm-bindgen-cli/build" \
        cargo install --locked --quiet wasm-bindgen-cli --version "$version" --root "$root"
fi

pkg=www/pkg
rm -rf "$pkg"
"$bindgen" --target web --out-dir "$pkg" --out-name kappa_web \
    "$target/wasm32-unknown-unknown/release/kappa_web.wasm"
python3 - "$pkg" <<'EOF'
import json, sys, tomllib
with open("Cargo.toml", "rb") as f:
    meta = tomllib.load(f)["package"]
package = {
    "name": "kappa-web",
    "version": meta["version"],
    "description": "The kappa path-tool engine (curves of controlled curvature) for web editors",
    "license": meta["license"],
    "type": "module",
    "module": "kappa_web.js",
    "main": "kappa_web.js",
    "types": "kappa_web.d.ts",
    "files": ["kappa_web.js", "kappa_web.d.ts", "kappa_web_bg.wasm", "kappa_web_bg.wasm.d.ts",
              "snippets"],
    "sideEffects": ["./snippets/*"],
}
with open(f"{sys.argv[1]}/package.json", "w") as f:
    json.dump(package, f, indent=2)
    f.write("\n")
EOF
echo "web/www/pkg: kappa_web_bg.wasm $(wc -c < "$pkg/kappa_web_bg.wasm") bytes, kappa_web.js $(wc -c < "$pkg/kappa_web.js") bytes"
