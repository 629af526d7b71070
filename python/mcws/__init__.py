"""mcws: Monte Carlo workspace analysis of robot manipulators, from Python.

The stages of the mcws command-line tools on NumPy arrays, computed by the same C++ library, so
that the same arguments give the same numbers as the tools:

    robot = mcws.Robot("robots/deicing.yaml")       # .yaml or .urdf
    T = robot.fk(q)                                  # (4, 4) pose, translation in robot.length_unit
    points = mcws.sample(robot, 100_000, seed=1)     # as mcws_sample: x y z q1..qn label
    mcws.write_pcd("cloud.pcd", points, robot=robot)
    cloud = mcws.read_pcd("cloud.pcd")

Every length is in the robot's length unit (robot.length_unit), every joint value in rad
(revolute) or that length unit (prismatic). Errors raise mcws.Error (a RuntimeError) or, for a
bad argument value, mcws.UsageError (a ValueError and an mcws.Error), with the tools' one-line
messages.
"""

import json as _json
import os as _os

import numpy as _np

from ._mcws import (
    Error,
    Robot,
    UsageError,
    _boundary,
    _envelope,
    _measure,
    _place,
    _plan,
    _reach_study,
    _point_dtype,
    _reach_map,
    _ReachMap,
    _refine,
    _write_points,
    read_pcd,
    read_provenance,
    sample,
    sample_shape,
)

__all__ = [
    "Error",
    "UsageError",
    "Robot",
    "sample",
    "sample_shape",
    "read_pcd",
    "read_provenance",
    "write_pcd",
    "boundary",
    "refine",
    "measure",
    "Measure",
    "envelope",
    "Envelope",
    "reach_map",
    "ReachMap",
    "reach_study",
    "ReachStudy",
    "place",
    "Placement",
    "plan",
    "Plan",
]

for _name in ("Error", "UsageError", "Robot"):
    globals()[_name].__module__ = __name__

_JOINT_FIELDS = tuple(f"q{i}" for i in range(1, 9))
_QUALITY_FIELDS = ("manipulability", "inverse_condition")
_KNOWN_FIELDS = ("x", "y", "z") + _JOINT_FIELDS + ("label",) + _QUALITY_FIELDS


def _packed_points(points):
    """points as records of _point_dtype(joints, quality): (array, quality, joints)."""
    array = _np.asarray(points)
    if array.dtype.names is None:
        if array.ndim != 2 or array.shape[1] != 3:
            raise UsageError(
                f"points: shape {array.shape} is neither a structured array (fields x y z ...) "
                "nor (N, 3)"
            )
        packed = _np.zeros(array.shape[0], dtype=_point_dtype(0, False))
        for axis, name in enumerate("xyz"):
            packed[name] = array[:, axis]
        return packed, False, 0
    names = array.dtype.names
    unknown = [name for name in names if name not in _KNOWN_FIELDS]
    if unknown:
        raise UsageError(
            f"points: field '{unknown[0]}' is not one of {' '.join(_KNOWN_FIELDS)}"
        )
    missing = [name for name in "xyz" if name not in names]
    if missing:
        raise UsageError(f"points: has no field '{missing[0]}'")
    if array.ndim != 1:
        raise UsageError(f"points: a structured array of shape {array.shape}, not (N,)")
    joints = sum(1 for name in _JOINT_FIELDS if name in names)
    if any(_JOINT_FIELDS[i] not in names for i in range(joints)):
        raise UsageError(
            f"points: joint fields must be q1..q{joints}, not {[n for n in names if n in _JOINT_FIELDS]}"
        )
    quality = any(name in names for name in _QUALITY_FIELDS)
    layout = _point_dtype(joints, quality)
    if array.dtype == layout and array.flags.c_contiguous:
        return array, quality, joints  # sample()'s own records: written without a copy
    packed = _np.zeros(array.shape[0], dtype=layout)
    for name in names:
        packed[name] = array[name]
    return packed, quality, joints


