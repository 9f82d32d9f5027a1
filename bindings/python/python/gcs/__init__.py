"""gcs: exact analysis of geometric constraint systems (CAD sketches), from Python.

Read a model (a gcs RON model, or a sketch of a SolveSpace ``.slvs``, FreeCAD ``.FCStd`` or
Onshape JSON file), analyse it at a witness, solve it at its values::

    import gcs
    model = gcs.load("data/paper/kite.ron")
    report = model.analyze()
    report.dof                          # 0
    report.redundant[0].constraint      # 'c6'
    report.redundant[0].spanning_group  # ['c1', 'c2', 'c3', 'c4', 'c5']
    report.to_dict()                    # the line of `gcs analyze --format json`, parsed

Everything is computed by the Rust crates of gcs through the functions the ``gcs`` binary
calls; the reports cross as the CLI's JSON lines (docs/format.md §2–§4), so this module and
the CLI cannot disagree. The GIL is released while a model is read, analysed or solved.
"""

from __future__ import annotations

import dataclasses
import json
import math
from decimal import Decimal
from fractions import Fraction
from typing import Any, Dict, Iterable, List, Optional, Tuple, Union

from . import _gcs
from ._gcs import SCHEMA, AnalysisError, GcsError, ReadError, SolveError, __version__

__all__ = [
    "load",
    "load_all",
    "loads",
    "Model",
    "Record",
    "Report",
    "SolveReport",
    "CheckReport",
    "Jacobian",
    "GcsError",
    "ReadError",
    "AnalysisError",
    "SolveError",
    "SCHEMA",
    "__version__",
]


class Record:
    """A JSON object of a report with its fields as attributes.

    ``record.dof`` is ``record.to_dict()["dof"]``; nested objects are records too, lists of
    objects lists of records. A field the report does not have raises ``AttributeError`` (some
    are present only in some reports: docs/format.md says which).
    """

    __slots__ = ("_data",)

    def __init__(self, data: Dict[str, Any]) -> None:
        object.__setattr__(self, "_data", data)

    def __getattr__(self, name: str) -> Any:
        try:
            return _wrap(self._data[name])
        except KeyError:
            raise AttributeError(
                f"{type(self).__name__} has no field {name!r} (fields: {', '.join(self._data)})"
            ) from None

    def __getitem__(self, name: str) -> Any:
        return _wrap(self._data[name])

    def __contains__(self, name: str) -> bool:
        return name in self._data

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("reports are read-only: use to_dict() for a copy to change")

    def __dir__(self) -> Iterable[str]:
        return list(self._data) + ["to_dict", "to_json"]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Record) and self._data == other._data

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._data!r})"

    def to_dict(self) -> Dict[str, Any]:
        """The object as plain data (a deep copy): equal to the parsed JSON line."""
        return json.loads(json.dumps(self._data))

    def to_json(self) -> str:
        """The object as one line of JSON."""
        return json.dumps(self._data, ensure_ascii=False)


def _wrap(value: Any) -> Any:
    if isinstance(value, dict):
        return Record(value)
    if isinstance(value, list):
        return [_wrap(v) for v in value]
    return value


class Report(Record):
    """The report of :meth:`Model.analyze`: the line of ``gcs analyze --format json``."""

    __slots__ = ()


class SolveReport(Record):
    """The report of :meth:`Model.solve`: the line of ``gcs solve --format json``."""

    __slots__ = ()


class CheckReport(Record):
    """The counts of :meth:`Model.check`: the line of ``gcs check --format json``."""

    __slots__ = ()


