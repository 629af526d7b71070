"""mcws.boundary and mcws.measure against mcws_boundary and mcws_measure on the same cloud, and
against the disk's and the ball's closed forms."""

import math

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool, tool_json


def xyz(points):
    return np.stack([points["x"], points["y"], points["z"]], axis=1)


def shape_cloud(tmp_path_factory, shape, seed):
    """20000 points of a validation shape, and the PCD file they were written to."""
    points = mcws.sample_shape(shape, 20000, seed=seed)
    path = tmp_path_factory.mktemp(shape) / (shape + ".pcd")
    mcws.write_pcd(path, points)
    return points, path


@pytest.fixture(scope="module")
def disk(tmp_path_factory):
    return shape_cloud(tmp_path_factory, "disk", 2)


@pytest.fixture(scope="module")
def ball(tmp_path_factory):
    return shape_cloud(tmp_path_factory, "ball", 3)


@pytest.fixture(scope="module")
def annulus(tmp_path_factory):
    return shape_cloud(tmp_path_factory, "annulus", 4)


def sorted_rows(rows):
    """The rows of an (N, 3) array in lexicographic order (x, then y, then z)."""
    return rows[np.lexsort(rows.T[::-1])]


@pytest.mark.parametrize("shape,plane,settings,flags", [
    ("disk", "xy", {}, []),
    ("disk", "xy", {"radius": 0.05, "hull_depth": 0}, ["--radius", "0.05", "--hull-depth", "0"]),
    ("ball", None, {}, []),
    ("disk", "xy", {"method": "grid"}, ["--method", "grid"]),
    ("disk", "xy", {"method": "grid", "cell": 0.04}, ["--method", "grid", "--cell", "0.04"]),
    ("ball", None, {"method": "grid"}, ["--method", "grid"]),
    ("ball", None, {"method": "grid", "cell": 0.15}, ["--method", "grid", "--cell", "0.15"]),
    ("annulus", "xy", {"method": "extremum"}, ["--method", "extremum"]),
    ("annulus", "xy", {"method": "extremum", "cell": 0.05, "gap": 0.3},
     ["--method", "extremum", "--cell", "0.05", "--gap", "0.3"]),
])
def test_boundary_is_mcws_boundary(disk, ball, annulus, tmp_path, shape, plane, settings, flags):
    points, path = {"disk": disk, "ball": ball, "annulus": annulus}[shape]
    out = tmp_path / "boundary.pcd"
    run_tool("boundary", "--input", path, "--output", out, *(["--plane", plane] if plane else []),
             *flags)
    mask = mcws.boundary(points, plane, **settings)
    assert mask.dtype == np.bool_ and mask.shape == (len(points),)
    written = xyz(mcws.read_pcd(out))
    # The grid method writes a cell's representative in the cells' order, the mask keeps the
    # input's: the same points, each once (the shapes' float32 positions are distinct).
    assert 0 < mask.sum() == len(written) < len(points)
    np.testing.assert_array_equal(sorted_rows(xyz(points[mask])), sorted_rows(written))


def test_extremum_finds_the_annulus_hole(annulus):
    # The annulus 0.5 <= r <= 1: with a gap threshold below its hole's width (1 at the centre
    # column), the extremum method finds points on the inner circle too.
    points, _ = annulus
    rim = points[mcws.boundary(points, "xy", method="extremum", cell=0.05, gap=0.3)]
    r = np.hypot(rim["x"], rim["y"])
    assert (r < 0.55).sum() > 10 and (r > 0.95).sum() > 10


def test_boundary_of_the_disk_is_its_rim(disk):
    points, _ = disk
    rim = points[mcws.boundary(points, "xy")]
    r = np.hypot(rim["x"], rim["y"])
    spacing = math.sqrt(math.pi / len(points))  # mean spacing of the 20000 points [1]
    assert r.min() > 1 - 4 * spacing
    angle = np.degrees(np.arctan2(rim["y"], rim["x"]))
    assert len(np.unique(np.floor(angle / 5))) == 72  # every 5-degree sector of the rim


def test_boundary_mask_of_non_finite_points_is_false():
    points = mcws.sample_shape("disk", 2000, seed=4)
    points["x"][7] = np.nan
    mask = mcws.boundary(points, "xy")
    assert not mask[7]


