"""Type stubs of the mcws extension module (lengths in the robot's length unit, joint values in
rad or that length unit; see the docstrings, help(mcws.Robot) & co.)."""

import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, bytes, "os.PathLike[str]"]
_Floats = npt.ArrayLike

class Error(RuntimeError): ...
class UsageError(Error, ValueError): ...

def _parse_length(text: str, name: str, robot: "Robot", allow_zero: bool) -> float: ...

class Robot:
    def __init__(
        self,
        path: _Path,
        *,
        base: Optional[str] = None,
        tip: Optional[str] = None,
        package_path: Union[_Path, Sequence[_Path], None] = None,
        srdf: Optional[_Path] = None,
    ) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def path(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def joint_types(self) -> List[str]: ...
    @property
    def joint_units(self) -> List[str]: ...
    @property
    def limits(self) -> npt.NDArray[np.float64]: ...
    @property
    def length_unit(self) -> str: ...
    @property
    def has_collision_model(self) -> bool: ...
    def fk(self, q: _Floats, frame: str = "tool", check_limits: bool = True) -> npt.NDArray[np.float64]: ...
    def jacobian(self, q: _Floats) -> npt.NDArray[np.float64]: ...
    def ik(
        self,
        pose: _Floats,
        q0: Optional[_Floats] = None,
        position_only: bool = False,
        *,
        free_roll: bool = False,
        tolerance: float = 1e-6,
        seed: int = 1,
    ) -> Optional[npt.NDArray[np.float64]]: ...

def sample(
    robot: Robot,
    n: int,
    seed: int = 0,
    threads: int = 0,
    fix: Optional[Dict[str, float]] = None,
    collision: bool = False,
    quality: bool = False,
    *,
    point: str = "tool",
    quality_task: Optional[str] = None,
    length: Optional[float] = None,
    progress: Any = None,
) -> npt.NDArray[np.void]: ...
def sample_shape(
    shape: str, n: int, seed: int = 0, threads: int = 0, *, progress: Any = None
) -> npt.NDArray[np.void]: ...
def read_pcd(path: _Path) -> npt.NDArray[np.void]: ...
def read_provenance(path: _Path) -> Optional[Dict[str, Any]]: ...
def _point_dtype(joints: int, quality: bool) -> np.dtype: ...
def _write_points(
    path: _Path,
    points: npt.NDArray[np.void],
    quality: bool,
    joints: int,
    robot: Optional[Robot],
    provenance: Optional[Dict[str, Any]],
    sampling: Optional[Dict[str, Any]],
) -> None: ...
def _boundary(
    xyz: npt.NDArray[np.float32],
    plane: Optional[str],
    method: str,
    radius: Optional[float],
    auto_radius: Optional[float],
    adaptive: Optional[int],
    outer_radius: Optional[float],
    min_gap: Optional[float],
    hull_depth: Optional[float],
    cell: Optional[float],
    gap: Optional[float],
    threads: int,
) -> npt.NDArray[np.bool_]: ...
def _boundary_tiled(
    path: str,
    plane: Optional[str],
    method: str,
    radius: Optional[float],
    auto_radius: Optional[float],
    adaptive: Optional[int],
    outer_radius: Optional[float],
    min_gap: Optional[float],
    hull_depth: Optional[float],
    cell: Optional[float],
    gap: Optional[float],
    threads: int,
    tiles: int,
    progress: Any,
) -> npt.NDArray[np.bool_]: ...
def _measure(
    xyz: npt.NDArray[np.float32],
    plane: Optional[str],
    alpha: Optional[float],
    correction: str,
    threads: int,
    length_unit: Optional[str],
    robot: Optional[Robot],
    provenance: Optional[Dict[str, Any]],
    method: str,
    leave_one_out: Optional[str],
    triangulate: Optional[str],
    boundary: Optional[npt.NDArray[np.float32]],
    column_width: Optional[float],
) -> str: ...
def _refine(
    robot: Robot,
    records: npt.NDArray[np.void],
    joints: int,
    n: int,
    seed: int,
    threads: int,
    spread: float,
    point: str,
    fix: Optional[Dict[str, float]],
    collision: bool,
    progress: Any,
) -> npt.NDArray[np.void]: ...

class _Envelope:
    def summary(self) -> str: ...
    def vertices(self) -> npt.NDArray[np.float64]: ...
    def triangles(self) -> npt.NDArray[np.uint32]: ...
    def save(self, path: _Path, source: str) -> None: ...
    def drawing(self, azimuth: float) -> str: ...
    def save_drawing(self, path: str, azimuth: float, source: str) -> None: ...
    def save_plot(self, path: str, source: str) -> None: ...

def _envelope(
    xyz: npt.NDArray[np.float32],
    alpha: Optional[float],
    correction: str,
    threads: int,
    length_unit: Optional[str],
    robot: Optional[Robot],
    provenance: Optional[Dict[str, Any]],
) -> _Envelope: ...

class _ReachMap:
    @staticmethod
    def load(path: _Path) -> "_ReachMap": ...
    def save(self, path: _Path) -> None: ...
    def save_points(self, path: _Path) -> None: ...
    def save_halfcut(self, path: _Path) -> None: ...
    def save_histogram(self, path: _Path) -> None: ...
    def header(self) -> str: ...
    def summary(self) -> str: ...
    def grid(self) -> Tuple[float, int, int]: ...
    def __len__(self) -> int: ...
    def voxels(self) -> npt.NDArray[np.int32]: ...
    def centres(self) -> npt.NDArray[np.float64]: ...
    def reachability(self) -> npt.NDArray[np.float64]: ...
    def manipulability(self) -> npt.NDArray[np.float32]: ...
    def count(self) -> npt.NDArray[np.uint64]: ...
    def query(self, points: npt.NDArray[np.float64], directions: Optional[_Floats]) -> Dict[str, npt.NDArray[Any]]: ...

def _reach_map(
    robot: Robot,
    resolution: float,
    samples: int,
    seed: int,
    threads: int,
    orientations: int,
    rolls: int,
    manipulability: bool,
    collision: bool,
    quality_task: Optional[str],
    length: Optional[float],
    progress: Any,
) -> _ReachMap: ...

class _PointsResult:
    def summary(self) -> str: ...
    def save(self, path: _Path) -> None: ...
    def save_plot(self, path: _Path) -> None: ...
    def points(self, joints: int) -> npt.NDArray[np.void]: ...

class _ReachStudy(_PointsResult): ...
class _Placement(_PointsResult): ...

def _reach_study(
    robot: Robot,
    targets: Any,
    normals: Optional[_Floats],
    standoff: float,
    approach_tolerance: float,
    ik_starts: int,
    seed: int,
    threads: int,
    collision: bool,
    quality_task: Optional[str],
    length: Optional[float],
    progress: Any,
) -> _ReachStudy: ...
def _place(
    robot: Robot,
    targets: Any,
    normals: Optional[_Floats],
    line: List[float],
    across: List[float],
    up: List[float],
    confirm: int,
    confirm_margin: Optional[float],
    map: Optional[_ReachMap],
    resolution: Optional[float],
    samples: int,
    orientations: int,
    rolls: int,
    manipulability: bool,
    standoff: float,
    approach_tolerance: float,
    ik_starts: int,
    seed: int,
    threads: int,
    collision: bool,
    quality_task: Optional[str],
    length: Optional[float],
    map_cache: str,
    progress: Any,
) -> _Placement: ...
def _default_map_cache() -> str: ...

class _Plan:
    def report(self) -> str: ...
    def path(self) -> Optional[npt.NDArray[np.float64]]: ...
    def save(self, path: _Path) -> None: ...
    def save_plot(self, path: _Path, cells: int) -> None: ...
    def save_offsets_plot(self, path: _Path) -> None: ...

def _plan(
    scenario: _Path,
    seed: Optional[int],
    validation_poses: Optional[int],
    threads: int,
    progress: Any,
) -> _Plan: ...
def _behave(
    model: str,
    insulators: int,
    faults: Optional[str],
    log: Optional[str],
    timeline: Optional[str],
    timeline_period: float,
) -> Tuple[str, str, List[str]]: ...