@dataclasses.dataclass(frozen=True)
class Jacobian:
    """The Jacobian of the constraint equations at the witness of the analysis.

    Its nonzero entries as coordinates (``rows[k]``, ``cols[k]``, ``values[k]``: the exact
    entries rounded to doubles); ``row_ids[i]`` is the constraint of row ``i`` (or the entity
    of an entity-internal row, ``row_internal[i]``), ``columns[j]`` names the coordinate of
    column ``j`` (``"p1[0]"``: the first coordinate of ``p1``).
    """

    shape: Tuple[int, int]
    rows: List[int]
    cols: List[int]
    values: List[float]
    row_ids: List[str]
    row_internal: List[bool]
    columns: List[str]

    def to_numpy(self) -> Any:
        """A dense ``numpy.ndarray`` (needs NumPy)."""
        import numpy as np

        a = np.zeros(self.shape)
        a[self.rows, self.cols] = self.values
        return a

    def to_scipy(self) -> Any:
        """A ``scipy.sparse.csr_matrix`` (needs SciPy)."""
        import scipy.sparse as sp

        return sp.csr_matrix((self.values, (self.rows, self.cols)), shape=self.shape)


class Model:
    """One model: a gcs RON model, or one sketch of a CAD file.

    Read it with :func:`load`, :func:`loads` or :meth:`Model.from_dict`.
    """

    __slots__ = ("_native",)

    def __init__(self, native: "_gcs.NativeModel") -> None:
        self._native = native

    @property
    def name(self) -> str:
        """The model's name (a CAD sketch's name)."""
        return self._native.name

    @property
    def dim(self) -> int:
        """2 or 3."""
        return self._native.dim

    @property
    def file(self) -> str:
        """The file it was read from, as given: the reports' ``file``."""
        return self._native.file

    def __repr__(self) -> str:
        return f"Model(name={self.name!r}, dim={self.dim}, file={self.file!r})"

    def to_ron(self) -> str:
        """The model as RON text (docs/format.md §1)."""
        return self._native.to_ron()

    def check(self) -> CheckReport:
        """The counts of ``gcs check``: entities, constraints, DOF and DOC sums, naive DOF."""
        return CheckReport(json.loads(self._native.check_json()))

    def analyze(
        self,
        backend: str = "exact",
        structural: bool = False,
        decompose: bool = False,
        seed: int = 1,
        tolerance: float = 1e-9,
    ) -> Report:
        """The witness analysis, as ``gcs analyze --format json`` gives it.

        ``backend``: ``exact`` (proven), ``rational``, ``modp``, ``float`` (with ``tolerance``)
        or ``rug`` (when built in). ``structural`` adds the counting methods' section,
        ``decompose`` the W-decomposition of every cluster. Raises :class:`AnalysisError`
        when the model cannot be analysed (no exact witness: try ``backend="float"``).
        """
        line = self._native.analyze_json(backend, tolerance, seed, structural, decompose)
        return Report(json.loads(line))

    def solve(
        self, tolerance: float = 1e-9, max_iterations: int = 500, max_unknowns: int | None = None
    ) -> SolveReport:
        """The solve at the values from the drawing, as ``gcs solve --format json`` gives it:
        the status, the solved entities, each redundant constraint consistent or conflicting.
        ``max_unknowns`` bounds the size of the model the solver takes (default: the solver's);
        a larger model raises :class:`SolveError`.
        """
        line = self._native.solve_json(tolerance, max_iterations, max_unknowns)
        return SolveReport(json.loads(line))

    def jacobian(self, backend: str = "exact", seed: int = 1, tolerance: float = 1e-9) -> Jacobian:
        """The Jacobian at the witness the analysis with these options takes (its rank is the
        report's ``rank``). ``.to_numpy()`` / ``.to_scipy()`` convert it."""
        nrows, ncols, rows, cols, values, row_ids, internal, columns = self._native.jacobian(
            backend, tolerance, seed
        )
        return Jacobian((nrows, ncols), rows, cols, values, row_ids, internal, columns)

    @classmethod
    def from_dict(cls, model: Dict[str, Any], file: str = "<dict>") -> "Model":
        """A model built in code, with the fields of the RON format (docs/format.md §1)::

            gcs.Model.from_dict({
                "name": "bar", "dim": 2,
                "entities": [{"kind": "Point", "id": "p", "at": [0, 0]},
                             {"kind": "Point", "id": "q", "at": [3, 4]}],
                "constraints": [{"kind": "Distance", "id": "d", "a": "p", "b": "q", "value": 5}],
            })

        An entity or constraint is a dict with its ``kind`` (the RON variant name) and fields,
        or a dataclass instance (its class name is the kind unless it has a ``kind`` field).
        Numbers: ``int``, ``float`` (read as its shortest decimal, as a RON file's numbers
        are), ``Fraction`` and ``Decimal`` exactly, or strings (``"1/3"``). The model is
        validated as a file is; errors name the id at fault.
        """
        return loads(_to_ron(model), format="ron", file=file)


