"""mcws.refine against mcws_refine on the same boundary points and seed, the same bytes for threads
1 and 2, and against its definition: each new sample within the spread of its parent, its
position the forward kinematics of its joints."""

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool


@pytest.fixture(scope="module")
def deicing_boundary(tmp_path_factory):
    """The de-icing arm's X-Z boundary as the tools make it (theta3 pinned, collision labels)."""
    folder = tmp_path_factory.mktemp("refine")
    cloud, boundary = folder / "cloud.pcd", folder / "boundary.pcd"
    run_tool("sample", "--robot", robot_path("deicing.yaml"), "--samples", 3000, "--seed", 5,
             "--fix", "theta3=0", "--collision", "--output", cloud)
    run_tool("boundary", "--input", cloud, "--plane", "xz", "--output", boundary)
    return boundary


def test_refine_is_mcws_refine(tmp_path, deicing, deicing_boundary):
    out = tmp_path / "refined.pcd"
    run_tool("refine", "--robot", robot_path("deicing.yaml"), "--input", deicing_boundary,
             "--samples", 2000, "--seed", 4, "--spread", 0.2, "--output", out)
    expected = mcws.read_pcd(out)
    parents = mcws.read_pcd(deicing_boundary)
    points = mcws.refine(deicing, parents, 2000, seed=4, spread=0.2, collision=True, threads=2)
    assert points.dtype == mcws.sample(deicing, 0).dtype
    for name in points.dtype.names:
        np.testing.assert_array_equal(points[name], expected[name], err_msg=name)
    assert set(np.unique(points["label"])) > {0}  # labelled, as the cloud was
    # The same bytes on one thread, and with the pinned joint named instead of inferred.
    again = mcws.refine(deicing, parents, 2000, seed=4, spread=0.2, collision=True, threads=1,
                        fix={"theta3": 0.0})
    for name in points.dtype.names:
        assert again[name].tobytes() == points[name].tobytes(), name


def test_refine_stays_within_the_spread_of_its_parent(ta1400):
    cloud = mcws.sample(ta1400, 4000, seed=2)
    parents = cloud[mcws.boundary(cloud)]
    points = mcws.refine(ta1400, parents, 3000, seed=9, spread=0.05)
    joints = [f"q{i}" for i in range(1, ta1400.dof + 1)]
    q = np.stack([points[name] for name in joints], axis=1).astype(np.float64)
    parent_q = np.stack([parents[name] for name in joints], axis=1).astype(np.float64)
    parent_q = parent_q[np.arange(len(points)) % len(parents)]  # sample i's parent: i mod P
    low, high = ta1400.limits[:, 0], ta1400.limits[:, 1]
    step = 0.05 * (high - low)
    assert np.all(np.abs(q - parent_q) <= step * (1 + 1e-6) + 1e-6)
    assert np.all((q >= low - 1e-6) & (q <= high + 1e-6))
    assert np.any(np.abs(q - parent_q) > 0.5 * step)  # they do move
    # The position is the tool point of the joint values (float32 as a PCD holds it).
    tool = ta1400.fk(q, check_limits=False)[:, :3, 3]  # a float32 limit rounds outward
    xyz = np.stack([points["x"], points["y"], points["z"]], axis=1)
    np.testing.assert_allclose(xyz, tool, rtol=0, atol=1e-4 * np.abs(tool).max())


def test_refine_errors(ta1400):
    cloud = mcws.sample(ta1400, 500, seed=1)
    with pytest.raises(mcws.UsageError, match=r"boundary_points: has no field 'q1'"):
        mcws.refine(ta1400, np.zeros((5, 3)), 10)
    with pytest.raises(mcws.UsageError, match=r"spread: 0(\.0)? is not in \(0, 1\]"):
        mcws.refine(ta1400, cloud, 10, spread=0)
    outside = cloud.copy()
    outside["q2"][3] = 100.0
    with pytest.raises(mcws.UsageError, match=r"boundary_points: point 3: q2 = 100 is outside"):
        mcws.refine(ta1400, outside, 10)
    with pytest.raises(mcws.UsageError, match=r"no boundary points to refine"):
        mcws.refine(ta1400, cloud[:0], 10)


def test_refine_refuses_the_points_of_a_robot_with_more_joints(deicing):
    planar2 = mcws.Robot(robot_path("planar2.yaml"))
    cloud = mcws.sample(deicing, 200, seed=1)  # q1..q4
    assert deicing.dof == 4 and planar2.dof == 2
    with pytest.raises(mcws.UsageError,
                       match=rf"boundary_points: point 0 has q3 = {float(cloud['q3'][0])!r}, "
                             r"but robot 'planar2' has 2 joints"):
        mcws.refine(planar2, cloud, 5, seed=1)
    # A file's q1..q8: 0 beyond the dof, as a cloud of planar2 holds them, is refined.
    own = mcws.sample(planar2, 200, seed=1)
    padded = np.zeros(200, dtype=mcws._point_dtype(4, False))
    for name in own.dtype.names:
        padded[name] = own[name]
    assert len(mcws.refine(planar2, padded, 5, seed=1)) == 5
