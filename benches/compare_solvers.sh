#!/bin/sh
# gcs, SolveSpace (python-solvespace) and FreeCAD's PlaneGCS (@salusoft89/planegcs) solving
# the same generated Laman sketches drawn with jitter (issue 13), one tool after another on
# each file: one line per tool and case. Not part of CI.
# Usage: benches/compare_solvers.sh [SIZES...]        (default 30 100 300 1000)
#        benches/compare_solvers.sh --diagnose [N]    (default 30: what each tool reports on
#            the sketch with its redundant distance, and with that distance given a
#            conflicting value; seed 1, jitter 0.05)
# The other tools live outside the repository: GCS_CMP_VENV (default /work/venv-cmp, a venv
# with python-solvespace) and GCS_CMP_NPM (default /work/npm-cmp, a directory where
# @salusoft89/planegcs is installed with npm). GCS_CMP_TIMEOUT: seconds per tool and case
# (default 600). Seeds 1-3, jitter 0.05 and 0.2; the JSON files go to
# ${CARGO_TARGET_DIR:-target}/compare-solvers. GCS_CMP_VARIANT=minimal: the sketches without
# the generator's redundant distance; GCS_CMP_PIN=0: no point held in any tool (the trivial
# motions left to each solver) instead of the pinned edge (see the export_drawn example).
set -e
venv="${GCS_CMP_VENV:-/work/venv-cmp}"
npm="${GCS_CMP_NPM:-/work/npm-cmp}"
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import python_solvespace' 2>/dev/null; then
  echo "compare_solvers.sh: no python-solvespace in the venv $venv; make it with" >&2
  echo "  python3 -m venv $venv && $venv/bin/pip install python-solvespace  (or set GCS_CMP_VENV)" >&2
  exit 2
fi
if [ ! -f "$npm/node_modules/@salusoft89/planegcs/package.json" ]; then
  echo "compare_solvers.sh: no @salusoft89/planegcs under $npm; install it with" >&2
  echo "  mkdir -p $npm && cd $npm && npm install @salusoft89/planegcs  (or set GCS_CMP_NPM)" >&2
  exit 2
fi
command -v node >/dev/null || { echo "compare_solvers.sh: node not found" >&2; exit 2; }
cargo build --release -q -p gcs-solve --example export_drawn --example solve_json
target="${CARGO_TARGET_DIR:-target}"
export_drawn="$target/release/examples/export_drawn"
solve_json="$target/release/examples/solve_json"
dir="$target/compare-solvers"
mkdir -p "$dir"
limit="${GCS_CMP_TIMEOUT:-600}"
echo "# $(uname -srm); $(nproc) cores; rustc $(rustc --version | cut -d' ' -f2);" \
  "python-solvespace $("$venv/bin/python" -c 'from importlib.metadata import version; print(version("python-solvespace"))');" \
  "planegcs $(node -p "require('$npm/node_modules/@salusoft89/planegcs/package.json').version"); node $(node --version)"

# One tool on one file; a line saying so when it fails or runs out of time.
run() {
  tool="$1"; file="$2"; shift 2
  if ! timeout "$limit" "$@" "$file"; then
    echo "tool=$tool file=$file status=error-or-timeout(${limit}s)"
  fi
}
three() {
  run gcs "$1" "$solve_json"
  run slvs "$1" "$venv/bin/python" benches/compare_solvers.py
  run planegcs "$1" node benches/compare_solvers.mjs
}

if [ "$1" = "--diagnose" ]; then
  n="${2:-30}"
  for variant in "" conflict; do
    file="$dir/drawn-$n-1-0.05${variant:+-$variant}.json"
    "$export_drawn" "$n" 1 0.05 $variant > "$file"
    echo "## n=$n seed=1 jitter=0.05 ${variant:-redundant distance consistent}"
    VERBOSE=1 three "$file" 2>&1 | grep -v '^$' | grep -v '^Sketcher'
  done
  exit 0
fi

sizes="${*:-30 100 300 1000}"
for jitter in 0.05 0.2; do
  for n in $sizes; do
    for seed in 1 2 3; do
      file="$dir/drawn-$n-$seed-$jitter${GCS_CMP_VARIANT:+-$GCS_CMP_VARIANT}.json"
      "$export_drawn" "$n" "$seed" "$jitter" $GCS_CMP_VARIANT > "$file"
      three "$file" | grep '^tool='
    done
  done
done