def write_pcd(path, points, robot=None, provenance=None):
    """Writes points as a binary PCD file through mcws's writer, as the tools write clouds.

    path: the file (str or os.PathLike); it appears only when complete.
    points: a structured array with fields x, y, z [length unit] and any of q1..q8
        [rad | length unit], label, manipulability, inverse_condition (missing ones are written
        as 0), such as sample() returns; or a plain (N, 3) array of positions.
    robot: an mcws.Robot: record it in the header (its name, file, SHA-256 and length unit), as
        the tools do, so that later stages check they are given the same robot.
    provenance: a dict as read_provenance() returns, recorded instead (to carry a cloud's
        provenance through a pipeline); give robot or provenance, not both.

    The file has the fields of mcws_sample's PCD (x y z q1..q8 label, and manipulability
    inverse_condition when points has either): write_pcd(p, sample(...), provenance=...) is byte
    for byte the file mcws_sample writes with the same arguments and provenance.

    Raises mcws.UsageError for points of another shape or with other fields, both robot and
    provenance, or a malformed provenance; mcws.Error naming the file when it cannot be written.
    """
    if robot is not None and provenance is not None:
        raise UsageError("write_pcd: give robot or provenance, not both")
    if robot is not None and not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    packed, quality, joints = _packed_points(points)
    _write_points(_os.fspath(path), packed, quality, joints, robot, provenance)


def _positions(points):
    """The x y z of a structured array, or an (N, 3) array, as float32 (N, 3): the positions as a
    PCD file holds them, so that the tools and these functions see the same numbers."""
    array = _np.asarray(points)
    if array.dtype.names is not None:
        missing = [name for name in "xyz" if name not in array.dtype.names]
        if missing:
            raise UsageError(f"points: has no field '{missing[0]}'")
        if array.ndim != 1:
            raise UsageError(f"points: a structured array of shape {array.shape}, not (N,)")
        xyz = _np.empty((array.shape[0], 3), dtype=_np.float32)
        for axis, name in enumerate("xyz"):
            xyz[:, axis] = array[name]
        return xyz
    if array.ndim != 2 or array.shape[1] != 3:
        raise UsageError(
            f"points: shape {array.shape} is neither a structured array (fields x y z) nor (N, 3)"
        )
    return _np.ascontiguousarray(array, dtype=_np.float32)


def boundary(points, plane=None, *, radius=None, auto_radius=None, adaptive=None,
             outer_radius=None, min_gap=None, hull_depth=None, threads=0):
    """The boundary points of a workspace cloud: the orthant test of mcws_boundary (Yin, Wang & Yu
    2010, section 4.3), with its settings and their defaults.

    points: a structured array with fields x, y, z (such as sample() or read_pcd() return) or an
        (N, 3) array [length unit]; positions are taken as float32, as a PCD file holds them.
    plane: None (3-D, octants) or "xy", "xz", "yz" (quadrants in that plane).
    radius: a fixed search radius [length unit] (mcws_boundary --radius).
    auto_radius: c of a radius c x the cloud's mean spacing (--auto-radius).
    adaptive: k of a per-point radius 2 x the distance to the k-th neighbour (--adaptive; the
        default, with k = 24 in a plane, 16 in 3-D).
    outer_radius: the second stage at R: a length > r [length unit] with radius or auto_radius,
        else a factor > 1 of each point's radius (--outer-radius).
    min_gap: 2-D: the empty sector that makes a boundary point [deg], in [90, 180) (default 92).
    hull_depth: 2-D: keep points less than t local spacings inside the convex hull of their
        neighbourhood, 0 = off, else in [0.1, 10] (default 1).
    threads: worker threads, 0 = all cores (the result does not depend on it).

    Returns a boolean array of N entries, True for the points mcws_boundary writes with the same
    settings (points[mask] is its output); non-finite points are False.

    Raises mcws.UsageError for settings out of their range for this cloud (the ranges of
    mcws_boundary: lengths between a tenth of the mean spacing and the cloud's extent, ...) or a
    cloud flat in one of the plane's axes; mcws.Error for a cloud with too few distinct points.
    """
    return _boundary(_positions(points), plane, radius, auto_radius, adaptive, outer_radius,
                     min_gap, hull_depth, threads)


