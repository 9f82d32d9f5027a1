#!/usr/bin/env bash
# The browser test of the npm package: headless Chromium opens the example page
# (bindings/wasm/example/index.html, which imports pkg/web and analyses the kite when it loads)
# and the page must show the kite's report. Needs `bash bindings/wasm/build.sh` first, python3
# (to serve the repository) and chromium.
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
port="${GCS_BROWSER_PORT:-8173}"
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$root" >/dev/null 2>&1 &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
for _ in $(seq 50); do
    if python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/')" 2>/dev/null; then break; fi
    sleep 0.1
done
dom="$(timeout 120 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=20000 \
    --dump-dom "http://127.0.0.1:$port/bindings/wasm/example/" 2>/dev/null)"
for want in '"model": "kite"' '"rank": 5' '"redundant": \['; do
    if ! grep -q "$want" <<<"$dom"; then
        echo "browser test: the page does not show $want; it shows:" >&2
        grep -A5 '<pre id="out">' <<<"$dom" >&2 || true
        exit 1
    fi
done
echo "browser test: the example page shows the kite's report"
