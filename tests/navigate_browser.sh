#!/usr/bin/env bash
# The browser test of `gcs navigate`: headless Chromium opens the page written for the chain of
# triangles (data/paper/chain.ron), first as written (autosolve: the drawing's choices), then
# with `#choose=STEP:K` flipping one closed-form step, and reads the page's state: the
# realization shown must change, take candidate K at that step, and satisfy every constraint.
# Needs the release CLI built and chromium. Writes a screenshot next to the page.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
gcs="${GCS_CLI:-$root/target/release/gcs}"
dir="$(mktemp -d)"
page="$dir/chain.html"
"$gcs" navigate "$root/data/paper/chain.ron" -o "$page"
state() {
    timeout 120 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 \
        --dump-dom "file://$page$1" 2>/dev/null \
        | python3 -c '
import html, json, re, sys
m = re.search(r"<pre id=\"state\">(.*?)</pre>", sys.stdin.read(), re.S)
print(json.dumps(json.loads(html.unescape(m.group(1)))) if m else "none")'
}
before="$(state "")"
# Step 2 of the plan is the second closed-form step (step 0 is the core): take the candidate
# the drawing did not.
k="$(python3 -c 'import json,sys; print(1 - json.loads(sys.argv[1])["choices"][1])' "$before")"
after="$(state "#choose=2:$k")"
python3 - "$before" "$after" "$k" <<'PY'
import json, sys
before, after, k = json.loads(sys.argv[1]), json.loads(sys.argv[2]), int(sys.argv[3])
problems = []
if after["realization"] == before["realization"]:
    problems.append("the realization did not change")
if after["choices"][1] != k:
    problems.append(f"step 2 is at candidate {after['choices'][1]}, not {k}")
for s in (before, after):
    if not s["max_residual"] <= 1e-9:
        problems.append(f"realization {s['realization']}: residual {s['max_residual']}")
if problems:
    sys.exit("navigate browser test: " + "; ".join(problems) + f"\n  before {before}\n  after {after}")
PY
timeout 120 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 \
    --window-size=1300,900 --screenshot="$dir/chain.png" "file://$page#choose=2:$k" >/dev/null 2>&1 || true
echo "navigate browser test: picking candidate $k of step 2 redraws another realization; screenshot $dir/chain.png"
