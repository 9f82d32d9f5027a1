"""Type stubs of `gcs`: the fields of the reports are those of docs/format.md §2–§4 (the
normative ones typed here; every field of the JSON line is an attribute). `Redundant`,
`Cluster` and `Checked` name the shapes of nested objects for type checkers only: at run time
they are `Record`s."""

from dataclasses import dataclass
from typing import Any, Dict, Iterable, List, Optional, Tuple, Union

from ._gcs import SCHEMA as SCHEMA
from ._gcs import AnalysisError as AnalysisError
from ._gcs import GcsError as GcsError
from ._gcs import ReadError as ReadError
from ._gcs import SolveError as SolveError
from ._gcs import __version__ as __version__

class Record:
    def __init__(self, data: Dict[str, Any]) -> None: ...
    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, name: str) -> Any: ...
    def __contains__(self, name: str) -> bool: ...
    def __dir__(self) -> Iterable[str]: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def to_json(self) -> str: ...

class Redundant(Record):
    constraint: str
    rows: int
    doc: int
    spanning_group: List[str]

class Cluster(Record):
    entities: List[str]
    constraints: List[str]

class Report(Record):
    schema: int
    model: str
    file: str
    dim: int
    backend: str
    witness: str
    entities: int
    constraints: int
    unknowns: int
    equations: int
    rank: int
    dof_absolute: int
    trivial_motions: int
    dof: int
    rigid: bool
    well_constrained: bool
    redundant: List[Redundant]
    clusters: List[Cluster]
    seed: int

class Checked(Record):
    constraint: str
    residual: float
    allowance: float
    conflicting: bool
    spanning_group: List[str]

class SolveReport(Record):
    schema: int
    model: str
    file: str
    status: str
    max_residual: float
    moved: float
    entities: List[Record]
    conflicting: List[Checked]
    redundant: List[Checked]
    tolerance: float
    scale: float
    iterations: int
    analysis_backend: str

class CheckReport(Record):
    schema: int
    model: str
    file: str
    dim: int
    entities: int
    constraints: int
    entity_dof: int
    constraint_doc: int
    naive_dof: int
    displacements: int

@dataclass(frozen=True)
class Jacobian:
    shape: Tuple[int, int]
    rows: List[int]
    cols: List[int]
    values: List[float]
    row_ids: List[str]
    row_internal: List[bool]
    columns: List[str]
    def to_numpy(self) -> Any: ...
    def to_scipy(self) -> Any: ...

class Model:
    @property
    def name(self) -> str: ...
    @property
    def dim(self) -> int: ...
    @property
    def file(self) -> str: ...
    def to_ron(self) -> str: ...
    def check(self) -> CheckReport: ...
    def analyze(
        self,
        backend: str = "exact",
        structural: bool = False,
        decompose: bool = False,
        seed: int = 1,
        tolerance: float = 1e-9,
    ) -> Report: ...
    def solve(
        self, tolerance: float = 1e-9, max_iterations: int = 500, max_unknowns: int | None = None
    ) -> SolveReport: ...
    def jacobian(self, backend: str = "exact", seed: int = 1, tolerance: float = 1e-9) -> Jacobian: ...
    @classmethod
    def from_dict(cls, model: Dict[str, Any], file: str = "<dict>") -> Model: ...

def load(path: str, sketch: Optional[str] = None) -> Model: ...
def load_all(path: str) -> List[Model]: ...
def loads(
    data: Union[str, bytes],
    format: Optional[str] = "ron",
    file: str = "<string>",
    sketch: Optional[str] = None,
) -> Model: ...
