"""mcws.reach_map, mcws.ReachMap, mcws.reach_study and mcws.place (imported into mcws)."""

import json as _json
import os as _os

import numpy as _np

from ._mcws import (Robot, UsageError, _default_map_cache, _parse_length, _place, _reach_map,
                    _reach_study, _ReachMap)
from ._record import _Record


def _length(value, name, robot, allow_zero=False):
    """A length argument in the robot's unit: a string with its unit as the tools' length flags
    take it ("2cm", "0.5m", "20mm"; a bare "0.02" in the robot's unit), converted; a number (or
    None) as it is, checked where it is used."""
    if isinstance(value, str):
        return _parse_length(value, name, robot, allow_zero)
    return value


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
        .header["manipulability"]["manipulability_unit"], for a map built or loaded alike; 0
        without it);
    count: uint64 (V,) the samples that fell in the voxel.

    header: the map file's header as a dict (robot, robot_file, robot_sha256, length_unit,
        samples, seed, collision, manipulability); length_unit: its length unit.
    summary: mcws_reach --json's summary but for files, processes and seconds (a dict, with
        "robot", the robot's name, and "tip", the frame mapped: a URDF robot's tip link, a D-H
        robot's "tool"), or None for a map read with ReachMap.load.
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

    def save_halfcut(self, path):
        """Writes the half-cut view (as ROS Reuleaux shows a map cut open: the voxels of the slab
        one voxel thick at y = 0 seen along y, coloured by reachability, lengths in the map's
        unit) as a PNG, as mcws_reach --halfcut does (gnuplot): its bytes for the same map.

        Raises mcws.Error when gnuplot fails or path cannot be written.
        """
        self._map.save_halfcut(_os.fspath(path))

    def save_histogram(self, path):
        """Writes the histogram of the reachability index D over the voxels (20 bins of width
        0.05) as a PNG, as mcws_reach --histogram does (gnuplot): its bytes for the same map.

        Raises mcws.Error when gnuplot fails or path cannot be written.
        """
        self._map.save_histogram(_os.fspath(path))


