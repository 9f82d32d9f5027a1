#!/usr/bin/env bash
# The browser test of `gcs navigate`: headless Chromium opens the pages written for
# - the chain of triangles (data/paper/chain.ron): first as written (autosolve: the drawing's
#   choices), then with `#choose=STEP:K` flipping one closed-form step;
# - two K3,3 joined by three distances (data/paper/two_k33.ron): with `#choose=0:1`, the second
#   candidate of the first K3,3 (step 0 of the core's DR-plan, found by homotopy continuation),
#   the assembly of the two re-solved;
# and reads the page's state: the realization shown must change, take candidate K at that
# step, and satisfy every constraint. Then, on two K3,3, as a user would: playwright-core
# (npm, installed into a temporary directory unless PLAYWRIGHT_CORE names one) drives Chromium
# to click the first K3,3's step and its second candidate's button (tests/navigate_click.mjs);
# the picture shown must change, and the realization shown, written as RON, must satisfy every
# constraint by `gcs analyze` itself (not by the residual the page embeds). Needs the release
# CLI built, chromium, and node with npm for the click. Screenshots go to
# target/navigate-browser/ (kept after the run: look at them).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
gcs="${GCS_CLI:-$root/target/release/gcs}"
dir="$(mktemp -d)"
state() {
    timeout 120 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 \
        --dump-dom "file://$1$2" 2>/dev/null \
        | python3 -c '
import html, json, re, sys
m = re.search(r"<pre id=\"state\">(.*?)</pre>", sys.stdin.read(), re.S)
print(json.dumps(json.loads(html.unescape(m.group(1)))) if m else "none")'
}
# check PAGE STEP CHOICE K: the page at `#choose=STEP:K` against the page as written; CHOICE
# is the step's place in the state's `choices`.
check() {
    local page="$1" step="$2" choice="$3" k="$4"
    local before after
    before="$(state "$page" "")"
    after="$(state "$page" "#choose=$step:$k")"
    python3 - "$before" "$after" "$choice" "$k" "$page" <<'PY'
import json, sys
before, after, c, k, page = json.loads(sys.argv[1]), json.loads(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
problems = []
if after["realization"] == before["realization"]:
    problems.append("the realization did not change")
if after["choices"][c] != k:
    problems.append(f"choice {c} is at candidate {after['choices'][c]}, not {k}")
for s in (before, after):
    if not s["max_residual"] <= 1e-9:
        problems.append(f"realization {s['realization']}: residual {s['max_residual']}")
if problems:
    sys.exit(f"navigate browser test ({page}): " + "; ".join(problems) + f"\n  before {before}\n  after {after}")
PY
    timeout 120 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 \
        --window-size=1400,1000 --screenshot="${page%.html}.png" "file://$page#choose=$step:$k&open=$step" \
        >/dev/null 2>&1 || true
    echo "navigate browser test: $(basename "$page"): candidate $k of step $step shows another realization, every constraint holding; screenshot ${page%.html}.png"
}

chain="$dir/chain.html"
"$gcs" navigate "$root/data/paper/chain.ron" -o "$chain"
# The chain's step 2 is its second closed-form step (step 0 is the core, one distance, no
# choice; the choices are the core node's, then the closed-form steps'): take the candidate the
# drawing did not.
k="$(python3 -c 'import json,sys; print(1 - json.loads(sys.argv[1])["choices"][2])' "$(state "$chain" "")")"
check "$chain" 2 2 "$k"

k33="$dir/two_k33.html"
"$gcs" navigate "$root/data/paper/two_k33.ron" -o "$k33"
check "$k33" 0 0 1

# The click.
shots="${CARGO_TARGET_DIR:-$root/target}/navigate-browser"
mkdir -p "$shots"
pw="${PLAYWRIGHT_CORE:-}"
if [ -z "$pw" ]; then
    npm install --silent --no-audit --no-fund --prefix "$dir/npm" playwright-core@1 >/dev/null
    pw="$dir/npm/node_modules/playwright-core"
fi
PLAYWRIGHT_CORE="$pw" node "$root/tests/navigate_click.mjs" "$k33" 0 1 "$shots/two_k33-click"
"$gcs" analyze --format json "$shots/two_k33-click.ron" >"$dir/click-analysis.json"
python3 - "$shots/two_k33-click.json" "$dir/click-analysis.json" <<'PY'
import json, sys
shown, analysis = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
before, after = shown["before"], shown["after"]
problems = []
if after["state"]["choices"][0] != 1:
    problems.append(f"the first K3,3 shows candidate {after['state']['choices'][0]}, not 1")
if after["state"]["realization"] == before["state"]["realization"]:
    problems.append("the realization did not change")
if after["svg"] == before["svg"]:
    problems.append("the picture did not change")
sketch = analysis.get("sketch") or {}
if sketch.get("satisfied") is not True:
    problems.append(f"gcs analyze of the realization shown: {sketch}")
if problems:
    sys.exit("navigate browser test (click): " + "; ".join(problems))
PY
echo "navigate browser test: two K3,3: a click on candidate 1 of step 0 redraws the sketch, and gcs analyze finds every constraint holding in the realization shown; screenshot $shots/two_k33-click.png"
