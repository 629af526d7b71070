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
import numbers as _numbers
import os as _os

import numpy as _np

from ._mcws import (
    Error,
    Robot,
    UsageError,
    _boundary,
    _boundary_tiled,
    _envelope,
    _measure,
    _point_dtype,
    _refine,
    _write_points,
    read_pcd,
    read_provenance,
    sample,
    sample_shape,
)
from ._plan import Behavior, Plan, behave, plan
from ._reach import Placement, ReachMap, ReachStudy, place, reach_map, reach_study
from ._record import _Record

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
    "behave",
    "Behavior",
]

for _name in ("Error", "UsageError", "Robot", "ReachMap", "ReachStudy", "Placement", "Plan",
              "Behavior", "reach_map", "reach_study", "place", "plan", "behave"):
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


def write_pcd(path, points, robot=None, provenance=None, *, sampling=None):
    """Writes points as a binary PCD file through mcws's writer, as the tools write clouds.

    path: the file (str, bytes or os.PathLike); it appears only when complete.
    points: a structured array with fields x, y, z [length unit] and any of q1..q8
        [rad | length unit], label, manipulability, inverse_condition (missing ones are written
        as 0), such as sample() returns; or a plain (N, 3) array of positions. At least one point.
    robot: an mcws.Robot: record it in the header as mcws_sample does (its name, file, SHA-256,
        length unit, a URDF robot's chain, and how the points were sampled, see sampling), so that
        later stages (mcws_refine, measure's tip) read the file as one of mcws_sample's.
    sampling: with robot, how the points were drawn, a dict as read_provenance()["sampling"]:
        "point" ("tool" or "flange", sample()'s point), "collision" (bool: the labels are
        sample(collision=True)'s), "fix" (sample()'s fix, {joint: value [rad | length unit]});
        a key left out (or sampling None) takes sample()'s default: tool, False, {}. The header
        records it as mcws_sample records its --point, --collision and --fix.
    provenance: a dict as read_provenance() returns, recorded instead (to carry a cloud's
        provenance through a pipeline); give robot or provenance, not both.

    The file has the fields of mcws_sample's PCD (x y z q1..q8 label, and manipulability
    inverse_condition when points has either): write_pcd(p, sample(robot, n, seed), robot=robot)
    is byte for byte the file mcws_sample --samples n --seed seed writes (with fix, collision,
    point: give the same as sampling), and so is write_pcd(p, points, provenance=...) with the
    provenance of that file.

    Raises mcws.UsageError for points of another shape or with other fields, no points, both
    robot and provenance, sampling without robot or malformed (naming the key), points with
    fewer joint fields than the robot's dof or a joint value beyond it (another robot's), labels
    other than 0 without sampling's collision, or a malformed provenance (naming the key and the
    value); mcws.Error naming the file when it cannot be written.
    """
    if robot is not None and provenance is not None:
        raise UsageError("write_pcd: give robot or provenance, not both")
    if robot is not None and not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    packed, quality, joints = _packed_points(points)
    if robot is not None:
        if 0 < joints < robot.dof:
            raise UsageError(
                f"points: {joints} joint fields (q1..q{joints}), but robot '{robot.name}' has "
                f"{robot.dof} joints: not points of this robot"
            )
        for k in range(robot.dof + 1, joints + 1):  # a file's q1..q8 hold 0 beyond the dof
            beyond = _np.flatnonzero(packed[f"q{k}"])
            if beyond.size:
                value = float(packed[f"q{k}"][beyond[0]])
                raise UsageError(
                    f"points: point {int(beyond[0])} has q{k} = {value!r}, but robot "
                    f"'{robot.name}' has {robot.dof} joints: points of a robot with more joints"
                )
        collision = isinstance(sampling, dict) and bool(sampling.get("collision", False))
        labelled = _np.flatnonzero(packed["label"])
        if not collision and labelled.size:
            first = int(labelled[0])
            raise UsageError(
                f"points: point {first} has label {int(packed['label'][first])}, a collision "
                "label: give sampling={'collision': True} (as sample(collision=True) draws them)"
            )
    _write_points(path, packed, quality, joints, robot, provenance, sampling)


def _positions(points, name="points"):
    """The x y z of a structured array, or an (N, 3) array, as float32 (N, 3): the positions as a
    PCD file holds them, so that the tools and these functions see the same numbers."""
    array = _np.asarray(points)
    if array.dtype.names is not None:
        missing = [name for name in "xyz" if name not in array.dtype.names]
        if missing:
            raise UsageError(f"{name}: has no field '{missing[0]}'")
        if array.ndim != 1:
            raise UsageError(f"{name}: a structured array of shape {array.shape}, not (N,)")
        xyz = _np.empty((array.shape[0], 3), dtype=_np.float32)
        for axis, name in enumerate("xyz"):
            xyz[:, axis] = array[name]
        return xyz
    if array.ndim != 2 or array.shape[1] != 3:
        raise UsageError(
            f"{name}: shape {array.shape} is neither a structured array (fields x y z) nor (N, 3)"
        )
    return _np.ascontiguousarray(array, dtype=_np.float32)