def reach_map(robot, resolution, samples, seed=0, threads=0, *, orientations=200, rolls=1,
              manipulability=True, collision=False, quality_task=None, length=None,
              progress=None):
    """The reachability map of a robot, as mcws_reach builds it: joint values drawn uniformly
    within their limits (sample i's values depend only on seed and i, the joint values of
    sample(robot, samples, seed)) through forward kinematics to the tool pose, whose point falls
    in a cubic voxel of edge resolution and whose orientation in one of orientations x rolls bins.

    robot: an mcws.Robot.
    resolution: the voxel edge [length unit] (the robot's .length_unit), > 0; or a string with
        its unit, as mcws_reach --resolution takes it ("2cm", "0.02m", "20mm").
    samples: joint samples (int >= 1; mcws_reach's default is 5e8, 1e7 gives a first look).
    seed: random seed, a whole number >= 0 (mcws_reach's default is 1).
    threads: worker threads, 0 = all cores. The map is the same for any thread count.
    orientations: approach-direction bins on the sphere, 1 .. 65536 (default 200).
    rolls: roll bins about the approach (default 1: any roll counts).
    manipulability: compute the Jacobian and keep each voxel's best manipulability (mcws_reach
        --no-manipulability is False).
    collision: count only collision-free samples (the robot file's collision model).
    quality_task, length: how manipulability is measured, as sample(quality=True); length
        [length unit] may also be a string with its unit ("50cm").
    progress: True for progress lines on stderr as mcws_reach writes them, or a callable called
        with (samples done, samples) after each chunk; None: silent.

    Returns a ReachMap: .save(path) writes the file mcws_reach --map writes for the same
    arguments, byte for byte; .save_points(path) its --output. The GIL is released; Ctrl-C
    interrupts (KeyboardInterrupt) between chunks of 4 million samples.

    Raises mcws.UsageError for a bad resolution, samples, seed, threads, orientations, rolls,
    quality_task or length (a string: the message of the tools' length flags, "resolution: '2x'
    is not a finite number"); mcws.Error for collision=True without collision geometry, a tool
    point beyond the grid's index range, or no sample counted.
    """
    if not isinstance(robot, Robot):
        raise UsageError(f"robot: {type(robot).__name__} is not an mcws.Robot")
    resolution = _length(resolution, "resolution", robot)
    length = _length(length, "length", robot)
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
    for output and seconds (keys also attributes): robot (the robot's name), tip (the frame
    placed on the targets: a URDF robot's tip link, a D-H robot's "tool"), length_unit, targets,
    reached, solved, share_reached [1],
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
    seconds (keys also attributes): robot and tip (as ReachStudy's), length_unit, targets,
    positions, map (its grid and where it came from),
    manipulability, collision, approach_tolerance_deg [deg], candidates (per position: offset
    [length unit], map_share and ik_share [1], map_score and ik_score; ik_* None where IK did not
    confirm it) and best (the best confirmed candidate with reached and base_position [length
    unit], or None).

    points: per position a record x, y, z (where the base frame lands [length unit]), map_share,
        map_score, ik_share, ik_score (-1 where not confirmed).
    save(path): those points as mcws_place --output writes them.
    save_plot(path): the map's and the confirmed IK share reached against the offset along x, a
        PNG as mcws_place --plot draws it (gnuplot; lengths in the robot's unit).
    """

    def save_plot(self, path):
        """Writes the map's and the confirmed IK share of the targets reached [1] against the
        base offset along x [length unit], a PNG, as mcws_place --plot does (gnuplot): its bytes
        for the same arguments.

        Raises mcws.Error when gnuplot fails or path cannot be written.
        """
        self._core.save_plot(_os.fspath(path))


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
        [length unit] (default 0), >= 0; or a string with its unit, as mcws_reach --standoff
        takes it ("5cm").
    approach_tolerance: the largest accepted approach (or orientation) error [deg] in [0, 180]
        (default 0: exact).
    ik_starts: IK starting joint vectors per target, 1 .. 1000 (default 4).
    seed: random seed of the starts, a whole number >= 0 (mcws_reach's default is 1).
    threads: worker threads, 0 = all cores. The result does not depend on it.
    collision: use the robot file's collision model when it has one (mcws_reach --no-collision
        is False).
    quality_task, length: how manipulability is measured, as sample(quality=True); length
        [length unit] may also be a string with its unit ("50cm").
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
    standoff = _length(standoff, "standoff", robot, allow_zero=True)
    length = _length(length, "length", robot)
    core = _reach_study(robot, _targets_argument(targets), normals, standoff,
                        approach_tolerance, ik_starts, seed, threads, collision, quality_task,
                        length, progress)
    return ReachStudy(core, robot.dof)


def place(robot, targets, line, across=(0.0,), up=(0.0,), *, normals=None, map=None,
          resolution=None, samples=None, orientations=200, rolls=1, manipulability=True,
          confirm=0, confirm_margin=0.1, standoff=0.0, approach_tolerance=0.0, ik_starts=4, seed=0, threads=0,
          collision=True, quality_task=None, length=None, map_cache=None, progress=None):
    """Where to put the robot's base so its arm reaches the targets, as mcws_place: the whole
    robot moved by every offset of line (x) x across (y) x up (z), the environment of its
    collision model staying in place; each position scored from a reachability map (the share
    of targets whose voxel and approach bin the map marks reached, their mean best
    manipulability); every position whose map share is within confirm_margin of the best, and
    the best `confirm` by the map, solved by inverse kinematics as reach_study.

    robot, targets, normals, standoff, approach_tolerance, ik_starts, seed, threads, collision,
        quality_task, length: as reach_study() (seed also draws a map built here; standoff and
        length also strings with their unit, "5cm").
    progress: as reach_study()'s, for the samples of a map built here, then for the positions
        confirmed.
    line, across, up: base offsets along x, y, z [length unit], sequences of values (the
        tool's "first last step" is first + k step, k = 0, 1, ...; numpy.arange gives them).
    map: an mcws.ReachMap of this robot file (mcws_reach --map read with ReachMap.load, or
        reach_map()), without collision filtering; or None and resolution [length unit; or a
        string with its unit, "2cm", as reach_map()'s] and
        samples to build one here, counting the samples free of self-collision (when
        collision and the robot file has a collision model), with orientations, rolls and
        manipulability as reach_map().
    confirm_margin: a share of the targets in 0..1 (default 0.1, as mcws_place's
        --confirm-margin): every position whose map share is at least the best map share less
        it is confirmed by IK; None: no margin.
    confirm: the best positions by the map confirmed besides: a number >= 0 (default 0, as
        --confirm) or None for all.
    map_cache: for a map built here, a folder of maps kept between calls, as mcws_place
        --map-cache: a map built from the same inputs (robot file and kinematics, collision
        model with its meshes, grid, samples, seed, manipulability) is read from it instead of
        being built again, and one built is stored in it; True: mcws_place's default folder
        ($XDG_CACHE_HOME/mcws/reach-maps, else ~/.cache/mcws/reach-maps), which the tool then
        shares; None (default): no cache, nothing written. A damaged entry is rebuilt with a
        RuntimeWarning; so is a failure to store one (the call goes on). After a store the
        folder's oldest maps are removed until they take at most 2 GiB (the environment
        variable MCWS_MAP_CACHE_LIMIT_MB, in MiB; 0: no limit), as the tool does, with a
        RuntimeWarning saying what went. The summary then has map_cache (directory, path,
        reused, stored) as the tool's --json.
    The summary's map.about names where the map came from: the file ReachMap.load read,
    "reach_map()", "built" (here) or "cache" (with built_utc).

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
    resolution = _length(resolution, "resolution", robot)
    standoff = _length(standoff, "standoff", robot, allow_zero=True)
    length = _length(length, "length", robot)
    map_cache = _map_cache_folder(map_cache)
    core = _place(robot, _targets_argument(targets), normals,
                  [float(v) for v in _np.atleast_1d(line)],
                  [float(v) for v in _np.atleast_1d(across)],
                  [float(v) for v in _np.atleast_1d(up)],
                  -1 if confirm is None else confirm, confirm_margin,
                  None if map is None else map._map,
                  resolution, 0 if samples is None else samples, orientations, rolls,
                  manipulability, standoff, approach_tolerance, ik_starts, seed, threads,
                  collision, quality_task, length, map_cache, progress)
    return Placement(core)


def _map_cache_folder(map_cache):
    """place()'s map_cache as the folder the C++ part takes ("": none)."""
    if map_cache is None or map_cache is False:
        return ""
    if map_cache is True:
        folder = _default_map_cache()
        if not folder:
            raise UsageError("map_cache=True: neither XDG_CACHE_HOME nor HOME is set")
        return folder
    if not isinstance(map_cache, (str, _os.PathLike)):
        raise UsageError(f"map_cache: {type(map_cache).__name__} is not a folder, True or None")
    folder = _os.fspath(map_cache)
    if not folder:
        raise UsageError("map_cache: empty (a folder, True or None)")
    return folder
