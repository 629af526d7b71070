"""mcws.envelope against mcws_envelope on the same cloud (its --json numbers, its mesh files byte
for byte, its drawing's numbers), the mesh against the divergence theorem and the ball's volume,
the same mesh for threads 1 and 2."""

import math

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool, tool_json


@pytest.fixture(scope="module")
def ball(tmp_path_factory):
    """3000 points of the unit ball, their file and mcws_envelope --json of it (with a drawing)."""
    folder = tmp_path_factory.mktemp("envelope")
    points = mcws.sample_shape("ball", 3000, seed=3)
    path = folder / "ball.pcd"
    mcws.write_pcd(path, points)
    report = tool_json("envelope", "--input", path, "--output", folder / "tool.ply", "--drawing",
                       folder / "tool.svg", "--azimuth", 30)
    return points, path, report


def test_envelope_is_mcws_envelope(ball):
    points, _, expected = ball
    result = mcws.envelope(points)
    drawing = expected.pop("drawing")
    del drawing["file"]
    for name in ("input", "output", "seconds"):
        del expected[name]
    units = {k: v for k, v in expected.pop("units").items() if "." not in k and k != "seconds"}
    assert result.units == units
    assert {k: v for k, v in result.items() if k != "units"} == expected  # every number exactly
    assert result.vertices.shape == (expected["vertices"], 3)
    assert result.triangles.shape == (expected["triangles"], 3)
    numbers = result.drawing(azimuth=30)
    drawing_units = numbers.pop("units")
    assert numbers == drawing
    assert drawing_units["front_reach"] == "unrecorded" and drawing_units["swept_angle"] == "deg"


@pytest.mark.parametrize("extension", ["ply", "stl", "vtk"])
def test_envelope_file_is_mcws_envelope_file(ball, tmp_path, extension):
    points, path, _ = ball
    tool_file, own = tmp_path / f"tool.{extension}", tmp_path / f"own.{extension}"
    run_tool("envelope", "--input", path, "--output", tool_file)
    mcws.envelope(points).save(own, source=path)
    assert own.read_bytes() == tool_file.read_bytes()


def test_envelope_of_a_robot_cloud_names_it_as_mcws_envelope(tmp_path):
    # The inspection arm's chain to link6, sampled and written with its record: the tool's JSON
    # and mesh comment name the robot and the tip; so do the function's, given the robot or the
    # file's record.
    arm = mcws.Robot(robot_path("inspection6.urdf"), tip="link6")
    points = mcws.sample(arm, 4000, seed=2)
    path = tmp_path / "arm.pcd"
    mcws.write_pcd(path, points, robot=arm)
    tool_mesh = tmp_path / "tool.stl"
    expected = tool_json("envelope", "--input", path, "--output", tool_mesh, "--correction",
                         "none")
    assert (expected["robot"], expected["tip"], expected["length_unit"]) == (arm.name, "link6",
                                                                            "m")
    for result in (mcws.envelope(points, correction="none", robot=arm),
                   mcws.envelope(mcws.read_pcd(path), correction="none",
                                 provenance=mcws.read_provenance(path))):
        assert (result.robot, result.tip, result.length_unit) == (arm.name, "link6", "m")
        assert result.volume == expected["volume"]
        own = tmp_path / "own.stl"
        result.save(own, source=path)
        assert own.read_bytes() == tool_mesh.read_bytes()


def test_envelope_mesh_is_closed_and_encloses_its_volume(ball):
    points, _, _ = ball
    result = mcws.envelope(points, threads=1)
    v, t = result.vertices, result.triangles.astype(np.int64)
    # Divergence theorem: sum of a . (b x c) / 6 over the outward triangles.
    enclosed = np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6
    assert math.isclose(enclosed, result.volume, rel_tol=1e-9)
    assert math.isclose(result.volume, 4 * math.pi / 3, rel_tol=0.02)  # the unit ball
    # Closed and oriented: every directed edge once, and its reverse once.
    edges = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    directed = set(map(tuple, edges))
    assert len(directed) == len(edges)
    assert all((b, a) in directed for a, b in directed)
    assert np.linalg.norm(v, axis=1).max() < 1.1
    again = mcws.envelope(points, threads=2)
    assert again.vertices.tobytes() == v.tobytes()
    assert again.triangles.tobytes() == result.triangles.tobytes()


def test_envelope_errors(ball, tmp_path):
    points, _, _ = ball
    with pytest.raises(mcws.UsageError, match=r"correction: 'efrom' is not one of efron, none"):
        mcws.envelope(points, correction="efrom")
    with pytest.raises(mcws.UsageError, match=r"alpha: 0.5 is not in \[1, 1000\]"):
        mcws.envelope(points, alpha=0.5)
    # Flat: no volume; the message names no tool flag (envelope() has no plane argument).
    with pytest.raises(mcws.Error, match=r"^points: the cloud is flat in z .*; envelope\(\) "
                                         r"meshes a volume \(measure\(\) and boundary\(\) take a "
                                         r"plane\)$"):
        mcws.envelope(mcws.sample_shape("disk", 500, seed=1))
    with pytest.raises(mcws.Error, match=r"^points: the cloud is flat in z .*; give plane$"):
        mcws.measure(mcws.sample_shape("disk", 500, seed=1))
    result = mcws.envelope(points)
    with pytest.raises(mcws.Error, match=r"mesh.obj: not a mesh file name"):
        result.save(tmp_path / "mesh.obj")
    with pytest.raises(mcws.UsageError, match=r"azimuth: nan is not finite"):
        result.drawing(float("nan"))