def _record_arguments(robot, provenance):
    """measure()'s and envelope()'s robot and provenance, checked as write_pcd() checks them."""
    if robot is not None and provenance is not None:
        raise UsageError("give robot or provenance, not both")
    if robot is not None and not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    if provenance is not None and not isinstance(provenance, dict):
        raise UsageError("provenance: give a dict as read_provenance() returns, or None")
    return robot, provenance


def boundary(points, plane=None, *, method="orthant", radius=None, auto_radius=None,
             adaptive=None, outer_radius=None, min_gap=None, hull_depth=None, cell=None,
             gap=None, threads=0, tiles=None, progress=None):
    """The boundary points of a workspace cloud, as mcws_boundary finds them, with its settings
    and their defaults.

    points: a structured array with fields x, y, z (such as sample() or read_pcd() return) or an
        (N, 3) array [length unit]; positions are taken as float32, as a PCD file holds them. Or
        the path of a PCD file (str or os.PathLike): its points, read as read_pcd() reads them
        (with tiles, a binary PCD read in pieces).
    plane: None (3-D) or "xy", "xz", "yz" (the cloud projected onto that plane).
    method: "orthant" (default; Yin, Wang & Yu 2010, section 4.3: a point some quadrant (in a
        plane) or octant (3-D) of whose neighbourhood is empty), "grid" (section 4.1: cells of
        side cell; an occupied cell with an empty neighbour, 8 in 2-D, 26 in 3-D, is a boundary
        cell, represented by its point nearest to the cell's mean) or "extremum" (4.2, needs a
        plane: in columns of width cell along the plane's first axis, the lowest and highest
        point along the second, and both points around any gap wider than gap), as
        mcws_boundary --method.
    Orthant only:
    radius: a fixed search radius [length unit] (mcws_boundary --radius).
    auto_radius: c of a radius c x the cloud's mean spacing (--auto-radius).
    adaptive: k of a per-point radius 2 x the distance to the k-th neighbour (--adaptive; the
        default, with k = 24 in a plane, 16 in 3-D).
    outer_radius: the second stage at R: a length > r [length unit] with radius or auto_radius,
        else a factor > 1 of each point's radius (--outer-radius).
    min_gap: 2-D: the empty sector that makes a boundary point [deg], in [90, 180) (default 92).
    hull_depth: 2-D: keep points less than t local spacings inside the convex hull of their
        neighbourhood, 0 = off, else in [0.1, 10] (default 1).
    threads: worker threads, 0 = all cores (the result does not depend on it); the grid and
        extremum methods run on one thread and take only 0 (as the tool refuses --threads).
    tiles: None, or N of mcws_boundary --tiles N (orthant with radius or adaptive, hull_depth=0
        in a plane): points must then be the path of a binary PCD file, read in pieces, and the
        boundary is found one slab at a time (N slabs of equal width along the cloud's longest
        axis in the plane, each with a halo that holds every neighbour its points search), in
        memory bounded by the largest slab and halo (and a byte a point for the mask): the same
        mask as without tiles, which is mcws_boundary --tiles N's output.
    progress: with tiles, True for progress lines on stderr, or a callable called with (slabs
        done, slabs) after each slab; None: silent. Ctrl-C interrupts between slabs.
    Grid and extremum only:
    cell: grid: the cell side, extremum: the column width dL [length unit] (--cell; default:
        from the number of points and the mean spacing).
    gap: extremum: a gap along the column wider than this is an inner boundary [length unit]
        (--gap; default: from the density).

    Returns a boolean array of N entries, True for the points mcws_boundary writes with the same
    settings (points[mask] holds its output's points, in the input's order); non-finite points
    are False.

    Raises mcws.UsageError with mcws_boundary's messages (the flag named as the argument) for an
    unknown method, a setting of another method, a length that is not positive, settings out of
    their range for this cloud (lengths between a tenth of the mean spacing and the cloud's
    extent, ...), method "extremum" without a plane, or a cloud flat in one of the plane's axes;
    mcws.Error for a cloud with too few distinct points. With tiles: mcws.UsageError for tiles
    not in 1 .. 100000, points that are not a path, another method, auto_radius, or a hull depth
    (give hull_depth=0 with a plane); mcws.Error naming the file for one that cannot be read or
    is ascii or compressed PCD.
    """
    if adaptive is not None and (isinstance(adaptive, bool) or
                                 not isinstance(adaptive, _numbers.Integral)):
        raise UsageError(f"adaptive: {adaptive!r} is not a whole number (k, a neighbour count)")
    is_path = isinstance(points, (str, bytes, _os.PathLike))
    if tiles is not None:
        if not is_path:
            raise UsageError("tiles: the cloud is read from a binary PCD file in pieces: give its "
                             "path as points (an array in memory: leave tiles out, the same mask)")
        return _boundary_tiled(_os.fspath(points), plane, method, radius, auto_radius, adaptive,
                               outer_radius, min_gap, hull_depth, cell, gap, threads,
                               tiles, progress)
    if progress is not None:
        raise UsageError("progress: applies with tiles (a boundary in memory takes seconds)")
    if is_path:
        points = read_pcd(points)
    return _boundary(_positions(points), plane, method, radius, auto_radius, adaptive,
                     outer_radius, min_gap, hull_depth, cell, gap, threads)


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
    without the joint fields or with a joint value beyond the robot's dof (another robot's), none
    at all, or one whose joint values lie outside the robot's limits; mcws.Error for
    collision=True on a robot file without collision geometry.
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