def refine(robot, boundary_points, n, seed=0, threads=0, *, spread=0.1, point="tool", fix=None,
           collision=False, progress=None):
    """New samples near a cloud's boundary (Liu et al. 2013), as mcws_refine draws them.

    robot: the mcws.Robot the points were sampled from.
    boundary_points: the boundary points with their joint values: a structured array with fields
        x, y, z and q1..q<dof> [rad | length unit] (points[boundary(points)], or read_pcd() of
        mcws_boundary's output).
    n: number of new samples (int >= 0).
    seed: random seed, a whole number >= 0 (mcws_refine's default is 1).
    threads: worker threads, 0 = all cores. The result is the same bytes for any thread count.
    spread: neighbourhood half-width, a fraction of each joint's range in (0, 1] (default 0.1):
        sample i moves each joint of boundary point i mod P by up to spread x its range, clamped
        to its limits.
    point: "tool" or "flange": the point the cloud was sampled at (sample()'s point).
    fix: the joints pinned when the cloud was sampled (sample()'s fix), a dict joint name ->
        value [rad | length unit]; they keep their value. None: the joints with one value in
        every boundary point (of two or more) are taken as pinned; {}: none is.
    collision: label the new samples by their collision status, as sample(collision=True).
    progress: True for progress lines on stderr, or a callable called with (samples done, n)
        every 65536 samples; None: silent (as sample()).

    Returns n new samples, a structured array as sample() returns (x, y, z [length unit],
    q1..q<dof>, label): the points mcws_refine writes for the same boundary points, seed and
    spread (a cloud sampled with --fix and --collision refined with the same fix and collision).
    Append them to the cloud (numpy.concatenate) and measure with correction="none".

    Raises mcws.UsageError for a bad n, seed, threads, spread, point or fix, boundary points
    without the joint fields, none at all, or one whose joint values lie outside the robot's
    limits; mcws.Error for collision=True on a robot file without collision geometry.
    """
    if not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    packed, quality, joints = _packed_points(boundary_points)
    if quality:  # the refinement reads positions and joints only
        plain = _np.zeros(packed.shape[0], dtype=_point_dtype(joints, False))
        for name in plain.dtype.names:
            plain[name] = packed[name]
        packed = plain
    return _refine(robot, packed, joints, n, seed, threads, spread, point, fix, collision,
                   progress)


class _Record(dict):
    """A dict whose keys are also attributes (names starting with _ excepted)."""

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None


class Measure(_Record):
    """The area or volume of a region, as mcws_measure --json gives it: a dict (dict(result)
    gives its keys) whose keys are also attributes.

    area (plane given) [length unit^2] or volume (3-D) [length unit^3]: the Delaunay measure with
    the edge correction; uncorrected: the kept simplices' total before the correction;
    correction: "efron" or "none"; alpha: the simplex size limit [local spacings]; points:
    distinct points; triangulated; boundary_vertices; outside (Efron's count); plane; method;
    length_unit; units: the unit of each dimensioned number.
    """



def measure(points, plane=None, *, alpha=None, correction="efron", threads=0, length_unit=None):
    """The area (in a plane) or volume (3-D) of the region a cloud samples, as mcws_measure.

    points: a structured array with fields x, y, z or an (N, 3) array [length unit], taken as
        float32 as a PCD file holds them.
    plane: None (volume) or "xy", "xz", "yz" (the area of the cloud projected onto that plane).
    alpha: simplex size limit [local spacings] in [1, 1000] (default 3, 5 with correction "none").
    correction: "efron" (leave-one-out edge correction, for uniform samples; default) or "none"
        (for refined clouds whose samples lie on the edge).
    threads: worker threads, 0 = all cores (the result does not depend on it).
    length_unit: "m", "cm" or "mm": the unit of the positions, named in the result's units
        (default: "unrecorded", as mcws_measure for a cloud that records none).

    Returns a Measure with .area or .volume, .units and the rest of mcws_measure --json but for
    its input and seconds: the same numbers for the same points. The GIL is released; Ctrl-C
    interrupts between the phases (local spacing, triangulation, alpha test, edge correction).

    Raises mcws.UsageError for a bad plane, alpha, correction, threads or length_unit, or a cloud
    flat in one of the plane's axes; mcws.Error for too few distinct points or a flat 3-D cloud.
    """
    return Measure(_json.loads(
        _measure(_positions(points), plane, alpha, correction, threads, length_unit)))


