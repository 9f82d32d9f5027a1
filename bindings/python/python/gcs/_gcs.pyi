"""Type stubs of the native module `gcs._gcs` (use the package `gcs` instead)."""

from typing import List, Optional, Tuple, Union

__version__: str
SCHEMA: int

class GcsError(Exception):
    message: str
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    id: Optional[str]
    element: Optional[str]

class ReadError(GcsError): ...
class AnalysisError(GcsError): ...
class SolveError(GcsError): ...

class NativeModel:
    @property
    def name(self) -> str: ...
    @property
    def dim(self) -> int: ...
    @property
    def file(self) -> str: ...
    def to_ron(self) -> str: ...
    def check_json(self) -> str: ...
    def analyze_json(
        self,
        backend: str = "exact",
        tolerance: float = 1e-9,
        seed: int = 1,
        structural: bool = False,
        decompose: bool = False,
    ) -> str: ...
    def solve_json(
        self, tolerance: float = 1e-9, max_iterations: int = 500, max_unknowns: int | None = None
    ) -> str: ...
    def jacobian(
        self, backend: str = "exact", tolerance: float = 1e-9, seed: int = 1
    ) -> Tuple[int, int, List[int], List[int], List[float], List[str], List[bool], List[str]]: ...

def load(path: str, sketch: Optional[str] = None, all: bool = False) -> List[NativeModel]: ...
def loads(
    data: Union[str, bytes],
    format: Optional[str] = None,
    file: str = "<string>",
    sketch: Optional[str] = None,
    all: bool = False,
) -> List[NativeModel]: ...