class Measure(_Record):
    """The area or volume of a region, as mcws_measure --json gives it: a dict (dict(result)
    gives its keys) whose keys are also attributes.

    area (plane given) [length unit^2] or volume (3-D) [length unit^3]: the Delaunay measure with
    the edge correction; uncorrected: the kept simplices' total before the correction;
    correction: "efron" or "none"; alpha: the simplex size limit [local spacings]; points:
    distinct points; triangulated; boundary_vertices; outside (Efron's count); plane; method;
    length_unit; robot and tip: the robot's name and the frame whose origin the points are (a
    URDF's tip link, a D-H robot's "tool" or "flange"), None when not known; units: the unit of
    each dimensioned number.
    """



def measure(points, plane=None, *, alpha=None, correction="efron", threads=0, length_unit=None,
            robot=None, provenance=None, method="delaunay", leave_one_out=None, triangulate=None,
            boundary=None, column_width=None):
    """The area (in a plane) or volume (3-D) of the region a cloud samples, as mcws_measure.

    points: a structured array with fields x, y, z or an (N, 3) array [length unit], taken as
        float32 as a PCD file holds them.
    plane: None (volume) or "xy", "xz", "yz" (the area of the cloud projected onto that plane).
    alpha: simplex size limit [local spacings] in [1, 1000] (default 3, 5 with correction "none").
    correction: "efron" (leave-one-out edge correction, for uniform samples; default) or "none"
        (for refined clouds whose samples lie on the edge).
    threads: worker threads, 0 = all cores (the result does not depend on it).
    length_unit: "m", "cm" or "mm": the unit of the positions, named in the result's units
        (default: the unit of robot or provenance, else "unrecorded", as mcws_measure for a
        cloud that records none).
    robot, provenance: what the points are of, which an array does not record (give one or
        neither): provenance, a dict as read_provenance() returns (read_provenance(path) of the
        file read_pcd(path) read gives mcws_measure's robot and tip for that file); robot, the
        mcws.Robot sample() drew them from at its tool point (names as mcws_sample records them:
        the robot's name and, as tip, its URDF tip link or "tool"; for points sampled at the
        flange give provenance). Neither: the result's robot and tip are None, as mcws_measure's
        for a cloud that records no robot.
    method: "delaunay" (default) or "column" (the rectangles of Yin, Wang & Yu 2010, eqs. (2)-(4),
        over the boundary points grouped into crossings per column: needs plane and boundary,
        takes none of alpha, correction, leave_one_out, threads, triangulate), as mcws_measure
        --method.
    leave_one_out: how the edge correction finds the boundary vertices outside the region of the
        others: "star" (each vertex's star, all threads; default) or "reinsert" (remove, locate
        and reinsert each vertex: the same count, one thread, slower), as --leave-one-out.
    triangulate: "shell" (only the points an empty ball of alpha radius may touch; default) or
        "all" (every point: the same measure, slower), as --triangulate.
    boundary: with a plane, the cloud's boundary points: a boolean mask over points (as
        boundary() returns) or the points themselves (a structured array or (N, 3) array [length
        unit], each one of points): the result then has the column method's area as
        "cross_check" (biased high; for comparison with the paper, not the result), as
        mcws_measure --boundary.
    column_width: the column method's column width L [length unit], 0 or None automatic, else
        between a tenth of the points' mean spacing and their extent (--column-width; needs
        boundary).

    Returns a Measure with .area or .volume, .units, .robot, .tip and the rest of mcws_measure
    --json but for its input and seconds: the same numbers for the same points. The GIL is
    released; Ctrl-C interrupts within about a second (KeyboardInterrupt): the library checks
    between its phases and every few milliseconds within them (the local spacing, the exposed
    points, the shell's triangulation, inserted in pieces of 65536 points when it has more, the
    alpha test, the edge correction), the same numbers as without the checks.

    Raises mcws.UsageError for a bad plane, alpha, correction, threads or length_unit (or one that
    is not robot's or provenance's unit), both robot and provenance, a malformed provenance, a
    cloud flat in one of the plane's axes, a bad method, leave_one_out, triangulate or
    column_width, a boundary without a plane or a mask of another length, settings the method
    does not take (as mcws_measure's flags); mcws.Error for too few distinct points (in points or
    boundary), a flat 3-D cloud, or a boundary point that is not one of points.
    """
    robot, provenance = _record_arguments(robot, provenance)
    xyz = _positions(points)
    if boundary is not None:
        mask = _np.asarray(boundary)
        if mask.dtype == _np.bool_:
            if mask.shape != (xyz.shape[0],):
                raise UsageError(f"boundary: a mask of shape {mask.shape}, not ({xyz.shape[0]},) "
                                 "as points")
            boundary = xyz[mask]
        else:
            boundary = _positions(boundary, "boundary")
    return Measure(_json.loads(_measure(xyz, plane, alpha, correction, threads, length_unit,
                                        robot, provenance, method, leave_one_out, triangulate,
                                        boundary, column_width)))


