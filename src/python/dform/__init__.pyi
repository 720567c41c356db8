# SPDX-License-Identifier: GPL-3.0-or-later
# Type stubs of the package dform (docs/python.md); tests/python/test_stubs.py checks them against
# the module with mypy's stubtest, and their keyword arguments against the settings table's rows.
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str
__all__ = ["Error", "Result", "__version__", "forward", "inverse", "read_curve", "read_outline"]

_ArrayLike = npt.ArrayLike
_Floats = npt.NDArray[np.float64]
_Ints = npt.NDArray[np.int32]

class Error(RuntimeError):
    exit_code: int

class _Piece(TypedDict):
    name: str
    flat: _Floats
    shape: _Floats
    faces: _Ints
    seam: _Ints

class _Check(TypedDict):
    name: str
    value: float
    limit: float
    verdict: str
    detail: str

class _Outline(TypedDict):
    outline: _Floats
    holes: List[_Floats]
    creases: List[_Floats]

class Result:
    def __init__(self, run: Any, call: Tuple[str, Tuple[Any, ...], Dict[str, Any]]) -> None: ...
    @property
    def model(self) -> str: ...
    @property
    def model_reason(self) -> str: ...
    @property
    def piece_a(self) -> _Piece: ...
    @property
    def piece_b(self) -> _Piece: ...
    @property
    def figures(self) -> Dict[str, Any]: ...
    @property
    def messages(self) -> List[Tuple[str, str]]: ...
    @property
    def target(self) -> Optional[_Floats]: ...
    def export(
        self,
        out_dir: str,
        *,
        profile: str = ...,
        sheet: Optional[str] = ...,
        page: Optional[str] = ...,
        scale: Union[float, str] = ...,
        tab_width: float = ...,
        tabs: Optional[str] = ...,
        tick_spacing: float = ...,
        joint: Optional[str] = ...,
        material: Optional[str] = ...,
        kerf: Optional[float] = ...,
        hole_spacing: Optional[float] = ...,
        hole_diameter: Optional[float] = ...,
        hole_edge: Optional[float] = ...,
        slot_length: Optional[float] = ...,
        score_folds: Optional[float] = ...,
        numbers: Optional[str] = ...,
        hinge: Optional[bool] = ...,
        title: bool = ...,
        gltf: bool = ...,
        cutting_files: bool = ...,
        export_anyway: bool = ...,
        gate: str = ...,
    ) -> Dict[str, Any]: ...
    def __getstate__(self) -> Dict[str, Any]: ...
    def __setstate__(self, state: Dict[str, Any]) -> None: ...
    def __eq__(self, other: object) -> bool: ...

def forward(
    outline_a: _ArrayLike,
    outline_b: _ArrayLike,
    *,
    holes_a: Sequence[_ArrayLike] = ...,
    holes_b: Sequence[_ArrayLike] = ...,
    creases_a: Sequence[_ArrayLike] = ...,
    creases_b: Sequence[_ArrayLike] = ...,
    name_a: str = ...,
    name_b: str = ...,
    model: str = ...,
    join: str = ...,
    start_a: Union[float, Mapping[str, Any]] = ...,
    start_b: Union[float, Mapping[str, Any]] = ...,
    interior_edge: float = ...,
    flip: bool = ...,
    fit_perimeter: bool = ...,
    perimeter_tolerance: float = ...,
    weights: Optional[Mapping[str, float]] = ...,
    resolution: int = ...,
    max_iterations: int = ...,
    function_tolerance: float = ...,
    gradient_tolerance: float = ...,
) -> Result: ...
def inverse(
    curve: _ArrayLike,
    *,
    name: str = ...,
    closed: bool = ...,
    weights: Optional[Mapping[str, float]] = ...,
    resolution: int = ...,
    max_iterations: int = ...,
    function_tolerance: float = ...,
    gradient_tolerance: float = ...,
) -> Result: ...
def read_outline(path: str) -> _Outline: ...
def read_curve(path: str) -> _Floats: ...
