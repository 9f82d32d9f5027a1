"""Times PyRigi's Graph.is_globally_rigid on the graphs of benches/global.rs.

The edge lists come from `GCS_BENCH_EDGES=DIR cargo bench --bench global` (one file
`global-<d>d-<n>.txt` per graph, one edge "u v" per line). Usage:

    python3 benches/pyrigi_global.py DIR [max seconds per case]

Prints a Markdown table: dimension, vertices, edges, answer, seconds (one call each; a case is
skipped once the previous size of the same dimension took longer than the limit).
"""
import sys
import time

from pyrigi import Graph

directory = sys.argv[1]
limit = float(sys.argv[2]) if len(sys.argv) > 2 else 600.0
print("| d | n | edges | PyRigi is_globally_rigid | answer |")
print("|---|---|---|---|---|")
for d in (2, 3):
    slow = False
    for n in (100, 300, 1000):
        with open(f"{directory}/global-{d}d-{n}.txt") as f:
            edges = [tuple(map(int, line.split())) for line in f if line.strip()]
        if slow:
            print(f"| {d} | {n} | {len(edges)} | not run (previous size over {limit:.0f} s) | |")
            continue
        g = Graph(edges)
        start = time.perf_counter()
        answer = g.is_globally_rigid(dim=d)
        t = time.perf_counter() - start
        print(f"| {d} | {n} | {len(edges)} | {t:.3f} s | {answer} |", flush=True)
        slow = t > limit
