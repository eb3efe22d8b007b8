# Copyright (c) 2026 CGAL Trivial Connections contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Type stubs of the module trivial_connections (python/trivial_connections_module.cpp), shipped beside it: copied
# into build/python by the build and installed next to the module by cmake --install and pip install. Checked by
# ctest python_typing (Debian's mypy: a typed use of the module, then stubtest against the module itself).
# Keep in step with the binding: every public name here has its docstring there.

import os
from fractions import Fraction
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
MAX_SYMMETRY_ORDER: int
DEFAULT_FEATURE_ANGLE: float
DEFAULT_FEATURE_SMOOTHING: int

# A file name: str, bytes or os.PathLike (pathlib.Path)
_StrPath = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
# A singularity index: exact (int, Fraction or "p/q"), never a float
_Index = Union[int, Fraction, str, np.integer[Any]]
# {vertex: index}, pairs (vertex, index), or a (k, 2) integer array
_Singularities = Union[Mapping[int, _Index], Sequence[Tuple[int, _Index]], npt.NDArray[Any]]
# per face one direction ((m, 3) array-like) or {face: (3,) vector}
_FaceDirections = Union[npt.ArrayLike, Mapping[int, npt.ArrayLike]]
# progress(phase, fraction): phase names as trivial_connections' phase_name() ("factorization", "solve", ...)
_Progress = Callable[[str, float], object]

class InvalidInput(ValueError):
    code: str
    where: Optional[int]

