"""Times PyRigi's rigidity and rigid components on the graph of a gcs model of points and
distances, beside `gcs analyze` on the same file (issue 15's side-by-side comparison).

    python3 benches/pyrigi_rigidity.py MODEL.ron [GCS [PEBBLE_TIME]]

Reads the `Distance(..., a: "pI", b: "pJ", ...)` constraints of the model (as `gcs generate
laman|laman-sketch N` writes them), builds PyRigi's `Graph`, and prints one Markdown row:
vertices, edges, PyRigi `is_rigid(dim=2)`, PyRigi `rigid_components(dim=2)` (their times in
seconds, one call each), the pebble game gcs decides such frameworks with (`pebble_game`,
timed in process by `cargo run --release -p gcs-decompose --example pebble_time`: rank, every
redundant bar's circuit, the rigid components; best of five), and the whole
`gcs analyze --backend modp --format json MODEL` (parse, witness, sketch rank, rank,
redundancy, clusters, global rigidity) timed as a command, with its verdict.
"""
import json
import re
import subprocess
import sys
import time

from pyrigi import Graph

path = sys.argv[1]
gcs = sys.argv[2] if len(sys.argv) > 2 else "target/release/gcs"
pebble_time = sys.argv[3] if len(sys.argv) > 3 else "target/release/examples/pebble_time"
text = open(path).read()
edges = [
    (int(a), int(b))
    for a, b in re.findall(r'Distance\([^)]*?a: "p(\d+)", b: "p(\d+)"', text)
]
vertices = {v for e in edges for v in e}
g = Graph(edges)
start = time.perf_counter()
rigid = g.is_rigid(dim=2)
t_rigid = time.perf_counter() - start
start = time.perf_counter()
components = g.rigid_components(dim=2)
t_components = time.perf_counter() - start
start = time.perf_counter()
out = subprocess.run(
    [gcs, "analyze", "--backend", "modp", "--format", "json", path],
    capture_output=True, text=True, check=False,
)
t_gcs = time.perf_counter() - start
report = json.loads(out.stdout.splitlines()[0])
pebble = json.loads(
    subprocess.run([pebble_time, path], capture_output=True, text=True, check=True).stdout
)
t_pebble = pebble["seconds"]
print(
    f"| {len(vertices)} | {len(edges)} | {t_rigid:.3f} s ({rigid}) | {t_components:.3f} s "
    f"({len(components)} components) | {t_pebble:.5f} s ({pebble['components']} components) | "
    f"{t_rigid / t_pebble:.0f}× / {t_components / t_pebble:.0f}× | {t_gcs:.3f} s "
    f"(rigid {report['rigid']}, {len(report['redundant'])} redundant, "
    f"{len(report['clusters'])} clusters, {report.get('rank_method')}) | "
    f"{min(t_rigid, t_components) / t_gcs:.1f}× |"
)
