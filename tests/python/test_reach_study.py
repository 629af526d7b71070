"""mcws.reach_study and mcws.place against mcws_reach --targets and mcws_place on the same targets
and seeds (summaries and files byte for byte), against the planar 2R arm's closed forms (its
reachable annulus, its manipulability l1 l2 |sin q2|), the same result for threads 1 and 2, and
bad input."""

import math

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool, tool_json

# planar2: links 40 and 30 cm, |q2| <= 160 deg: the tool point reaches the annulus
# R_MIN <= r <= 70 cm of the plane z = 0, its z axis always +z.
R_MIN = math.sqrt(40**2 + 30**2 + 2 * 40 * 30 * math.cos(math.radians(160)))
RADII = [R_MIN - 2, R_MIN + 2, 40, 55, 69, 71, 5]


@pytest.fixture(scope="module")
def planar2():
    return mcws.Robot(robot_path("planar2.yaml"))


@pytest.fixture(scope="module")
def targets(tmp_path_factory):
    """Point-and-normal targets in the plane z = 0 approached along +z: points, normals, CSV."""
    angles = [0.7 * i - 2.0 for i in range(len(RADII))]
    points = np.array([[r * math.cos(t), r * math.sin(t), 0.0] for r, t in zip(RADII, angles)])
    normals = np.tile([0.0, 0.0, -1.0], (len(RADII), 1))
    path = tmp_path_factory.mktemp("targets") / "targets.csv"
    lines = ["x,y,z,normal_x,normal_y,normal_z"]
    lines += [",".join(repr(float(v)) for v in (*p, *n)) for p, n in zip(points, normals)]
    path.write_text("\n".join(lines) + "\n")
    return points, normals, path


def without(summary, *names):
    return {k: v for k, v in summary.items() if k not in names}


def test_reach_study_is_mcws_reach_targets(planar2, targets, tmp_path):
    points, normals, path = targets
    heat = tmp_path / "heat.pcd"
    expected = tool_json("reach", "--robot", robot_path("planar2.yaml"), "--targets", path,
                         "--quality-task", "position", "--seed", 2, "--output", heat)
    study = mcws.reach_study(planar2, path, quality_task="position", seed=2, threads=2)
    assert dict(study) == without(expected, "output", "seconds")
    assert (study.robot, study.tip) == ("planar2", "tool")
    own = tmp_path / "own.pcd"
    study.save(own)
    assert own.read_bytes() == heat.read_bytes()
    # The same targets given as arrays, on one thread: the same heat map.
    again = mcws.reach_study(planar2, points, normals, quality_task="position", seed=2, threads=1)
    for name in study.points.dtype.names:
        assert again.points[name].tobytes() == study.points[name].tobytes(), name
    assert dict(again) == dict(study)


def test_reach_study_is_the_planar_arm_closed_form(planar2, targets):
    points, normals, _ = targets
    study = mcws.reach_study(planar2, points, normals, quality_task="position", collision=False)
    heat = study.points
    assert heat.dtype.names[6:8] == ("q1", "q2") and "q3" not in heat.dtype.names
    for i, r in enumerate(RADII):
        reachable = R_MIN <= r <= 70
        assert heat["reached"][i] == (1.0 if reachable else 0.0), r
        if reachable:
            c2 = (r * r - 40**2 - 30**2) / (2 * 40 * 30)  # law of cosines
            assert heat["manipulability"][i] == pytest.approx(40 * 30 * math.sqrt(1 - c2 * c2),
                                                              abs=1e-3)
            assert abs(heat["q2"][i]) == pytest.approx(math.acos(c2), abs=1e-5)
            assert heat["clearance"][i] == -1.0  # no collision model used
    assert study.reached == sum(R_MIN <= r <= 70 for r in RADII)
    assert study.collision is False


def test_place_is_mcws_place(planar2, targets, tmp_path):
    _, _, path = targets
    common = ["--robot", robot_path("planar2.yaml"), "--targets", path, "--quality-task",
              "position", "--seed", 2]
    bases = tmp_path / "bases.pcd"
    expected = tool_json("place", *common, "--along", "-40 40 20", "--resolution", 5,
                         "--samples", 30000, "--map-cache", "off", "--output", bases)
    result = mcws.place(planar2, path, np.arange(-40, 41, 20), resolution=5, samples=30000,
                        quality_task="position", seed=2)
    assert dict(result) == without(expected, "output", "seconds", "map_cache")
    own = tmp_path / "own.pcd"
    result.save(own)
    assert own.read_bytes() == bases.read_bytes()
    assert mcws.read_provenance(own)["robot"] == "planar2"  # and the positions' length unit
    assert mcws.read_provenance(own)["length_unit"] == "cm"
    assert list(result.points["x"]) == [-40, -20, 0, 20, 40]  # planar2's base is at the origin
    # With a map file from mcws_reach, read by ReachMap.load, as mcws_place --map.
    map_file = tmp_path / "planar2.bin"
    run_tool("reach", "--robot", robot_path("planar2.yaml"), "--resolution", 5, "--samples",
             30000, "--quality-task", "position", "--seed", 2, "--map", map_file, "--output",
             tmp_path / "voxels.pcd")
    expected = tool_json("place", *common, "--along", "0 20 10", "--map", map_file, "--output",
                         bases, "--confirm", "all")
    result = mcws.place(planar2, path, [0, 10, 20], map=mcws.ReachMap.load(map_file),
                        quality_task="position", seed=2, confirm=None)
    assert dict(result) == without(expected, "output", "seconds")
    assert result.best is not None and result.map["about"]["source"] == str(map_file)


