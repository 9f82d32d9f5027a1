#!/usr/bin/env bash
# Fuzzes the gcs readers with cargo-fuzz (nightly toolchain; `cargo install cargo-fuzz`).
#
#   fuzz/run.sh [RUNS] [TARGET...]
#
# RUNS inputs per target (default 1000000); targets default to all of them. Each target starts
# from its committed seeds (fuzz/seeds/TARGET, copied into fuzz/corpus/TARGET, which grows and
# is not committed) and runs with the limits below. A crash, a hang or an allocation over the
# limit stops the target and leaves the input in fuzz/artifacts/TARGET. Logs: fuzz/logs/.
# Set JOBS for cargo's build jobs (default 1), EXTRA for more libFuzzer options; the build goes
# to CARGO_TARGET_DIR when set, else fuzz/target.
set -u
cd "$(dirname "$0")"

runs=${1:-1000000}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(ron slvs freecad freecad_xml onshape)
fi
# A hang: one input over 10 s. Memory: 2 GB resident, 512 MB in one allocation.
limits=(-rss_limit_mb=2048 -malloc_limit_mb=512 -timeout=10)

mkdir -p logs
status=0
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t" "artifacts/$t"
    cp seeds/"$t"/* "corpus/$t/"
    log="logs/$t.log"
    start=$(date +%s)
    # cargo-fuzz builds optimised with debug assertions and overflow checks, under ASan.
    CARGO_BUILD_JOBS="${JOBS:-1}" cargo +nightly fuzz run --target-dir "${CARGO_TARGET_DIR:-target}" \
        "$t" "corpus/$t" -- \
        -runs="$runs" "${limits[@]}" -artifact_prefix="artifacts/$t/" ${EXTRA:-} \
        >"$log" 2>&1
    rc=$?
    secs=$(( $(date +%s) - start ))
    done_line=$(grep -E '^Done [0-9]+ runs' "$log" | tail -1)
    execs=$(grep -oE '^#[0-9]+' "$log" | tail -1 | tr -d '#')
    if [ "$rc" -eq 0 ]; then
        outcome="ok: ${done_line:-no summary}"
    else
        status=1
        found=$(grep -E 'ERROR: libFuzzer|panicked at|deadly signal|Test unit written' "$log" | head -3 | tr '\n' ' ')
        outcome="FAILED (exit $rc): $found"
    fi
    printf '%-12s executions %-10s %5d s  %s\n' "$t" "${execs:-?}" "$secs" "$outcome"
done
exit $status