@pytest.mark.parametrize("plane", ["xy", None])
def test_measure_is_mcws_measure(disk, ball, plane):
    points, path = disk if plane else ball
    expected = tool_json("measure", "--input", path, *(["--plane", plane] if plane else []))
    result = mcws.measure(points, plane)
    key = "area" if plane else "volume"
    assert math.isclose(result[key], expected[key], rel_tol=1e-12)
    for name in ("uncorrected", "points", "triangulated", "boundary_vertices", "outside",
                 "correction", "alpha", "length_unit", "plane", "method"):
        assert result[name] == expected[name], name
    del expected["units"]["seconds"]
    assert result.units == expected["units"]
    assert dict(result).keys() == expected.keys() - {"input", "seconds"}
    # A shape's cloud records no robot: null in the tool's JSON, None here.
    assert result.robot is None is expected["robot"] and result.tip is None is expected["tip"]


@pytest.fixture(scope="module")
def arm_clouds(tmp_path_factory):
    """The inspection arm's chain to link6 (not the tree's leaf, its flange): 20000 samples
    written with the robot's record; and the de-icing arm sampled by mcws_sample at its flange."""
    folder = tmp_path_factory.mktemp("arms")
    arm = mcws.Robot(robot_path("inspection6.urdf"), tip="link6")
    points = mcws.sample(arm, 20000, seed=1)
    urdf_cloud = folder / "arm.pcd"
    mcws.write_pcd(urdf_cloud, points, robot=arm)
    flange_cloud = folder / "flange.pcd"
    run_tool("sample", "--robot", robot_path("deicing.yaml"), "--samples", 20000, "--point",
             "flange", "--output", flange_cloud)
    return arm, points, urdf_cloud, flange_cloud


def test_measure_names_the_robot_and_tip_as_mcws_measure(arm_clouds, deicing):
    arm, points, urdf_cloud, flange_cloud = arm_clouds
    expected = tool_json("measure", "--input", urdf_cloud, "--plane", "xy")
    assert (expected["robot"], expected["tip"]) == (arm.name, "link6")
    del expected["units"]["seconds"]
    expected = {k: v for k, v in expected.items() if k not in ("input", "seconds")}
    # The file's record, as read_provenance() gives it; or the robot the samples are of.
    from_file = mcws.measure(mcws.read_pcd(urdf_cloud), "xy",
                             provenance=mcws.read_provenance(urdf_cloud))
    assert dict(from_file) == expected
    assert dict(mcws.measure(points, "xy", robot=arm)) == expected
    # A D-H robot sampled at its flange: its record says so; the robot alone names its tool.
    expected = tool_json("measure", "--input", flange_cloud, "--plane", "xz")
    assert (expected["robot"], expected["tip"]) == ("deicing", "flange")
    cloud = mcws.read_pcd(flange_cloud)
    result = mcws.measure(cloud, "xz", provenance=mcws.read_provenance(flange_cloud))
    assert (result.robot, result.tip, result.length_unit) == ("deicing", "flange", "cm")
    assert result.area == expected["area"]
    result = mcws.measure(cloud, "xz", robot=deicing)
    assert (result.robot, result.tip, result.units["area"]) == ("deicing", "tool", "cm^2")


def test_measure_robot_and_provenance_errors(arm_clouds, deicing):
    arm, points, urdf_cloud, _ = arm_clouds
    provenance = mcws.read_provenance(urdf_cloud)
    with pytest.raises(mcws.UsageError, match="^give robot or provenance, not both$"):
        mcws.measure(points, "xy", robot=arm, provenance=provenance)
    with pytest.raises(mcws.UsageError, match="^robot: str is not an mcws.Robot$"):
        mcws.measure(points, "xy", robot="arm")
    with pytest.raises(mcws.UsageError, match="^provenance: give a dict"):
        mcws.envelope(points, provenance="arm")
    with pytest.raises(mcws.UsageError, match="^length_unit: 'cm' is not 'm', the unit of"):
        mcws.measure(points, "xy", robot=arm, length_unit="cm")
    with pytest.raises(mcws.UsageError, match="^provenance: "):
        mcws.measure(points, "xy", provenance={**provenance, "sha256": "12"})