class Envelope(_Record):
    """The envelope of a 3-D cloud, as mcws_envelope makes it: a closed triangle mesh, every
    triangle counter-clockwise seen from outside, enclosing the volume measure() gives.

    A dict of mcws_envelope --json's numbers but for its files and seconds (dict(result) gives
    its keys; they are also attributes): volume (enclosed by the mesh) [length unit^3],
    measure_volume (mcws_measure's), uncorrected, filled_volume [length unit^3], area
    [length unit^2], offset [length unit], alpha [local spacings], correction, points, vertices
    and triangles (the counts), edges, euler_characteristic, closed_and_oriented,
    non_manifold_edges, length_unit and units (the unit of each number).

    vertices: the mesh's vertices, a float64 (V, 3) array [length unit] (the attribute; the count
        is result["vertices"]).
    triangles: the mesh's triangles, a uint32 (T, 3) array of vertex indices (likewise).
    """

    def __init__(self, mesh):
        super().__init__(_json.loads(mesh.summary()))
        self._mesh = mesh
        self.vertices = mesh.vertices()
        self.triangles = mesh.triangles()

    def save(self, path, source="points"):
        """Writes the mesh as mcws_envelope --output does: binary PLY, binary STL or ASCII VTK by
        the extension of path (.ply, .stl, .vtk), lengths in the positions' unit; the file
        appears whole or not at all. source names the cloud in the file's comment
        ("mcws_envelope of <source>, lengths in <unit>"): mcws_envelope's --input path gives
        its bytes.

        Raises mcws.Error naming the file for another extension or when it cannot be written.
        """
        self._mesh.save(_os.fspath(path), str(source))

    def drawing(self, azimuth=0.0):
        """The numbers of the datasheet drawing, as mcws_envelope --drawing --json gives them
        under "drawing" (its "units" here under "units"): the side view, the section of the mesh
        by the vertical plane through the z axis at azimuth [deg from +x] (azimuth [deg],
        section_area [length unit^2], front_reach, back_reach, section_highest, section_lowest
        [length unit]); the top view of the samples (max_reach, min_reach [length unit],
        swept_angle, sweep_from, sweep_to [deg]); the envelope's highest and lowest [length
        unit]. Returns a Measure (a dict whose keys are also attributes).

        Raises mcws.UsageError when the plane misses the mesh or azimuth is not finite.
        """
        return Measure(_json.loads(self._mesh.drawing(float(azimuth))))


def envelope(points, *, alpha=None, correction="efron", threads=0, length_unit=None):
    """The workspace envelope of a 3-D cloud as a closed, outward-oriented triangle mesh, as
    mcws_envelope makes it: the surface of the tetrahedra measure() keeps (the alpha shape at the
    same alpha), moved outward so that it encloses measure()'s volume (with correction "none",
    the alpha surface as it is); cavities filled and pinches mended to make it a 2-manifold.

    points: a structured array with fields x, y, z or an (N, 3) array [length unit], taken as
        float32 as a PCD file holds them.
    alpha: simplex size limit [local spacings] in [1, 1000] (default 3, 5 with correction "none").
    correction: "efron" (uniform samples; default) or "none" (refined clouds).
    threads: worker threads, 0 = all cores (the result does not depend on it).
    length_unit: "m", "cm" or "mm": the unit of the positions, named in the result's units and
        the files (default: "unrecorded", as mcws_envelope for a cloud that records none).

    Returns an Envelope: .vertices (V, 3), .triangles (T, 3), .volume, .units, .save(path),
    .drawing(azimuth) and the rest of mcws_envelope --json: the same numbers and, saved, the same
    file as the tool for the same points. The GIL is released; Ctrl-C interrupts between phases.

    Raises mcws.UsageError for a bad alpha, correction, threads or length_unit; mcws.Error for too
    few distinct points, a flat cloud, or an offset that does not converge.
    """
    return Envelope(_envelope(_positions(points), alpha, correction, threads, length_unit))