def test_place_shares_the_tools_map_cache(planar2, targets, tmp_path):
    # The key is the tool's: a map place() stores, mcws_place reuses, and the other way round;
    # the results are those of a map built afresh.
    _, _, path = targets
    cache = tmp_path / "cache"
    kwargs = dict(resolution=5, samples=30000, quality_task="position", seed=2)
    fresh = mcws.place(planar2, path, [-20, 0, 20], **kwargs)
    assert "map_cache" not in fresh and not cache.exists()  # None: no cache, nothing written
    stored = mcws.place(planar2, path, [-20, 0, 20], map_cache=cache, **kwargs)
    entries = list(cache.iterdir())
    assert len(entries) == 1
    assert stored.map_cache == {"directory": str(cache), "path": str(entries[0]),
                                "reused": False, "stored": True}
    assert without(dict(stored), "map_cache") == dict(fresh)
    tool = tool_json("place", "--robot", robot_path("planar2.yaml"), "--targets", path,
                     "--quality-task", "position", "--seed", 2, "--along", "-20 20 20",
                     "--resolution", 5, "--samples", 30000, "--map-cache", cache,
                     "--output", tmp_path / "bases.pcd")
    assert tool["map_cache"]["reused"] is True and tool["map"]["about"]["source"] == "cache"
    assert tool["candidates"] == fresh.candidates
    reused = mcws.place(planar2, path, [-20, 0, 20], map_cache=str(cache), **kwargs)
    assert reused.map_cache["reused"] is True and reused.map_cache["stored"] is False
    assert reused.map["about"] == tool["map"]["about"]
    assert without(dict(reused), "map_cache", "map") == without(dict(fresh), "map")
    # A damaged entry is rebuilt, with a warning naming it, and stored again.
    entries[0].write_bytes(entries[0].read_bytes()[:100])
    with pytest.warns(RuntimeWarning, match="ignoring the cached map"):
        rebuilt = mcws.place(planar2, path, [-20, 0, 20], map_cache=cache, **kwargs)
    assert rebuilt.map_cache["stored"] is True and rebuilt.candidates == fresh.candidates
    with pytest.raises(mcws.UsageError, match="map_cache is for a map built here"):
        mcws.place(planar2, path, [0.0], map=mcws.ReachMap.load(entries[0]), map_cache=cache)
    with pytest.raises(mcws.UsageError, match="map_cache: int is not a folder"):
        mcws.place(planar2, path, [0.0], map_cache=3, **kwargs)


def test_robot_and_tip_of_a_urdf_chain_are_the_tools(tmp_path):
    # The inspection arm's chain to link6 (not its flange, the whole tree's leaf): both tools and
    # both functions name that chain's tip, as --tip link6 does.
    urdf = robot_path("inspection6.urdf")
    arm = mcws.Robot(urdf, tip="link6")
    pose = arm.fk([0.3, -0.4, 0.5, 0.0, 0.2, 0.0])
    targets = tmp_path / "targets.csv"
    x, y, z = pose[:3, 3]
    targets.write_text(f"x,y,z,normal_x,normal_y,normal_z\n{x!r},{y!r},{z!r},0,0,-1\n")
    chain = ["--robot", urdf, "--tip", "link6", "--targets", targets, "--seed", 2,
             "--no-collision"]
    expected = tool_json("reach", *chain, "--approach-tolerance", "180deg", "--output",
                         tmp_path / "heat.pcd")
    study = mcws.reach_study(arm, targets, seed=2, collision=False, approach_tolerance=180)
    assert dict(study) == without(expected, "output", "seconds")
    assert (study.robot, study.tip) == (expected["robot"], "link6")
    expected = tool_json("place", *chain, "--along", "0 0.1 0.1", "--resolution", 0.2,
                         "--samples", 2000, "--map-cache", "off", "--output",
                         tmp_path / "bases.pcd")
    result = mcws.place(arm, targets, [0.0, 0.1], resolution=0.2, samples=2000, seed=2,
                        collision=False)
    assert dict(result) == without(expected, "output", "seconds", "map_cache")
    assert (result.robot, result.tip) == (expected["robot"], "link6")
    expected = tool_json("reach", "--robot", urdf, "--tip", "link6", "--resolution", 0.2,
                         "--samples", 2000, "--seed", 2, "--output", tmp_path / "map.pcd")
    summary = mcws.reach_map(arm, 0.2, 2000, seed=2).summary
    assert summary == without(expected, "output", "processes", "resumed_samples", "seconds")
    assert summary["tip"] == "link6"