class Result:
    @property
    def connection(self) -> npt.NDArray[np.float64]: ...
    @property
    def edges(self) -> npt.NDArray[np.int64]: ...
    @property
    def field(self) -> npt.NDArray[np.float64]: ...
    @property
    def directions(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def n(self) -> int: ...
    @property
    def energy(self) -> float: ...
    @property
    def guidance_energy(self) -> float: ...
    @property
    def max_residual(self) -> float: ...
    @property
    def max_loop_residual(self) -> float: ...
    @property
    def loop_periods(self) -> List[int]: ...
    @property
    def boundary_indices(self) -> Dict[int, Fraction]: ...
    @property
    def integers_proven_optimal(self) -> bool: ...
    @property
    def energy_lower_bound(self) -> float: ...
    @property
    def rounding_energy(self) -> float: ...
    @property
    def constraints(self) -> List[Dict[str, Any]]: ...
    @property
    def guidance(self) -> List[Dict[str, Any]]: ...
    @property
    def timings(self) -> Dict[str, float]: ...

class Solver:
    def __init__(
        self,
        V: npt.ArrayLike,
        F: npt.ArrayLike,
        *,
        weights: str = "hodge",
        backend: str = "auto",
        constrained_faces: Optional[Sequence[int]] = None,
        guided_faces: Optional[Sequence[int]] = None,
        guidance_weight: float = 1.0,
        align_boundary: bool = False,
        align_features: Union[None, bool, float] = None,
        feature_smoothing: int = 3,
        feature_n: int = 4,
        progress: Optional[_Progress] = None,
    ) -> None: ...
    @staticmethod
    def from_file(
        path: _StrPath,
        triangulate: bool = False,
        *,
        weights: str = "hodge",
        backend: str = "auto",
        constrained_faces: Optional[Sequence[int]] = None,
        guided_faces: Optional[Sequence[int]] = None,
        guidance_weight: float = 1.0,
        align_boundary: bool = False,
        align_features: Union[None, bool, float] = None,
        feature_smoothing: int = 3,
        feature_n: int = 4,
        progress: Optional[_Progress] = None,
    ) -> Solver: ...
    def solve(
        self,
        singularities: Optional[_Singularities],
        n: int = 1,
        directions: Optional[_FaceDirections] = None,
        loop_periods: Optional[Sequence[Optional[int]]] = None,
        *,
        all_directions: bool = True,
        progress: Optional[_Progress] = None,
    ) -> Result: ...
    def set_constraints(
        self, constrained_faces: Optional[Sequence[int]] = None, guided_faces: Optional[Sequence[int]] = None
    ) -> Dict[str, Any]: ...
    def place_singularities(
        self,
        *,
        n: int = 1,
        align_boundary: bool = False,
        alignment_guide: Optional[_FaceDirections] = None,
        alignment_strength: float = 100.0,
        fixed_singularities: Optional[_Singularities] = None,
        loop_periods: Optional[Sequence[Optional[int]]] = None,
        directions: Optional[_FaceDirections] = None,
        progress: Optional[_Progress] = None,
    ) -> Tuple[Dict[int, Fraction], Dict[str, Any]]: ...
    def principal_curvature_guide(self) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def spread_guided_faces(self, guide: _FaceDirections, count: int) -> List[int]: ...
    def refine_singularities(
        self,
        singularities: _Singularities,
        *,
        n: int = 1,
        directions: Optional[_FaceDirections] = None,
        loop_periods: Optional[Sequence[Optional[int]]] = None,
        fixed_vertices: Optional[Sequence[int]] = None,
        cancel_pairs: bool = False,
        maximum_trials: Optional[int] = None,
        progress: Optional[_Progress] = None,
    ) -> Tuple[Dict[int, Fraction], Dict[str, Any]]: ...
    def trace_streamlines(
        self,
        result: Result,
        singularities: Optional[_Singularities],
        seed_faces: Optional[Sequence[int]] = None,
        maximum_faces_per_ray: int = 0,
    ) -> List[npt.NDArray[np.float64]]: ...
    def quad_mesh(
        self,
        result: Result,
        singularities: Optional[_Singularities],
        quad_size: Optional[float] = None,
        target_faces: Optional[int] = None,
        rounding: str = "greedy",
        max_quads: float = 1e7,
        feature_edges: Optional[Union[npt.ArrayLike, Sequence[Tuple[int, int]]]] = None,
        scale_smoothness: float = 0.0,
        untangle: bool = True,
        cone_mode_weight: float = 0.0,
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], Dict[str, Any]]: ...
    def move_singularities_off_features(
        self,
        singularities: Optional[_Singularities],
        feature_edges: Union[npt.ArrayLike, Sequence[Tuple[int, int]]],
        quad_size: Optional[float] = None,
        target_faces: Optional[int] = None,
        fixed_vertices: Optional[Sequence[int]] = None,
    ) -> Tuple[Dict[int, Fraction], Dict[str, Any]]: ...
    def write_field(self, path: _StrPath, result: Result, singularities: Optional[_Singularities]) -> None: ...
    @property
    def feature_pins(self) -> Optional[Tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]]: ...
    @property
    def feature_alignment(self) -> Optional[Dict[str, Any]]: ...
    @property
    def loops(self) -> List[Dict[str, Any]]: ...
    @property
    def build_timings(self) -> Dict[str, float]: ...
    @property
    def number_of_vertices(self) -> int: ...
    @property
    def number_of_faces(self) -> int: ...
    @property
    def topology(self) -> List[Dict[str, Any]]: ...
    @property
    def number_of_loops(self) -> int: ...
    @property
    def backend(self) -> str: ...
    @property
    def edges(self) -> npt.NDArray[np.int64]: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def faces(self) -> npt.NDArray[np.int64]: ...
    @property
    def weights(self) -> npt.NDArray[np.float64]: ...

def read_mesh(path: _StrPath, triangulate: bool = False) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
def repair_mesh(path: _StrPath) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], Dict[str, int]]: ...
def read_singularities(path: _StrPath, number_of_vertices: Optional[int] = None) -> Dict[int, Fraction]: ...
def write_singularities(path: _StrPath, singularities: _Singularities) -> None: ...
def read_face_directions(
    path: _StrPath, number_of_faces: Optional[int] = None
) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]: ...
def write_face_directions(
    path: _StrPath, faces: Union[Sequence[int], Mapping[int, npt.ArrayLike]], directions: Optional[npt.ArrayLike] = None
) -> None: ...
def feature_aligned_faces(
    V: npt.ArrayLike, F: npt.ArrayLike, threshold: float = 30.0, *, n: int = 4, smoothing: int = 3
) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.float64], Dict[str, Any]]: ...
def feature_curves(
    V: npt.ArrayLike, F: npt.ArrayLike, threshold: float = 30.0
) -> Tuple[List[npt.NDArray[np.int64]], Dict[str, Any]]: ...
def write_streamlines(path: _StrPath, lines: List[npt.NDArray[np.float64]]) -> None: ...