class ReachMap:
    """A reachability map (Zacharias, Borst & Hirzinger 2007), as mcws_reach builds it: position
    voxels of edge .resolution [length unit] x orientation bins (.orientations approach regions of
    the sphere x .rolls roll bins). Only voxels some sample reached are stored, in the order of
    the tool's outputs (by index, z fastest).

    Per voxel (arrays of len(map) rows, read-only, made on first use):
    voxels: int32 (V, 3) voxel indices (floor(x / resolution), ...);
    centres: float64 (V, 3) voxel centres [length unit];
    reachability: float64 (V,) the reachability index D, the share of orientation bins reached
        [1], in (0, 1];
    manipulability: float32 (V,) the best manipulability of the voxel's samples (the unit of
        .summary["manipulability"]["manipulability_unit"]; 0 without it);
    count: uint64 (V,) the samples that fell in the voxel.

    header: the map file's header as a dict (robot, robot_file, robot_sha256, length_unit,
        samples, seed, collision, manipulability); length_unit: its length unit.
    summary: mcws_reach --json's summary but for files, processes and seconds (a dict), or None
        for a map read with ReachMap.load.
    """

    def __init__(self, core):
        if not isinstance(core, _ReachMap):
            raise UsageError("ReachMap: made by mcws.reach_map() or mcws.ReachMap.load(path)")
        self._map = core
        self._arrays = {}
        self.resolution, self.orientations, self.rolls = core.grid()
        self.header = _json.loads(core.header())
        self.summary = _json.loads(core.summary())
        self.length_unit = self.header.get("length_unit", "unrecorded")

    @classmethod
    def load(cls, path):
        """Reads a map file (mcws_reach --map, ReachMap.save; docs/reach_map.md).

        Raises mcws.Error naming the file when it is missing, unreadable or malformed.
        """
        return cls(_ReachMap.load(_os.fspath(path)))

    def _array(self, name):
        if name not in self._arrays:
            array = getattr(self._map, name)()
            array.flags.writeable = False
            self._arrays[name] = array
        return self._arrays[name]

    voxels = property(lambda self: self._array("voxels"), doc="int32 (V, 3) voxel indices")
    centres = property(lambda self: self._array("centres"),
                       doc="float64 (V, 3) voxel centres [length unit]")
    reachability = property(lambda self: self._array("reachability"),
                            doc="float64 (V,) reachability index D [1]")
    manipulability = property(lambda self: self._array("manipulability"),
                              doc="float32 (V,) best manipulability of the voxel's samples")
    count = property(lambda self: self._array("count"), doc="uint64 (V,) samples in the voxel")

    def __len__(self):
        return len(self._map)

    def __repr__(self):
        return (f"<mcws.ReachMap of {self.header.get('robot', '?')}: {len(self)} voxels of "
                f"{self.resolution} {self.length_unit}, {self.orientations} x {self.rolls} bins>")

    def query(self, points, directions=None):
        """Looks points (and tool orientations) up in the map.

        points: (N, 3) or (3,) positions [length unit], any float dtype.
        directions: None; approach directions (the tool's z axis, any length), (N, 3) or (3,);
            or tool rotations, (N, 3, 3) or (3, 3).

        Returns a dict of arrays of N entries (scalars for a single point): "voxel" (int64, the
        row of the point's voxel in .voxels & co., -1 where no sample fell or the point is not
        finite), "reachability" [1], "manipulability" and "count" of that voxel (0 where voxel
        is -1), and with directions "reached" (bool): whether a sample fell in the point's voxel
        with its orientation in the direction's bin (any roll bin for an approach direction).

        Raises mcws.UsageError for other shapes, or a direction that is zero or not finite.
        """
        p = _np.asarray(points, dtype=_np.float64)
        single = p.ndim == 1
        if single:
            p = p[None, :]
            if directions is not None:
                directions = _np.asarray(directions, dtype=_np.float64)[None, ...]
        result = self._map.query(p, directions)
        return {k: v[0] for k, v in result.items()} if single else result

    def save(self, path):
        """Writes the map file, byte for byte what mcws_reach --map writes for the same map
        (docs/reach_map.md); it appears whole or not at all.

        Raises mcws.Error naming the file when it cannot be written.
        """
        self._map.save(_os.fspath(path))

    def save_points(self, path):
        """Writes the voxel centres with fields reachability, manipulability and count as a
        binary PCD, byte for byte what mcws_reach --output writes for the same map (the robot
        its header names recorded in the file).

        Raises mcws.Error naming the file when it cannot be written.
        """
        self._map.save_points(_os.fspath(path))