def _to_ron(model: Dict[str, Any]) -> str:
    """The RON text of a model given as plain data (a syntax conversion only: the reader of
    gcs-model validates it)."""
    if not isinstance(model, dict):
        raise TypeError(f"a model is a dict, not {type(model).__name__}")
    unknown = set(model) - {"name", "dim", "entities", "constraints"}
    if unknown:
        raise ValueError(f"unknown model fields: {', '.join(sorted(unknown))}")
    fields = []
    if model.get("name") is not None:
        fields.append(f"name: {_ron_value(model['name'])}")
    fields.append(f"dim: {_ron_value(model.get('dim'))}")
    for key in ("entities", "constraints"):
        items = [_ron_item(item, key) for item in model.get(key, ())]
        fields.append(f"{key}: [{', '.join(items)}]")
    return f"System({', '.join(fields)})"


def _ron_item(item: Any, where: str) -> str:
    if dataclasses.is_dataclass(item) and not isinstance(item, type):
        data = dataclasses.asdict(item)
        kind = data.pop("kind", None) or type(item).__name__
    elif isinstance(item, dict):
        data = dict(item)
        kind = data.pop("kind", None)
    else:
        raise TypeError(f"{where}: expected a dict or a dataclass, not {type(item).__name__}")
    if not isinstance(kind, str) or not kind.isidentifier():
        raise ValueError(f"{where}: {item!r} has no kind (such as 'Point' or 'Distance')")
    parts = [f"{k}: {_ron_value(v)}" for k, v in data.items() if v is not None]
    return f"{kind}({', '.join(parts)})"


def _ron_value(v: Any) -> str:
    if isinstance(v, bool):
        raise TypeError("a model holds no booleans")
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"not a finite number: {v}")
        return repr(v)
    if isinstance(v, Fraction):
        return f'"{v.numerator}/{v.denominator}"'
    if isinstance(v, Decimal):
        return f'"{v}"'
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, (list, tuple)):
        return f"[{', '.join(_ron_value(x) for x in v)}]"
    raise TypeError(f"cannot write {type(v).__name__} in a model")


def load(path: str, sketch: Optional[str] = None) -> Model:
    """The model of a file: a gcs ``.ron`` model, or a sketch of a ``.slvs``, ``.FCStd`` or
    Onshape ``.json`` file (recognised by extension, then content). A CAD file with several
    sketches needs ``sketch`` (the model name); :func:`load_all` reads them all."""
    return Model(_gcs.load(str(path), sketch, False)[0])


def load_all(path: str) -> List[Model]:
    """Every model of a file: one for a ``.ron`` model, one per sketch of a CAD file."""
    return [Model(m) for m in _gcs.load(str(path), None, True)]


def loads(
    data: Union[str, bytes],
    format: Optional[str] = "ron",
    file: str = "<string>",
    sketch: Optional[str] = None,
) -> Model:
    """The model of a text or bytes: ``format`` is ``ron``, ``slvs``, ``fcstd`` or
    ``onshape`` (``None``: recognised by ``file``'s extension, then content); ``file`` names
    it in reports and errors."""
    return Model(_gcs.loads(data, format, file, sketch, False)[0])

