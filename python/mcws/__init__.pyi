"""Type stubs of the mcws package (see _mcws.pyi for the extension's functions)."""

import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._mcws import Error as Error
from ._mcws import Robot as Robot
from ._mcws import UsageError as UsageError
from ._mcws import read_pcd as read_pcd
from ._mcws import read_provenance as read_provenance
from ._mcws import sample as sample
from ._mcws import sample_shape as sample_shape

# A length argument: a number in the robot's length unit, or a string with its unit ("2cm").
_Length = Union[float, str]

def write_pcd(
    path: Union[str, bytes, "os.PathLike[str]"],
    points: npt.ArrayLike,
    robot: Optional[Robot] = None,
    provenance: Optional[Dict[str, Any]] = None,
    *,
    sampling: Optional[Dict[str, Any]] = None,
) -> None: ...

def refine(
    robot: Robot,
    boundary_points: npt.ArrayLike,
    n: int,
    seed: int = 0,
    threads: int = 0,
    *,
    spread: float = 0.1,
    point: str = "tool",
    fix: Optional[Dict[str, float]] = None,
    collision: bool = False,
    progress: Any = None,
) -> npt.NDArray[np.void]: ...

class Measure(Dict[str, Any]):
    # The robot's name and the frame whose origin the points are (a URDF tip link, "tool",
    # "flange"), from measure()'s robot= or provenance=; None when neither was given (an array
    # records no robot), as the tools' null for a cloud that records none.
    robot: Optional[str]
    tip: Optional[str]
    def __getattr__(self, name: str) -> Any: ...

def boundary(
    points: Union[npt.ArrayLike, str, "os.PathLike[str]"],
    plane: Optional[str] = None,
    *,
    method: str = "orthant",
    radius: Optional[float] = None,
    auto_radius: Optional[float] = None,
    adaptive: Optional[int] = None,
    outer_radius: Optional[float] = None,
    min_gap: Optional[float] = None,
    hull_depth: Optional[float] = None,
    cell: Optional[float] = None,
    gap: Optional[float] = None,
    threads: int = 0,
    tiles: Optional[int] = None,
    progress: Any = None,
) -> npt.NDArray[np.bool_]: ...
def measure(
    points: npt.ArrayLike,
    plane: Optional[str] = None,
    *,
    alpha: Optional[float] = None,
    correction: str = "efron",
    threads: int = 0,
    length_unit: Optional[str] = None,
    robot: Optional[Robot] = None,
    provenance: Optional[Dict[str, Any]] = None,
    method: str = "delaunay",
    leave_one_out: Optional[str] = None,
    triangulate: Optional[str] = None,
    boundary: Optional[npt.ArrayLike] = None,
    column_width: Optional[float] = None,
) -> Measure: ...

class Envelope(Dict[str, Any]):
    vertices: npt.NDArray[np.float64]
    triangles: npt.NDArray[np.uint32]
    robot: Optional[str]  # as Measure's: None without robot= or provenance=
    tip: Optional[str]
    def __getattr__(self, name: str) -> Any: ...
    def save(self, path: Union[str, "os.PathLike[str]"], source: str = "points") -> None: ...
    def drawing(self, azimuth: float = 0.0) -> Measure: ...
    def save_drawing(
        self, path: Union[str, "os.PathLike[str]"], azimuth: float = 0.0, source: str = "points"
    ) -> None: ...
    def save_plot(self, path: Union[str, "os.PathLike[str]"], source: str = "points") -> None: ...

def envelope(
    points: npt.ArrayLike,
    *,
    alpha: Optional[float] = None,
    correction: str = "efron",
    threads: int = 0,
    length_unit: Optional[str] = None,
    robot: Optional[Robot] = None,
    provenance: Optional[Dict[str, Any]] = None,
) -> Envelope: ...