def test_measure_of_the_disk_and_the_ball_are_their_closed_forms(disk, ball):
    # 20000 uniform samples: the corrected measure is within 0.2 % (BENCHMARKS.md: 0.02 % at 1e5)
    assert abs(mcws.measure(disk[0], "xy").area / math.pi - 1) < 2e-3
    assert abs(mcws.measure(ball[0]).volume / (4 * math.pi / 3) - 1) < 5e-3


def test_measure_names_its_units(disk):
    result = mcws.measure(disk[0], "xy", length_unit="cm")
    assert result.length_unit == "cm" and result.units["area"] == "cm^2"
    assert mcws.measure(disk[0], "xy").units["area"] == "unrecorded^2"


@pytest.mark.parametrize("plane,settings,flags,message", [
    ("xy", {"method": "hull"}, ["--method", "hull"],
     "method: 'hull' is not one of orthant, grid, extremum"),
    ("xy", {"cell": 0.1}, ["--cell", "0.1"], "cell does not apply to method orthant"),
    ("xy", {"method": "grid", "gap": 0.1}, ["--method", "grid", "--gap", "0.1"],
     "gap does not apply to method grid"),
    ("xy", {"method": "grid", "radius": 0.1}, ["--method", "grid", "--radius", "0.1"],
     "radius does not apply to method grid"),
    ("xy", {"method": "extremum", "threads": 2}, ["--method", "extremum", "--threads", "2"],
     "threads does not apply to method extremum"),
    (None, {"method": "extremum"}, ["--method", "extremum"],
     "method extremum works in a plane: give plane 'xy', 'xz' or 'yz'"),
    ("xy", {"method": "grid", "cell": -1}, ["--method", "grid", "--cell", "-1"],
     "cell: -1 is not a positive number"),
    ("xy", {"method": "extremum", "gap": 0}, ["--method", "extremum", "--gap", "0"],
     "gap: 0 is not a positive number"),
    ("xy", {"method": "grid", "cell": 50}, ["--method", "grid", "--cell", "50"], None),
    ("xy", {"method": "extremum", "cell": 0.0001}, ["--method", "extremum", "--cell", "0.0001"],
     None),
    ("xy", {"method": "extremum", "gap": 50}, ["--method", "extremum", "--gap", "50"], None),
])
def test_boundary_method_errors_are_mcws_boundarys(disk, tmp_path, plane, settings, flags,
                                                   message):
    points, path = disk
    with pytest.raises(mcws.UsageError) as error:
        mcws.boundary(points, plane, **settings)
    # The tool's one line (exit 2), its --flag named as the argument: "mcws_boundary: --cell: 50
    # is not in [...] [length unit] (...) (see --help)" is "cell: 50 is not in ... (...)" here.
    _, _, err = run_tool("boundary", "--input", path, "--output", tmp_path / "b.pcd",
                         *(["--plane", plane] if plane else []), *flags, expect=2)
    tool_line = err.splitlines()[0].removeprefix("mcws_boundary: ").removesuffix(" (see --help)")
    if message is None:  # a range: the tool's words exactly
        assert "is not in" in str(error.value)
        assert tool_line == "--" + str(error.value)
    else:
        assert str(error.value) == message
        # The tool refuses the same flag ("--cell does not apply to --method orthant").
        assert tool_line.startswith("--" + message.split()[0].rstrip(":"))


def test_bad_settings(disk):
    points, _ = disk
    with pytest.raises(mcws.UsageError, match="^plane: "):
        mcws.boundary(points, "xw")
    with pytest.raises(mcws.UsageError, match="^give at most one of radius, auto_radius, adaptive$"):
        mcws.boundary(points, "xy", radius=0.1, adaptive=10)
    with pytest.raises(mcws.UsageError, match=r"^radius: 50 is not in \["):
        mcws.boundary(points, "xy", radius=50)
    with pytest.raises(mcws.UsageError, match="^hull_depth works in a plane"):
        mcws.boundary(points, hull_depth=1)
    with pytest.raises(mcws.UsageError, match="^plane: points: the cloud is flat in z"):
        mcws.boundary(points, "xz")
    with pytest.raises(mcws.Error, match="^points: "):
        mcws.measure(points[:2], "xy")
    with pytest.raises(mcws.UsageError, match="^alpha: 0.5 is not in"):
        mcws.measure(points, "xy", alpha=0.5)
