"""mcws.sample and mcws.sample_shape against mcws_sample on the same arguments (its PCD read back
with mcws.read_pcd), the same bytes for any thread count, closed forms of the shapes."""

import math
import subprocess
import sys

import numpy as np
import pytest

import mcws
from conftest import interrupted_cpu, robot_path, run_tool


def tool_cloud(tmp_path, *args):
    """The cloud mcws_sample writes for args, read back, and its path."""
    out = tmp_path / "tool.pcd"
    run_tool("sample", *args, "--output", out)
    return mcws.read_pcd(out), out


def assert_same_points(points, cloud, dof, quality=False):
    names = ["x", "y", "z"] + [f"q{i}" for i in range(1, dof + 1)] + ["label"]
    if quality:
        names += ["manipulability", "inverse_condition"]
    assert list(points.dtype.names) == names
    assert len(points) == len(cloud)
    for name in names:
        np.testing.assert_array_equal(points[name], cloud[name], err_msg=name)
    for i in range(dof + 1, 9):  # the file's joints beyond the robot's are 0
        assert not cloud[f"q{i}"].any()


@pytest.mark.parametrize("name", ["ta1400.yaml", "deicing.yaml"])
def test_sample_is_mcws_sample(tmp_path, name):
    robot = mcws.Robot(robot_path(name))
    cloud, _ = tool_cloud(tmp_path, "--robot", robot_path(name), "--samples", 3000, "--seed", 7)
    points = mcws.sample(robot, 3000, seed=7)
    assert_same_points(points, cloud, robot.dof)
    assert points["x"].dtype == np.float32 and points["label"].dtype == np.uint32


def test_sample_with_fix_collision_and_quality_is_mcws_sample(tmp_path, deicing):
    cloud, path = tool_cloud(
        tmp_path, "--robot", robot_path("deicing.yaml"), "--samples", 2000, "--seed", 3,
        "--fix", "theta3=0.25", "--collision", "--quality")
    points = mcws.sample(deicing, 2000, seed=3, fix={"theta3": 0.25}, collision=True, quality=True)
    assert_same_points(points, cloud, deicing.dof, quality=True)
    np.testing.assert_array_equal(points["q1"], np.float32(0.25))
    assert set(np.unique(points["label"])) > {0}  # some samples collide
    # Written with the tool's provenance, the points make the tool's file, byte for byte.
    again = tmp_path / "again.pcd"
    mcws.write_pcd(again, points, provenance=mcws.read_provenance(path))
    assert again.read_bytes() == path.read_bytes()


def test_sample_of_the_flange_is_mcws_sample(tmp_path, ta1400):
    cloud, path = tool_cloud(
        tmp_path, "--robot", robot_path("ta1400.yaml"), "--samples", 1000, "--seed", 0,
        "--point", "flange")
    points = mcws.sample(ta1400, 1000, point="flange")
    assert_same_points(points, cloud, 6)
    again = tmp_path / "again.pcd"
    mcws.write_pcd(again, points, provenance=mcws.read_provenance(path))
    assert again.read_bytes() == path.read_bytes()


def test_sample_positions_are_fk_of_the_joint_values(ta1400):
    points = mcws.sample(ta1400, 50, seed=2)
    q = np.stack([points[f"q{i}"] for i in range(1, 7)], axis=1).astype(np.float64)
    p = ta1400.fk(q, check_limits=False)[:, :3, 3]
    xyz = np.stack([points["x"], points["y"], points["z"]], axis=1)
    # float32 joint values and positions: 1e-3 mm on 1.6 m covers both roundings (6e-8 relative)
    np.testing.assert_allclose(xyz, p, rtol=0, atol=1e-3)
    lower, upper = ta1400.limits[:, 0], ta1400.limits[:, 1]
    assert ((q >= lower - 1e-6) & (q <= upper + 1e-6)).all()


def test_same_bytes_for_one_and_two_threads(ta1400):
    one = mcws.sample(ta1400, 70000, seed=5, threads=1)  # more than one piece of 2^16
    two = mcws.sample(ta1400, 70000, seed=5, threads=2)
    assert one.tobytes() == two.tobytes()


def test_the_array_owns_the_points_without_a_copy(ta1400):
    points = mcws.sample(ta1400, 1000)
    assert points.base is not None  # the capsule holding the C++ vector
    assert points.flags.writeable
    assert points.strides == (points.dtype.itemsize,)
    view = points["x"]
    del points
    assert view.sum() == view.sum()  # still valid: the view keeps the buffer alive