class ReachMap:
    resolution: float
    orientations: int
    rolls: int
    header: Dict[str, Any]
    summary: Optional[Dict[str, Any]]
    length_unit: str
    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "ReachMap": ...
    @property
    def voxels(self) -> npt.NDArray[np.int32]: ...
    @property
    def centres(self) -> npt.NDArray[np.float64]: ...
    @property
    def reachability(self) -> npt.NDArray[np.float64]: ...
    @property
    def manipulability(self) -> npt.NDArray[np.float32]: ...
    @property
    def count(self) -> npt.NDArray[np.uint64]: ...
    def __len__(self) -> int: ...
    def query(self, points: npt.ArrayLike, directions: Optional[npt.ArrayLike] = None) -> Dict[str, Any]: ...
    def save(self, path: Union[str, "os.PathLike[str]"]) -> None: ...
    def save_points(self, path: Union[str, "os.PathLike[str]"]) -> None: ...
    def save_halfcut(self, path: Union[str, "os.PathLike[str]"]) -> None: ...
    def save_histogram(self, path: Union[str, "os.PathLike[str]"]) -> None: ...

def reach_map(
    robot: Robot,
    resolution: _Length,
    samples: int,
    seed: int = 0,
    threads: int = 0,
    *,
    orientations: int = 200,
    rolls: int = 1,
    manipulability: bool = True,
    collision: bool = False,
    quality_task: Optional[str] = None,
    length: Optional[_Length] = None,
    progress: Any = None,
) -> ReachMap: ...

_Targets = Union[str, "os.PathLike[str]", npt.ArrayLike]

class _PointsResult(Dict[str, Any]):
    points: npt.NDArray[np.void]
    robot: str  # the robot's name
    tip: str  # its URDF tip link, or "tool" for a D-H robot
    def __getattr__(self, name: str) -> Any: ...
    def save(self, path: Union[str, "os.PathLike[str]"]) -> None: ...

class ReachStudy(_PointsResult): ...
class Placement(_PointsResult):
    def save_plot(self, path: Union[str, "os.PathLike[str]"]) -> None: ...

def reach_study(
    robot: Robot,
    targets: _Targets,
    normals: Optional[npt.ArrayLike] = None,
    *,
    standoff: _Length = 0.0,
    approach_tolerance: float = 0.0,
    ik_starts: int = 4,
    seed: int = 0,
    threads: int = 0,
    collision: bool = True,
    quality_task: Optional[str] = None,
    length: Optional[_Length] = None,
    progress: Any = None,
) -> ReachStudy: ...
def place(
    robot: Robot,
    targets: _Targets,
    line: Sequence[float],
    across: Sequence[float] = (0.0,),
    up: Sequence[float] = (0.0,),
    *,
    normals: Optional[npt.ArrayLike] = None,
    map: Optional[ReachMap] = None,
    resolution: Optional[_Length] = None,
    samples: Optional[int] = None,
    orientations: int = 200,
    rolls: int = 1,
    manipulability: bool = True,
    confirm: Optional[int] = 0,
    confirm_margin: Optional[float] = 0.1,
    standoff: _Length = 0.0,
    approach_tolerance: float = 0.0,
    ik_starts: int = 4,
    seed: int = 0,
    threads: int = 0,
    collision: bool = True,
    quality_task: Optional[str] = None,
    length: Optional[_Length] = None,
    map_cache: Union[None, bool, str, "os.PathLike[str]"] = None,
    progress: Any = None,
) -> Placement: ...

class Plan(Dict[str, Any]):
    path: Optional[npt.NDArray[np.float64]]
    def __getattr__(self, name: str) -> Any: ...
    def save(self, path: Union[str, "os.PathLike[str]"]) -> None: ...
    def save_plot(self, path: Union[str, "os.PathLike[str]"], cells: int = 120) -> None: ...
    def save_offsets_plot(self, path: Union[str, "os.PathLike[str]"]) -> None: ...

def plan(
    scenario: Union[str, "os.PathLike[str]"],
    seed: Optional[int] = None,
    validation_poses: Optional[int] = None,
    threads: int = 0,
    progress: Any = None,
) -> Plan: ...

class Behavior(Dict[str, Any]):
    log: List[Dict[str, Any]]
    failure: Optional[str]
    pose_findings: List[str]
    def __getattr__(self, name: str) -> Any: ...

def behave(
    model: Union[str, "os.PathLike[str]"],
    insulators: int,
    faults: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    log: Optional[Union[str, "os.PathLike[str]"]] = None,
    timeline: Optional[Union[str, "os.PathLike[str]"]] = None,
    timeline_period: float = 0.1,
) -> Behavior: ...
