#!/bin/sh
# The solver on generated Laman sketches drawn with jitter (issue 13): one line per case with
# the analysis and solve times, the status and the triangles that kept their drawn orientation.
# Usage: benches/solve.sh [SIZES...]   (default 100 300 1000 3000 10000)
set -e
cargo build --release -q -p gcs-solve --example drawn
bin="${CARGO_TARGET_DIR:-target}/release/examples/drawn"
sizes="${*:-100 300 1000 3000 10000}"
for jitter in 0.05 0.2; do
  for n in $sizes; do
    for seed in 1 2 3; do
      "$bin" "$n" "$seed" "$jitter"
    done
  done
done