def reach_map(robot, resolution, samples, seed=0, threads=0, *, orientations=200, rolls=1,
              manipulability=True, collision=False, quality_task=None, length=None,
              progress=None):
    """The reachability map of a robot, as mcws_reach builds it: joint values drawn uniformly
    within their limits (sample i's values depend only on seed and i, the joint values of
    sample(robot, samples, seed)) through forward kinematics to the tool pose, whose point falls
    in a cubic voxel of edge resolution and whose orientation in one of orientations x rolls bins.

    robot: an mcws.Robot.
    resolution: the voxel edge [length unit] (the robot's .length_unit), > 0.
    samples: joint samples (int >= 1; mcws_reach's default is 5e8, 1e7 gives a first look).
    seed: random seed, a whole number >= 0 (mcws_reach's default is 1).
    threads: worker threads, 0 = all cores. The map is the same for any thread count.
    orientations: approach-direction bins on the sphere, 1 .. 65536 (default 200).
    rolls: roll bins about the approach (default 1: any roll counts).
    manipulability: compute the Jacobian and keep each voxel's best manipulability (mcws_reach
        --no-manipulability is False).
    collision: count only collision-free samples (the robot file's collision model).
    quality_task, length: how manipulability is measured, as sample(quality=True).
    progress: True for progress lines on stderr as mcws_reach writes them, or a callable called
        with (samples done, samples) after each chunk; None: silent.

    Returns a ReachMap: .save(path) writes the file mcws_reach --map writes for the same
    arguments, byte for byte; .save_points(path) its --output. The GIL is released; Ctrl-C
    interrupts (KeyboardInterrupt) between chunks of 4 million samples.

    Raises mcws.UsageError for a bad resolution, samples, seed, threads, orientations, rolls,
    quality_task or length; mcws.Error for collision=True without collision geometry, a tool
    point beyond the grid's index range, or no sample counted.
    """
    if not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    return ReachMap(_reach_map(robot, resolution, samples, seed, threads, orientations, rolls,
                               manipulability, collision, quality_task, length, progress))


class _PointsResult(_Record):
    """A summary dict (keys also attributes) with .points and .save(path)."""

    def __init__(self, core, joints=0):
        super().__init__(_json.loads(core.summary()))
        self._core = core
        self.points = core.points(joints)

    def save(self, path):
        """Writes .points as a binary PCD, byte for byte the tool's --output for the same
        arguments. Raises mcws.Error naming the file when it cannot be written."""
        self._core.save(_os.fspath(path))


class ReachStudy(_PointsResult):
    """A reach study's result, as mcws_reach --targets gives it: a dict of its --json summary but
    for output and seconds (keys also attributes): targets, reached, solved, share_reached [1],
    mean_score, mean_manipulability_reached, manipulability (how it is measured),
    min_clearance_reached [length unit] (None when not measured), collision,
    approach_tolerance_deg [deg], ik_starts, seed and unreached (per target not reached: solved,
    label, position_error [length unit], orientation_error_deg [deg]).

    points: the heat map, a structured array of one record per target (viewing the C++ points):
        x, y, z the target point [length unit]; normal_x, normal_y, normal_z its surface normal;
        q1..q<dof> the chosen joint values [rad | length unit] (0 when not solved); label;
        reached (1 or 0); score (manipulability where reached, else 0); manipulability;
        clearance [length unit] (-1 where not measured); orientation_error [rad].
    save(path): the heat map as mcws_reach --targets --output writes it.
    """


