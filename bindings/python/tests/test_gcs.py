"""Tests of the Python bindings: the reports equal the CLI's JSON lines on every shipped
example (the "one API" proof), the typed attributes, errors, models built in code, the
Jacobian.

The CLI is `$GCS_CLI` when set, else `target/release/gcs` (or `$CARGO_TARGET_DIR/release/gcs`)
built by `cargo build --release -p gcs-cli`.
"""

import json
import os
import subprocess
import threading
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import List, Optional

import pytest

import gcs

ROOT = Path(__file__).resolve().parents[3]
DATA = ROOT / "data"


def cli_path() -> str:
    if os.environ.get("GCS_CLI"):
        return os.environ["GCS_CLI"]
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    exe = target / "release" / "gcs"
    if not exe.exists():
        subprocess.run(
            ["cargo", "build", "--release", "-q", "-p", "gcs-cli"], cwd=ROOT, check=True
        )
    return str(exe)


def cli_lines(*args: str) -> List[dict]:
    """The JSON lines of the CLI run in the repository root (so `file` fields match)."""
    out = subprocess.run(
        [cli_path(), *args, "--format", "json", "data"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert out.returncode in (0, 1), out.stderr
    return [json.loads(line) for line in out.stdout.splitlines()]


def example_files() -> List[str]:
    files = [
        p
        for p in DATA.rglob("*")
        if p.suffix.lower() in (".ron", ".slvs", ".fcstd", ".json")
    ]
    return sorted(str(p.relative_to(ROOT)).replace("\\", "/") for p in files)


@pytest.fixture(autouse=True)
def in_root(monkeypatch):
    monkeypatch.chdir(ROOT)


def python_lines(run) -> List[dict]:
    """What the bindings give for every model of every example file, in the CLI's order, a
    failure as the CLI's failure object would carry it."""
    lines = []
    for f in example_files():
        for model in gcs.load_all(f):
            try:
                lines.append(run(model).to_dict())
            except gcs.GcsError as e:
                lines.append({"file": f, "python_error": e.message})
    return lines


def compare(cli: List[dict], py: List[dict]) -> None:
    assert len(cli) == len(py) > 0
    for c, p in zip(cli, py):
        if "python_error" in p:
            # The CLI's message is "<file>[: <sketch>]: <the error>[: <a hint naming a flag>]",
            # the binding's the same without the hint.
            assert "error" in c, (c, p)
            assert p["python_error"] in c["error"], (c["error"], p["python_error"])
        else:
            assert c == p


def test_analyze_equals_cli_on_every_example():
    compare(cli_lines("analyze"), python_lines(lambda m: m.analyze()))


def test_analyze_options_equal_cli():
    args = ("analyze", "--structural", "--decompose", "--backend", "modp", "--seed", "7")
    compare(
        cli_lines(*args),
        python_lines(lambda m: m.analyze(backend="modp", structural=True, decompose=True, seed=7)),
    )


def test_solve_equals_cli_on_every_example():
    compare(cli_lines("solve"), python_lines(lambda m: m.solve()))


def test_check_equals_cli_on_every_example():
    compare(cli_lines("check"), python_lines(lambda m: m.check()))


def test_kite_typed_attributes():
    report = gcs.load("data/paper/kite.ron").analyze()
    assert isinstance(report, gcs.Report)
    assert (report.model, report.dim, report.rank, report.dof) == ("kite", 2, 5, 0)
    assert report.rigid and not report.well_constrained
    assert report.redundant[0].constraint == "c6"
    assert report.redundant[0].spanning_group == ["c1", "c2", "c3", "c4", "c5"]
    assert report.redundant[0].conflicting is False
    assert report.sketch.satisfied is True
    assert report.to_dict()["redundant"][0]["spanning_group"] == ["c1", "c2", "c3", "c4", "c5"]
    with pytest.raises(AttributeError):
        report.no_such_field
    with pytest.raises(AttributeError):
        report.dof = 3


def test_cad_sketches():
    models = gcs.load_all("data/cad/plate.FCStd")
    assert [m.name for m in models] == ["plate/Sketch"]
    plate = gcs.load("data/cad/plate.FCStd", sketch="plate/Sketch")
    report = plate.analyze()
    assert report.complete_import is True and report.skipped == []
    assert report.well_constrained and report.dof == 0
    with pytest.raises(gcs.ReadError) as e:
        gcs.load("data/cad/plate.FCStd", sketch="Sketch999")
    assert "plate/Sketch" in e.value.message and e.value.file == "data/cad/plate.FCStd"
    # Bytes work as well as files.
    data = Path("data/cad/plate.FCStd").read_bytes()
    again = gcs.loads(data, format="fcstd", file="data/cad/plate.FCStd").analyze()
    assert again == report


def test_read_errors_carry_file_line_column_id():
    text = 'System(dim: 2, entities: [Point(id: "p")],\n    constraints: [Fix(id: "f", a: "q")])'
    with pytest.raises(gcs.ReadError) as e:
        gcs.loads(text, file="bad.ron")
    err = e.value
    assert isinstance(err, gcs.GcsError)
    assert (err.file, err.line, err.id) == ("bad.ron", 2, "f")
    assert err.column is not None and err.column > 1
    assert 'unknown entity id "q"' in str(err)
    with pytest.raises(gcs.ReadError) as e:
        gcs.load("data/no_such_file.ron")
    assert e.value.file == "data/no_such_file.ron"
    with pytest.raises(gcs.ReadError) as e:
        gcs.loads("System(dim: 2, entities: [Point(id: \"p\", at: [0, 0]),", file="cut.ron")
    assert e.value.line == 1 and e.value.id is None
    with pytest.raises(ValueError):
        gcs.load("data/paper/kite.ron").analyze(backend="quantum")


def test_solve_errors_name_the_file():
    # 376 rectangles' points: 3008 unknowns, more than the solver is allowed here (3000).
    rect = "Point(id: \"a{i}\", at: [{x}, 0]), Point(id: \"b{i}\", at: [{y}, 0]), Point(id: \"c{i}\", at: [{y}, 1]), Point(id: \"d{i}\", at: [{x}, 1])"
    points = ", ".join(rect.format(i=i, x=2 * i, y=2 * i + 1) for i in range(376))
    model = gcs.loads(f"System(dim: 2, entities: [{points}])", file="big.ron")
    with pytest.raises(gcs.SolveError) as e:
        model.solve(max_unknowns=3000)
    assert e.value.file == "big.ron"
    assert e.value.message.startswith("big.ron: 3008 unknowns: more than the solver is allowed")
    assert isinstance(e.value, gcs.GcsError)


KITE = {
    "name": "kite",
    "dim": 2,
    "entities": [
        {"kind": "Point", "id": "p1", "at": [2, 7]},
        {"kind": "Point", "id": "p2", "at": [5, 6]},
        {"kind": "Point", "id": "p3", "at": [1, 1]},
        {"kind": "Point", "id": "p4", "at": [6, 3]},
    ],
    "constraints": [
        {"kind": "Distance", "id": "c1", "a": "p1", "b": "p2", "value": 3.1623},
        {"kind": "Distance", "id": "c2", "a": "p1", "b": "p3", "value": 6.0828},
        {"kind": "Distance", "id": "c3", "a": "p2", "b": "p4", "value": 3.1623},
        {"kind": "Distance", "id": "c4", "a": "p3", "b": "p4", "value": 5.3852},
        {"kind": "Distance", "id": "c5", "a": "p2", "b": "p3", "value": 6.4031},
        {"kind": "Distance", "id": "c6", "a": "p1", "b": "p4", "value": 5.6569},
    ],
}


def test_from_dict_is_the_file():
    built = gcs.Model.from_dict(KITE, file="data/paper/kite.ron")
    assert built.analyze() == gcs.load("data/paper/kite.ron").analyze()
    assert built.solve() == gcs.load("data/paper/kite.ron").solve()


@dataclass
class Point:
    id: str
    at: List[object]


@dataclass
class Distance:
    id: str
    a: str
    b: str
    value: Optional[object] = None


def test_from_dict_with_small_classes_and_exact_numbers():
    model = gcs.Model.from_dict(
        {
            "dim": 2,
            "entities": [Point("p", [0, 0]), Point("q", [Fraction(3, 1), "4"])],
            "constraints": [Distance("d", "p", "q", 5)],
        }
    )
    report = model.analyze()
    assert (report.rank, report.dof, report.witness) == (1, 0, "sketch")
    with pytest.raises(gcs.ReadError) as e:
        gcs.Model.from_dict({"dim": 2, "entities": [Point("p", [0, 0]), Point("p", [1, 0])]})
    assert e.value.id == "p"
    with pytest.raises(TypeError):
        gcs.Model.from_dict({"dim": 2, "entities": [object()]})


def test_jacobian_rank_is_the_reports():
    np = pytest.importorskip("numpy")
    pytest.importorskip("scipy")
    for f in ["data/paper/kite.ron", "data/sketches/rectangle_overdimensioned.ron",
              "data/paper/double_banana.ron", "data/sketches/block_3d.ron"]:
        model = gcs.load(f)
        report = model.analyze()
        j = model.jacobian()
        assert j.shape == (report.equations, report.unknowns)
        assert len(j.row_ids) == j.shape[0] and len(j.columns) == j.shape[1]
        dense = j.to_numpy()
        assert np.linalg.matrix_rank(dense) == report.rank, f
        sparse = j.to_scipy()
        assert sparse.shape == j.shape and sparse.nnz == len(j.values)
        assert (sparse.toarray() == dense).all()
    kite = gcs.load("data/paper/kite.ron").jacobian()
    assert kite.row_ids == ["c1", "c2", "c3", "c4", "c5", "c6"]
    assert kite.columns[:2] == ["p1[0]", "p1[1]"]


def test_threads_see_the_same_reports():
    # The GIL is released during analysis: threads run side by side and agree.
    model = gcs.load("data/paper/double_banana.ron")
    expected = model.analyze().to_dict()
    results = []
    threads = [
        threading.Thread(target=lambda: results.append(model.analyze().to_dict()))
        for _ in range(4)
    ]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == [expected] * 4


def test_to_ron_round_trips():
    model = gcs.load("data/sketches/flange.ron")
    again = gcs.loads(model.to_ron(), file="data/sketches/flange.ron")
    assert again.analyze() == model.analyze()