def test_sample_shape_is_mcws_sample_shape(tmp_path):
    cloud, path = tool_cloud(tmp_path, "--shape", "disk", "--samples", 4000, "--seed", 9)
    points = mcws.sample_shape("disk", 4000, seed=9)
    assert list(points.dtype.names) == ["x", "y", "z", "label"]
    for name in points.dtype.names:
        np.testing.assert_array_equal(points[name], cloud[name])
    assert mcws.read_provenance(path) is None
    again = tmp_path / "again.pcd"
    mcws.write_pcd(again, points)
    assert again.read_bytes() == path.read_bytes()


def test_shapes_are_uniform_in_their_closed_forms():
    n = 40000
    disk = mcws.sample_shape("disk", n, seed=1)
    r2 = disk["x"].astype(float) ** 2 + disk["y"].astype(float) ** 2
    assert r2.max() <= 1 + 1e-6 and not disk["z"].any()
    # uniform in area: r^2 is uniform on [0, 1], mean 1/2, standard deviation 1/sqrt(12)
    assert abs(r2.mean() - 0.5) < 5 / math.sqrt(12 * n)
    ball = mcws.sample_shape("ball", n, seed=1)
    r = np.sqrt(sum(ball[a].astype(float) ** 2 for a in "xyz"))
    # uniform in volume: r^3 is uniform on [0, 1]
    assert r.max() <= 1 + 1e-6 and abs((r**3).mean() - 0.5) < 5 / math.sqrt(12 * n)
    box = mcws.sample_shape("box", n, seed=1)
    assert all(np.abs(box[a]).max() <= 0.5 for a in "xyz")


def test_bad_arguments(ta1400, tmp_path):
    with pytest.raises(mcws.UsageError, match="^n: -1 is negative$"):
        mcws.sample(ta1400, -1)
    with pytest.raises(mcws.UsageError, match="^seed: -2 is negative"):
        mcws.sample(ta1400, 10, seed=-2)
    with pytest.raises(mcws.UsageError, match="^threads: 999 is not in 0 .. 256"):
        mcws.sample(ta1400, 10, threads=999)
    with pytest.raises(mcws.UsageError, match="^fix: .*nope"):
        mcws.sample(ta1400, 10, fix={"nope": 0.0})
    with pytest.raises(mcws.UsageError, match="^quality_task and length need quality=True$"):
        mcws.sample(ta1400, 10, quality_task="position")
    with pytest.raises(mcws.UsageError, match="^shape: .*cube"):
        mcws.sample_shape("cube", 10)
    # the same message as mcws_sample --fix
    _, _, err = run_tool("sample", "--robot", robot_path("ta1400.yaml"), "--fix", "j2=1",
                         "--output", tmp_path / "x.pcd", expect=2)
    with pytest.raises(mcws.UsageError) as error:
        mcws.sample(ta1400, 10, fix={"j2": 1.0})
    assert err == f"mcws_sample: --{error.value} (see --help)\n"


def test_collision_needs_a_collision_model(tmp_path):
    bare = tmp_path / "bare.yaml"
    text = open(robot_path("planar2.yaml")).read().split("collision:")[0]
    bare.write_text(text)
    robot = mcws.Robot(bare)
    assert not robot.has_collision_model
    with pytest.raises(mcws.Error, match="has no collision geometry"):
        mcws.sample(robot, 10, collision=True)


def test_peak_memory_of_a_large_sample_is_the_array_alone():
    # In a fresh interpreter: the growth of the peak resident set while sampling 2e6 points
    # (128 MB of records) is the array itself, not a copy of it (at most 1.2 x its bytes).
    script = (
        "import resource, mcws\n"
        f"robot = mcws.Robot({robot_path('ta1400.yaml')!r})\n"
        "mcws.sample(robot, 10)\n"
        "before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
        "points = mcws.sample(robot, 2_000_000, seed=1)\n"
        "after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
        "print((after - before) * 1024, points.nbytes)\n"
    )
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            check=True)
    grown, nbytes = map(int, result.stdout.split())
    assert nbytes == 2_000_000 * 64
    assert grown <= 1.2 * nbytes


def test_ctrl_c_interrupts_a_long_sample():
    # 2e6 samples labelled against meshes, with their quality, on one thread: about 24 s of CPU.
    # SIGINT 0.3 s after the call starts ends it with KeyboardInterrupt before it returns, within
    # a piece of 2^16 samples: the child uses a fraction of that CPU time (without the check for
    # signals between pieces, Python would raise it only after the whole call).
    cpu = interrupted_cpu(robot_path("ta1400_mesh.yaml"),
                          "mcws.sample(robot, 2_000_000, threads=1, collision=True, quality=True)")
    assert cpu < 8.0  # seconds; the whole call takes about 24 s of CPU
