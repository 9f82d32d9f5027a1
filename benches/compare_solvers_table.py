"""The table of benches/compare_solvers.sh's output (read from stdin): per tool, size and
jitter, the median solve time over the seeds (gcs: also analysis + solve), the statuses the
tool reported, the largest distance residual, the seeds whose distances all hold within
1e-3 model units ("met": the sketches span about 2000 units, the values are written to 6 decimals, so a consistent redundant distance over a long circuit may miss by more than 1e-6; every failure misses by at least 1), the triangles that kept their drawn orientation (summed over the
seeds); then each tool's growth exponent from the two largest sizes where every seed met its
distances, and the exponent of the time to return (solved or not) from the two largest sizes
run. Usage: benches/compare_solvers.sh ... | python3 benches/compare_solvers_table.py"""

import math
import re
import statistics
import sys
from collections import Counter, defaultdict

MET = 1e-3
rows = defaultdict(list)
for line in sys.stdin:
    if not line.startswith("tool="):
        continue
    f = dict(re.findall(r"(\w+)=(\S+)", line))
    if "n" not in f:  # a run that failed or ran out of time
        print(f"note: {line.strip()}")
        continue
    rows[(f["tool"], int(f["n"]), f["jitter"])].append(f)

secs = lambda s: float(s.rstrip("s"))
print("| tool | n | jitter | median solve (s) | median analysis+solve (s) | status (seeds) "
      "| max residual | met | orientation kept |")
print("|---|---:|---:|---:|---:|---|---:|---:|---:|")
summary = {}
for (tool, n, jitter), fs in sorted(rows.items(), key=lambda k: (k[0][2], k[0][0], k[0][1])):
    solve = statistics.median(secs(f["solve"]) for f in fs)
    total = (
        statistics.median(secs(f["analysis"]) + secs(f["solve"]) for f in fs)
        if "analysis" in fs[0]
        else None
    )
    status = ", ".join(f"{s} {c}" for s, c in sorted(Counter(f["status"] for f in fs).items()))
    residual = max(float(f["max_residual"]) for f in fs)
    met = sum(float(f["max_residual"]) <= MET for f in fs)
    kept = [tuple(map(int, f["orientation_kept"].split("/"))) for f in fs]
    summary[(tool, jitter, n)] = (solve, total, met == len(fs))
    print(
        f"| {tool} | {n} | {jitter} | {solve:.3f} | {'' if total is None else f'{total:.3f}'} "
        f"| {status} | {residual:.1e} | {met}/{len(fs)} "
        f"| {sum(k for k, _ in kept)}/{sum(t for _, t in kept)} |"
    )
print()
for tool, jitter in sorted({(t, j) for t, j, _ in summary}):
    sizes = sorted(n for t, j, n in summary if (t, j) == (tool, jitter) and summary[(t, j, n)][2])
    if len(sizes) < 2:
        print(f"- {tool}, jitter {jitter}: fewer than two sizes with every seed met; no exponent")
        continue
    a, b = sizes[-2], sizes[-1]
    (sa, ta, _), (sb, tb, _) = summary[(tool, jitter, a)], summary[(tool, jitter, b)]
    k = lambda x, y: math.log(y / x) / math.log(b / a) if x > 0 and y > 0 else float("nan")
    extra = f"; analysis+solve {k(ta, tb):.2f}" if ta is not None else ""
    print(f"- {tool}, jitter {jitter}: solve time ~ n^{k(sa, sb):.2f} (n = {a} -> {b}){extra}")
for tool, jitter in sorted({(t, j) for t, j, _ in summary}):
    sizes = sorted(n for t, j, n in summary if (t, j) == (tool, jitter))
    if len(sizes) >= 2:
        a, b = sizes[-2], sizes[-1]
        (sa, ta, _), (sb, tb, _) = summary[(tool, jitter, a)], summary[(tool, jitter, b)]
        k = math.log(sb / sa) / math.log(b / a)
        extra = f"; analysis+solve {math.log(tb / ta) / math.log(b / a):.2f}" if ta else ""
        print(
            f"- time to return, solved or not, {tool}, jitter {jitter}: "
            f"~ n^{k:.2f} (n = {a} -> {b}){extra}"
        )