def test_reach_study_and_place_errors(planar2, ta1400, targets, tmp_path):
    points, normals, _ = targets
    with pytest.raises(mcws.UsageError, match=r"targets: shape \(7, 2\) is neither"):
        mcws.reach_study(planar2, points[:, :2])
    with pytest.raises(mcws.UsageError, match=r"normals: give the \(N, 3\) surface normals"):
        mcws.reach_study(planar2, points)
    zero = normals.copy()
    zero[3] = 0
    with pytest.raises(mcws.UsageError, match=r"targets: row 3: "):
        mcws.reach_study(planar2, points, zero)
    with pytest.raises(mcws.UsageError, match=r"approach_tolerance: 200(\.0)? is not in"):
        mcws.reach_study(planar2, points, normals, approach_tolerance=200)
    with pytest.raises(mcws.Error, match=r"missing.csv"):
        mcws.reach_study(planar2, tmp_path / "missing.csv")
    with pytest.raises(mcws.UsageError, match=r"give map \(an mcws.ReachMap\) or resolution"):
        mcws.place(planar2, points, [0.0], normals=normals)
    with pytest.raises(mcws.UsageError, match=r"line: no offsets given"):
        mcws.place(planar2, points, [], normals=normals, resolution=5, samples=100)
    with pytest.raises(mcws.UsageError, match=r"confirm_margin: 1.5 is not a share"):
        mcws.place(planar2, points, [0.0], normals=normals, resolution=5, samples=100,
                   confirm_margin=1.5)
    other = mcws.reach_map(ta1400, 200.0, 1000)
    # A map of another robot is a bad argument, as the docstring says (a UsageError).
    with pytest.raises(mcws.UsageError,
                       match=r"map: reach_map\(\): the map is of robot 'ta1400'"):
        mcws.place(planar2, points, [0.0], normals=normals, map=other)


def test_a_negative_standoff_is_refused(planar2, targets):
    # As the string "-20cm" is (mcws_reach --standoff refuses a negative length): the tool point
    # would otherwise be put inside the surface.
    points, normals, _ = targets
    for standoff in (-20.0, -1e-3):
        with pytest.raises(mcws.UsageError, match=rf"standoff: {standoff!r} is less than 0"):
            mcws.reach_study(planar2, points, normals, standoff=standoff)
        with pytest.raises(mcws.UsageError, match=rf"standoff: {standoff!r} is less than 0"):
            mcws.place(planar2, points, [0.0], normals=normals, resolution=5, samples=100,
                       standoff=standoff)
    with pytest.raises(mcws.UsageError, match=r"standoff: nan is not finite"):
        mcws.reach_study(planar2, points, normals, standoff=float("nan"))
    # 0 stays accepted: the tool point on the surface.
    assert mcws.reach_study(planar2, points[:1], normals[:1], standoff=0.0).targets == 1


def test_pose_targets_are_checked_as_robot_ik_checks_a_pose(planar2):
    pose = planar2.fk([0.3, 0.5])
    good = np.stack([pose, pose])
    assert mcws.reach_study(planar2, good).reached == 2
    last_row = good.copy()
    last_row[1, 3] = [1.0, 2.0, 3.0, 4.0]
    with pytest.raises(mcws.UsageError, match=r"pose: last row is 1 2 3 4, not 0 0 0 1"):
        planar2.ik(last_row[1])
    with pytest.raises(mcws.UsageError, match=r"targets\[1\]: last row is 1 2 3 4, not 0 0 0 1"):
        mcws.reach_study(planar2, last_row)
    with pytest.raises(mcws.UsageError, match=r"targets\[1\]: last row is 1 2 3 4"):
        mcws.place(planar2, last_row, [0.0], resolution=5, samples=100)
    scaled = good.copy()
    scaled[1, :3, :3] *= 2  # |R^T R - I| = 3
    not_orthonormal = r"the rotation is not orthonormal \(\|R\^T R - I\| = "
    with pytest.raises(mcws.UsageError, match=r"pose: " + not_orthonormal + "3,"):
        planar2.ik(scaled[1])
    with pytest.raises(mcws.UsageError,
                       match=r"targets\[1\]: " + not_orthonormal + r"3, det R = 8\)"):
        mcws.reach_study(planar2, scaled)
    mirrored = good.copy()
    mirrored[0, :3, 2] *= -1  # a reflection: orthonormal, det R = -1
    with pytest.raises(mcws.UsageError,
                       match=r"targets\[0\]: " + not_orthonormal + r"0, det R = -1\)"):
        mcws.reach_study(planar2, mirrored)
    infinite = good.copy()
    infinite[1, 0, 3] = np.inf
    with pytest.raises(mcws.UsageError, match=r"targets\[1\]: holds a value that is not a finite"):
        mcws.reach_study(planar2, infinite)