class Placement(_PointsResult):
    """A base placement, as mcws_place gives it: a dict of its --json summary but for output and
    seconds (keys also attributes): targets, positions, map (its grid and where it came from),
    manipulability, collision, approach_tolerance_deg [deg], candidates (per position: offset
    [length unit], map_share and ik_share [1], map_score and ik_score; ik_* None where IK did not
    confirm it) and best (the best confirmed candidate with reached and base_position [length
    unit], or None).

    points: per position a record x, y, z (where the base frame lands [length unit]), map_share,
        map_score, ik_share, ik_score (-1 where not confirmed).
    save(path): those points as mcws_place --output writes them.
    """


def _targets_argument(targets):
    if isinstance(targets, (str, _os.PathLike)):
        return _os.fspath(targets)
    return targets


def reach_study(robot, targets, normals=None, *, standoff=0.0, approach_tolerance=0.0,
                ik_starts=4, seed=0, threads=0, collision=True, quality_task=None, length=None,
                progress=None):
    """Solves target poses by inverse kinematics, as mcws_reach --targets (ROS-Industrial REACH):
    each target from ik_starts starting joint vectors, the best solution kept (collision-free
    first, then the highest manipulability).

    robot: an mcws.Robot.
    targets: a targets file (str or os.PathLike: PCD with normals or CSV, as mcws_reach
        --targets reads); or target points (N, 3) [length unit] with normals; or tool poses
        (N, 4, 4) [length unit] (the whole orientation counts).
    normals: the surface normals (N, 3) of target points (any length): the tool's z axis
        approaches against the normal, its roll free.
    standoff: distance of the tool point from each target's surface, along its normal
        [length unit] (default 0).
    approach_tolerance: the largest accepted approach (or orientation) error [deg] in [0, 180]
        (default 0: exact).
    ik_starts: IK starting joint vectors per target, 1 .. 1000 (default 4).
    seed: random seed of the starts, a whole number >= 0 (mcws_reach's default is 1).
    threads: worker threads, 0 = all cores. The result does not depend on it.
    collision: use the robot file's collision model when it has one (mcws_reach --no-collision
        is False).
    quality_task, length: how manipulability is measured, as sample(quality=True).
    progress: True for progress lines on stderr, or a callable called with (targets done,
        targets) now and then; None: silent.

    Returns a ReachStudy (its summary, .points, .save(path)): the numbers and heat map of
    mcws_reach --targets with the same arguments. The GIL is released; Ctrl-C interrupts.

    Raises mcws.UsageError for targets or normals of another shape, a zero or non-finite normal,
    a bad standoff, approach_tolerance, ik_starts, seed, threads, quality_task or length;
    mcws.Error for a targets file that is missing or malformed (naming it).
    """
    if not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    core = _reach_study(robot, _targets_argument(targets), normals, standoff,
                        approach_tolerance, ik_starts, seed, threads, collision, quality_task,
                        length, progress)
    return ReachStudy(core, robot.dof)


