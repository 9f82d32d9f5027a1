"""SolveSpace's solver (the Python binding python-solvespace, module python_solvespace) on
sketches written by `cargo run --release -p gcs-solve --example export_drawn` (JSON), for
benches/compare_solvers.sh: one line per file in the format of gcs's `solve_json` example.

Usage: $GCS_CMP_VENV/bin/python benches/compare_solvers.py FILE...
(GCS_CMP_VENV: the venv where python-solvespace is installed, default /work/venv-cmp;
VERBOSE=1: the diagnosis, dof() and failures(), on stderr; GCS_CMP_PIN=0: nothing held.)

The sketch, in a 2D workplane of group 1: a point per point in group 2; the `fixed` point
held by SolveSpace's "where dragged" constraint (locked at its drawing); a point-point
distance per distance; and the pinned coordinate by a horizontal (axis y) or vertical
(axis x) constraint between the pinned point and a point of group 1 (not solved) at the
pinned value. Solved in group 2 from the drawing with the library's defaults.
"""

import json
import os
import sys
import time

try:
    import python_solvespace as slvs
    from python_solvespace import Constraint, Entity, SolverSystem
except ImportError:
    venv = os.environ.get("GCS_CMP_VENV", "/work/venv-cmp")
    sys.exit(
        f"compare_solvers.py: python_solvespace not importable; run this with "
        f"{venv}/bin/python after `python3 -m venv {venv} && "
        f"{venv}/bin/pip install python-solvespace` (or set GCS_CMP_VENV)"
    )

try:
    from importlib.metadata import version

    VERSION = version("python-solvespace")
except Exception:  # pragma: no cover
    VERSION = getattr(slvs, "__version__", "?")


def triangles(n, edges):
    """The triangles of the graph of distances: triples a < b < c joined pairwise."""
    adjacent = [set() for _ in range(n)]
    for u, v in edges:
        if u != v:
            adjacent[u].add(v)
            adjacent[v].add(u)
    out = []
    for a in range(n):
        for b in adjacent[a]:
            if b <= a:
                continue
            for c in adjacent[b]:
                if c > b and c in adjacent[a]:
                    out.append((a, b, c))
    return out


def turn(p, a, b, c):
    return (p[b][0] - p[a][0]) * (p[c][1] - p[a][1]) - (p[b][1] - p[a][1]) * (p[c][0] - p[a][0])


def run(path):
    with open(path) as f:
        sketch = json.load(f)
    points, distances = sketch["points"], sketch["distances"]
    pin = sketch["pin"]
    t = time.perf_counter()
    s = SolverSystem()
    s.set_group(1)
    wp = s.create_2d_base()
    a, b = points[pin["from"]], points[pin["point"]]
    if pin["axis"] == "y":
        anchor = s.add_point_2d(b[0], a[1] + pin["offset"], wp)
    else:
        anchor = s.add_point_2d(a[0] + pin["offset"], b[1], wp)
    s.set_group(2)
    handles = [s.add_point_2d(x, y, wp) for x, y in points]
    names = {}  # constraint handle (its place, from 1) -> name

    def named(name):
        names[s.cons_len()] = name

    pinned = os.environ.get("GCS_CMP_PIN", "1") != "0"
    for k in sketch["fixed"] if pinned else []:
        s.dragged(handles[k], wp)
        named(f"fix{k}")
    for k, (i, j, value) in enumerate(distances):
        s.distance(handles[i], handles[j], value, wp)
        named(f"d{k}")
    if pinned:
        kind = Constraint.HORIZONTAL if pin["axis"] == "y" else Constraint.VERTICAL
        s.add_constraint(kind, wp, 0.0, handles[pin["point"]], anchor, Entity.NONE, Entity.NONE)
        named("pin")
    setup = time.perf_counter() - t
    t = time.perf_counter()
    result = s.solve()
    solve = time.perf_counter() - t
    x = [s.params(h.params) for h in handles]
    residual = max(
        abs(((x[i][0] - x[j][0]) ** 2 + (x[i][1] - x[j][1]) ** 2) ** 0.5 - v) for i, j, v in distances
    )
    tri = triangles(len(points), [(i, j) for i, j, _ in distances])
    kept = sum(1 for a, b, c in tri if turn(points, a, b, c) * turn(x, a, b, c) > 0)
    if os.environ.get("VERBOSE"):
        failed = [names.get(h, str(h)) for h in s.failures()]
        print(
            f"slvs {VERSION} {sketch['name']}: result {result.name} dof {s.dof()} failures {failed}",
            file=sys.stderr,
        )
    print(
        f"tool=slvs{'' if pinned else '-free'} n={len(points)} seed={sketch['seed']} jitter={sketch['jitter']} "
        f"setup={setup:.3f}s solve={solve:.3f}s status={result.name} "
        f"max_residual={residual:.1e} orientation_kept={kept}/{len(tri)}",
        flush=True,
    )


for path in sys.argv[1:]:
    run(path)
