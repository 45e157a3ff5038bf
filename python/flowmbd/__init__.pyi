"""Type stub of the public ``flowmbd`` API."""

from typing import Any, Callable, Iterable, List, Mapping, Optional, Sequence, Union

from . import beam as beam
from . import belt as belt
from . import reduce as reduce
from . import string as string
from . import tire as tire

__version__: str

Grid = Union[Mapping[str, Sequence[Any]], Iterable[Mapping[str, Any]]]

class NumericalError(RuntimeError):
    partial: Optional[Any]
    def __init__(self, message: str, partial: Optional[Any] = ...) -> None: ...

class Result(dict):
    def records(self) -> str: ...
    def to_dataframe(
        self, records: Optional[str] = ..., explode: Optional[str] = ...
    ) -> Any: ...  # pandas.DataFrame

def points(grid: Grid) -> List[dict]: ...
def sweep(
    fn: Callable[..., Any],
    grid: Grid,
    client: Any = ...,
    *,
    progress: bool = ...,
    select: Optional[Mapping[str, Union[str, Callable[[Any], Any]]]] = ...,
    explode: Optional[str] = ...,
) -> Any: ...  # pandas.DataFrame