def place(robot, targets, line, across=(0.0,), up=(0.0,), *, normals=None, map=None,
          resolution=None, samples=None, orientations=200, rolls=1, manipulability=True,
          confirm=5, standoff=0.0, approach_tolerance=0.0, ik_starts=4, seed=0, threads=0,
          collision=True, quality_task=None, length=None, progress=None):
    """Where to put the robot's base so its arm reaches the targets, as mcws_place: the whole
    robot moved by every offset of line (x) x across (y) x up (z), the environment of its
    collision model staying in place; each position scored from a reachability map (the share
    of targets whose voxel and approach bin the map marks reached, their mean best
    manipulability), the best `confirm` by the map solved by inverse kinematics as reach_study.

    robot, targets, normals, standoff, approach_tolerance, ik_starts, seed, threads, collision,
        quality_task, length: as reach_study() (seed also draws a map built here).
    progress: as reach_study()'s, for the samples of a map built here, then for the positions
        confirmed.
    line, across, up: base offsets along x, y, z [length unit], sequences of values (the
        tool's "first last step" is first + k step, k = 0, 1, ...; numpy.arange gives them).
    map: an mcws.ReachMap of this robot file (mcws_reach --map read with ReachMap.load, or
        reach_map()), without collision filtering; or None and resolution [length unit] and
        samples to build one here, counting the samples free of self-collision (when
        collision and the robot file has a collision model), with orientations, rolls and
        manipulability as reach_map().
    confirm: positions confirmed by IK: a number >= 0 (default 5) or None for all.
    The summary's map.about names where the map came from: the file ReachMap.load read,
    "reach_map()", or "built" (here).

    Returns a Placement (its summary with the candidates and the best, .points,
    .save(path)): the numbers and file of mcws_place with the same arguments (--map or
    --resolution and --samples). The GIL is released; Ctrl-C interrupts.

    Raises mcws.UsageError as reach_study() and reach_map(), for empty or non-finite offsets,
    more than 1e6 positions, both or neither of map and resolution, a map of another robot file,
    chain, unit or manipulability, or a map counting only samples free of the environment.
    """
    if not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    if map is not None and not isinstance(map, ReachMap):
        raise UsageError(f"map: {type(map).__name__} is not an mcws.ReachMap")
    if resolution is not None and samples is None:
        raise UsageError("samples: give the sample count of the map built at resolution")
    core = _place(robot, _targets_argument(targets), normals,
                  [float(v) for v in _np.atleast_1d(line)],
                  [float(v) for v in _np.atleast_1d(across)],
                  [float(v) for v in _np.atleast_1d(up)],
                  -1 if confirm is None else confirm, None if map is None else map._map,
                  resolution, 0 if samples is None else samples, orientations, rolls,
                  manipulability, standoff, approach_tolerance, ik_starts, seed, threads,
                  collision, quality_task, length, progress)
    return Placement(core)


class Plan(_Record):
    """An arm plan under base sway, as mcws_plan gives it: a dict of its --json report (keys also
    attributes; every number's unit in its key or under "units"): status, accepted_round, the
    rounds with their candidates and shared-node decisions, chosen (the accepted path's
    length, probability, vertices, waypoints, collision counts and interval), validation, ...

    path: the chosen path, a float64 (K, dof) array of joint values [rad | length unit] (the
        waypoints of mcws_plan --output), or None when no path was accepted.
    save(path): the path's CSV, byte for byte mcws_plan --output (raises mcws.Error naming the
        file and the status when no path was accepted).
    """

    def __init__(self, core):
        super().__init__(_json.loads(core.report()))
        self._core = core
        self.path = core.path()

    def save(self, path):
        """Writes the chosen path as mcws_plan --output does: D (the distance along it, scaled
        as the report's distance_unit says) then one column per joint, units in the names."""
        self._core.save(_os.fspath(path))


def plan(scenario, seed=None, validation_poses=None, threads=0, progress=None):
    """Plans the arm of a robot whose base sways on the line, as mcws_plan: candidate paths
    through a roadmap for the measured base pose, their segments checked for base poses drawn
    from the scenario's sway, the dominant path taken at every shared node, the base shifted
    along the line until a path is accepted; the chosen path validated on fresh base poses.

    scenario: the scenario file (str or os.PathLike, .yaml; see scenarios/).
    seed: seed of the base poses and the roadmap, a whole number >= 0 (None: the scenario's).
    validation_poses: fresh base poses of the validation (None: the scenario's; 0 skips it).
    threads: worker threads, 0 = all cores.
    progress: True for progress lines on stderr, or a callable called with (done, total) of
        each stage (roadmap, validation) on the calling thread; Ctrl-C interrupts there.

    Returns a Plan (the report as a dict, .path, .save(path)): the report of mcws_plan --json
    and the file of --output for the same scenario, seed and validation poses. When no path is
    accepted (the tool's exit 1) the report's status says why and .path is None.

    Raises mcws.Error naming the scenario file (and line) for a missing or malformed scenario or
    robot; mcws.UsageError for a bad seed, validation_poses or threads.
    """
    return Plan(_plan(_os.fspath(scenario), seed, validation_poses, threads, progress))