class Envelope(_Record):
    """The envelope of a 3-D cloud, as mcws_envelope makes it: a closed triangle mesh, every
    triangle counter-clockwise seen from outside, enclosing the volume measure() gives.

    A dict of mcws_envelope --json's numbers but for its files and seconds (dict(result) gives
    its keys; they are also attributes): volume (enclosed by the mesh) [length unit^3],
    measure_volume (mcws_measure's), uncorrected, filled_volume [length unit^3], area
    [length unit^2], offset [length unit], alpha [local spacings], correction, points, vertices
    and triangles (the counts), edges, euler_characteristic, closed_and_oriented,
    non_manifold_edges, length_unit, robot and tip (as Measure's: None when not known) and units
    (the unit of each number).

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
        ("mcws_envelope of <source>, lengths in <unit>"; with a robot known, "of robot '<name>',
        tip <tip>, from <source>"): mcws_envelope's --input path gives its bytes.

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

    def save_drawing(self, path, azimuth=0.0, source="points"):
        """Writes the datasheet drawing as mcws_envelope --drawing does (through the same library
        code, drawn by gnuplot): the side view (the mesh's section by the vertical plane at
        azimuth [deg from +x]) and the top view of the samples, with dimension lines (reach in
        front of and behind the axis, highest and lowest point [length unit], maximum and minimum
        reach, swept angle [deg]); PNG or SVG by the extension of path (.png, .svg). The title
        names the robot and tip when known (robot or provenance), else the file name of source:
        mcws_envelope's --input path gives its bytes. drawing(azimuth) gives its numbers.

        Raises mcws.UsageError for another extension, an azimuth that is not finite or whose
        plane misses the mesh; mcws.Error when gnuplot fails or path cannot be written.
        """
        self._mesh.save_drawing(_os.fspath(path), float(azimuth), str(source))

    def save_plot(self, path, source="points"):
        """Writes the mesh shaded from two views (front-left from above, and along -y) as a PNG,
        as mcws_envelope --plot does (gnuplot), axes in the length unit; the title names the robot
        and tip, or source's file name, as save_drawing()'s.

        Raises mcws.Error when gnuplot fails or path cannot be written.
        """
        self._mesh.save_plot(_os.fspath(path), str(source))


def envelope(points, *, alpha=None, correction="efron", threads=0, length_unit=None, robot=None,
             provenance=None):
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
        the files (default: the unit of robot or provenance, else "unrecorded", as mcws_envelope
        for a cloud that records none).
    robot, provenance: what the points are of, as measure()'s: the result's robot and tip, and
        the robot and tip the saved mesh's comment names (None and none without them).

    Returns an Envelope: .vertices (V, 3), .triangles (T, 3), .volume, .units, .robot, .tip,
    .save(path),
    .drawing(azimuth) and the rest of mcws_envelope --json: the same numbers and, saved, the same
    file as the tool for the same points. The GIL is released; Ctrl-C interrupts within about a
    second (more than 65536 points are triangulated in pieces so it can: the same mesh as the
    tool's).

    Raises mcws.UsageError for a bad alpha, correction, threads or length_unit, robot or
    provenance (as measure()); mcws.Error for too few distinct points, a flat cloud, or an offset
    that does not converge.
    """
    robot, provenance = _record_arguments(robot, provenance)
    return Envelope(_envelope(_positions(points), alpha, correction, threads, length_unit, robot,
                              provenance))
