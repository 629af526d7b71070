"""mcws.reach_map and mcws.ReachMap against mcws_reach on the same arguments (the map file and the
voxel PCD byte for byte, its --json summary), against the samples the map is made of (each one's
pose reached, the counts adding up), the same map for threads 1 and 2, and bad input."""

import numpy as np
import pytest

import mcws
from conftest import interrupted_cpu, robot_path, tool_json

# The TA1400's map at 10 cm (the robot's unit is mm): small and fast.
ARGS = {"resolution": 100.0, "samples": 20000, "seed": 3, "orientations": 50}


@pytest.fixture(scope="module")
def tool_map(tmp_path_factory):
    """mcws_reach's map file, voxel PCD and --json summary for ARGS."""
    folder = tmp_path_factory.mktemp("reach")
    map_file, points = folder / "tool.bin", folder / "tool.pcd"
    summary = tool_json("reach", "--robot", robot_path("ta1400.yaml"), "--resolution",
                        ARGS["resolution"], "--samples", ARGS["samples"], "--seed", ARGS["seed"],
                        "--orientations", ARGS["orientations"], "--map", map_file,
                        "--output", points)
    return map_file, points, summary


@pytest.fixture(scope="module")
def own_map(ta1400):
    return mcws.reach_map(ta1400, **ARGS)


def test_reach_map_is_mcws_reach(tool_map, own_map, tmp_path):
    map_file, points, summary = tool_map
    own_file, own_points = tmp_path / "own.bin", tmp_path / "own.pcd"
    own_map.save(own_file)
    own_map.save_points(own_points)
    assert own_file.read_bytes() == map_file.read_bytes()
    assert own_points.read_bytes() == points.read_bytes()
    for name in ("output", "processes", "resumed_samples", "seconds"):
        del summary[name]
    assert own_map.summary == summary
    assert (own_map.summary["robot"], own_map.summary["tip"]) == ("ta1400", "tool")
    cloud = mcws.read_pcd(points)
    assert len(own_map) == len(cloud) == summary["voxels"]
    for axis, name in enumerate("xyz"):
        np.testing.assert_array_equal(own_map.centres[:, axis].astype(np.float32), cloud[name])
    np.testing.assert_array_equal(own_map.reachability.astype(np.float32), cloud["reachability"])
    np.testing.assert_array_equal(own_map.manipulability, cloud["manipulability"])
    np.testing.assert_array_equal(own_map.count, cloud["count"])


def test_reach_map_is_made_of_the_samples(ta1400, own_map):
    # The map's samples are sample()'s joint values for the same seed (float32 here: a pose may
    # move by ~1e-4 mm, far from a voxel's or a bin's edge for these samples).
    samples = mcws.sample(ta1400, ARGS["samples"], seed=ARGS["seed"])
    q = np.stack([samples[f"q{i}"] for i in range(1, 7)], axis=1).astype(np.float64)
    poses = ta1400.fk(q, check_limits=False)
    assert own_map.count.sum() == ARGS["samples"]
    found = own_map.query(poses[:, :3, 3], poses[:, :3, :3])
    assert found["reached"].all()
    assert found["reached"].dtype == np.bool_
    np.testing.assert_array_equal(found["voxel"] >= 0, True)
    # Each voxel's count is the number of samples that fell in it.
    np.testing.assert_array_equal(np.bincount(found["voxel"], minlength=len(own_map)),
                                  own_map.count)
    # D is the share of the 50 bins reached; centres are the voxels' middles.
    bins = own_map.reachability * ARGS["orientations"]
    np.testing.assert_allclose(bins, np.round(bins), atol=1e-9)
    np.testing.assert_array_equal(own_map.centres, (own_map.voxels + 0.5) * ARGS["resolution"])
    # The approach direction alone is reached too; a point far outside is in no voxel.
    assert own_map.query(poses[:, :3, 3], poses[:, :3, 2])["reached"].all()
    far = own_map.query([1e5, 0, 0], [0, 0, 1])
    assert far["voxel"] == -1 and not far["reached"] and far["count"] == 0


def test_reach_map_threads_and_load(ta1400, tool_map, own_map, tmp_path):
    map_file, _, _ = tool_map
    one = mcws.reach_map(ta1400, **ARGS, threads=1)
    two = mcws.reach_map(ta1400, **ARGS, threads=2)
    one.save(tmp_path / "one.bin")
    two.save(tmp_path / "two.bin")
    assert (tmp_path / "one.bin").read_bytes() == (tmp_path / "two.bin").read_bytes()
    loaded = mcws.ReachMap.load(map_file)
    assert loaded.summary is None and loaded.length_unit == "mm"
    assert loaded.header["robot"] == "ta1400" and loaded.header["samples"] == ARGS["samples"]
    for name in ("voxels", "centres", "reachability", "manipulability", "count"):
        np.testing.assert_array_equal(getattr(loaded, name), getattr(own_map, name), name)
    loaded.save(tmp_path / "again.bin")
    assert (tmp_path / "again.bin").read_bytes() == map_file.read_bytes()


def test_reach_map_errors(ta1400, own_map, tmp_path):
    with pytest.raises(mcws.UsageError, match=r"resolution: 0(\.0)? is not a positive length"):
        mcws.reach_map(ta1400, 0, 100)
    with pytest.raises(mcws.UsageError, match=r"samples: 0 is not >= 1"):
        mcws.reach_map(ta1400, 100.0, 0)
    with pytest.raises(mcws.UsageError, match=r"orientations: 0 is not in 1 \.\. 65536"):
        mcws.reach_map(ta1400, 100.0, 100, orientations=0)
    with pytest.raises(mcws.UsageError, match=r"points: shape \(4, 2\) is not \(N, 3\)"):
        own_map.query(np.zeros((4, 2)))
    with pytest.raises(mcws.UsageError, match=r"directions: row 1 is not finite"):
        own_map.query(np.zeros((2, 3)), [[0, 0, 1], [0, 0, 0]])
    missing = tmp_path / "missing.bin"
    with pytest.raises(mcws.Error, match=r"missing.bin: cannot open the reachability map"):
        mcws.ReachMap.load(missing)
    bad = tmp_path / "bad.bin"
    bad.write_bytes(b"not a map")
    with pytest.raises(mcws.Error, match=r"bad.bin"):
        mcws.ReachMap.load(bad)


def test_ctrl_c_interrupts_a_long_map():
    # 2e9 samples through forward kinematics on one thread: several minutes of CPU. SIGINT ends
    # the call between chunks of 4 194 304 samples (about a second each).
    cpu = interrupted_cpu(robot_path("ta1400.yaml"),
                          "mcws.reach_map(robot, 100.0, 2_000_000_000, threads=1, "
                          "manipulability=False)")
    assert cpu < 15.0  # seconds; the whole call takes about 400 s of CPU


def test_the_manipulability_unit_is_where_the_docstring_says(tmp_path):
    # planar2 (cm) has 2 joints: manipulability of the position task, l1 l2 |sin q2| [cm^2].
    arm = mcws.Robot(robot_path("planar2.yaml"))
    built = mcws.reach_map(arm, 5.0, 3000)
    built.save(tmp_path / "m.bin")
    loaded = mcws.ReachMap.load(tmp_path / "m.bin")
    assert loaded.summary is None
    assert '.header["manipulability"]["manipulability_unit"]' in mcws.ReachMap.__doc__
    for reach in (built, loaded):
        assert reach.header["manipulability"]["manipulability_unit"] == "cm^2"
