#!/usr/bin/env bash
# Builds the npm package bindings/wasm/pkg: the gcs-wasm crate for wasm32-unknown-unknown,
# wasm-bindgen for node (pkg/node, CommonJS: `require`, and `import` through node's CommonJS
# interop) and for browsers (pkg/web, an ES module with an `init`), wasm-opt -Oz when it is
# installed, TypeScript definitions from wasm-bindgen, and a package.json.
#
# Needs: `rustup target add wasm32-unknown-unknown`, and wasm-bindgen-cli at the version of
# wasm-bindgen in bindings/wasm/Cargo.lock (`cargo install wasm-bindgen-cli --version V`).
# Prints the sizes of the .wasm (bytes, gzip).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here"
target="${CARGO_TARGET_DIR:-$here/target}"
version="$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p')"
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$version" ]; then
    echo "build.sh: needs wasm-bindgen-cli $version (cargo install wasm-bindgen-cli --version $version)" >&2
    exit 1
fi
cargo build --release --locked --target wasm32-unknown-unknown
wasm="$target/wasm32-unknown-unknown/release/gcs_wasm.wasm"
rm -rf pkg
wasm-bindgen --target nodejs --remove-name-section --remove-producers-section --out-dir pkg/node "$wasm"
wasm-bindgen --target web --remove-name-section --remove-producers-section --out-dir pkg/web "$wasm"
# binaryen older than 116 mishandles the reference types wasm-bindgen emits (node then fails
# in __wbindgen_init_externref_table): only a recent wasm-opt is used.
# (`|| true`: without wasm-opt the pipeline fails, which `set -e -o pipefail` would make fatal.)
wasm_opt_version="$({ wasm-opt --version 2>/dev/null || true; } | sed -n 's/^wasm-opt version \([0-9]*\).*/\1/p')"
if [ "${wasm_opt_version:-0}" -ge 116 ]; then
    for f in pkg/node/gcs_wasm_bg.wasm pkg/web/gcs_wasm_bg.wasm; do
        # The features Rust's wasm32 target emits by default.
        wasm-opt -Oz --enable-bulk-memory --enable-mutable-globals --enable-sign-ext \
            --enable-nontrapping-float-to-int --enable-multivalue --enable-reference-types \
            "$f" -o "$f.opt" && mv "$f.opt" "$f"
    done
else
    echo "build.sh: no wasm-opt ≥ 116 (found: ${wasm_opt_version:-none}): the .wasm is not shrunk further" >&2
fi
pkg_version="$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)"
cat > pkg/package.json <<JSON
{
  "name": "gcs-wasm",
  "version": "$pkg_version",
  "description": "Exact analysis of geometric constraint systems (CAD sketches) in WebAssembly: the reports of the gcs CLI as objects.",
  "license": "MIT OR Apache-2.0",
  "main": "node/gcs_wasm.js",
  "types": "node/gcs_wasm.d.ts",
  "browser": "web/gcs_wasm.js",
  "exports": {
    ".": {
      "types": "./node/gcs_wasm.d.ts",
      "node": "./node/gcs_wasm.js",
      "default": "./web/gcs_wasm.js"
    },
    "./web": "./web/gcs_wasm.js"
  },
  "files": ["node", "web"]
}
JSON
size="$(wc -c < pkg/web/gcs_wasm_bg.wasm)"
gz="$(gzip -9 -c pkg/web/gcs_wasm_bg.wasm | wc -c)"
echo "build.sh: pkg/ ready; gcs_wasm_bg.wasm: $size bytes, $gz gzipped"
