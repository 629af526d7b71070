"""mcws.read_pcd, mcws.read_provenance and mcws.write_pcd: the library's reader and writer, the
provenance line, and the errors naming the file."""

import numpy as np
import pytest

import mcws


def test_write_then_read_keeps_every_field_and_the_robot(tmp_path, deicing):
    points = mcws.sample(deicing, 500, seed=4)
    path = tmp_path / "cloud.pcd"
    mcws.write_pcd(path, points, robot=deicing)
    cloud = mcws.read_pcd(path)
    assert cloud.dtype.names == ("x", "y", "z", "q1", "q2", "q3", "q4", "q5", "q6", "q7", "q8", "label")
    for name in points.dtype.names:
        np.testing.assert_array_equal(cloud[name], points[name])
    provenance = mcws.read_provenance(path)
    assert provenance["robot"] == "deicing"
    assert provenance["file"] == "deicing.yaml"
    assert provenance["length_unit"] == "cm"
    assert len(provenance["sha256"]) == 64
    assert "sampling" not in provenance


def test_hidden_joint_bytes_are_written_as_zero(tmp_path, deicing):
    points = mcws.sample(deicing, 10)
    raw = points.view(np.uint8).reshape(10, -1)
    raw[:, 32:48] = 0xFF  # q5..q8 of WorkspacePoint: outside the robot's 4 joints
    path = tmp_path / "cloud.pcd"
    mcws.write_pcd(path, points)
    cloud = mcws.read_pcd(path)
    assert not cloud["q5"].any() and not cloud["q8"].any()


def test_plain_positions_and_other_layouts(tmp_path):
    xyz = np.array([[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]])
    path = tmp_path / "xyz.pcd"
    mcws.write_pcd(path, xyz)
    cloud = mcws.read_pcd(path)
    np.testing.assert_array_equal(cloud["y"], [1.0, 4.0])
    assert not cloud["label"].any()
    records = np.zeros(2, dtype=[("z", "f8"), ("x", "f4"), ("y", "f4"), ("q1", "f8"), ("label", "i4")])
    records["z"], records["q1"], records["label"] = (7, 8), (0.5, 0.25), (2, 3)
    mcws.write_pcd(path, records)
    cloud = mcws.read_pcd(path)
    np.testing.assert_array_equal(cloud["z"], [7, 8])
    np.testing.assert_array_equal(cloud["q1"], [0.5, 0.25])
    np.testing.assert_array_equal(cloud["label"], [2, 3])


def test_read_pcd_keeps_a_foreign_files_fields(tmp_path):
    path = tmp_path / "xyzi.pcd"
    path.write_text(
        "VERSION .7\nFIELDS x y z intensity\nSIZE 4 4 4 8\nTYPE F F F F\nCOUNT 1 1 1 1\n"
        "WIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\n1 2 3 0.5\n4 5 6 0.25\n")
    cloud = mcws.read_pcd(path)
    assert cloud.dtype.names == ("x", "y", "z", "intensity")
    assert cloud["intensity"].dtype == np.float64
    np.testing.assert_array_equal(cloud["intensity"], [0.5, 0.25])
    np.testing.assert_array_equal(cloud["z"], np.float32([3, 6]))
    assert mcws.read_provenance(path) is None


def test_errors_name_the_file(tmp_path):
    missing = tmp_path / "missing.pcd"
    with pytest.raises(mcws.Error, match="missing.pcd"):
        mcws.read_pcd(missing)
    bad = tmp_path / "bad.pcd"
    bad.write_text("VERSION .7\nFIELDS x y z\nthis is not a header\n")
    with pytest.raises(mcws.Error, match="bad.pcd"):
        mcws.read_pcd(bad)
    with pytest.raises(mcws.Error, match="nowhere"):
        mcws.write_pcd(tmp_path / "nowhere" / "x.pcd", np.zeros((1, 3)))


def test_bad_points_and_provenance(tmp_path, deicing):
    path = tmp_path / "x.pcd"
    with pytest.raises(mcws.UsageError, match="field 'speed'"):
        mcws.write_pcd(path, np.zeros(2, dtype=[("x", "f4"), ("y", "f4"), ("z", "f4"), ("speed", "f4")]))
    with pytest.raises(mcws.UsageError, match="has no field 'z'"):
        mcws.write_pcd(path, np.zeros(2, dtype=[("x", "f4"), ("y", "f4")]))
    with pytest.raises(mcws.UsageError, match=r"shape \(2, 4\)"):
        mcws.write_pcd(path, np.zeros((2, 4)))
    with pytest.raises(mcws.UsageError, match="not both"):
        mcws.write_pcd(path, np.zeros((2, 3)), robot=deicing, provenance={})
    with pytest.raises(mcws.UsageError, match="^provenance: "):
        mcws.write_pcd(path, np.zeros((2, 3)), provenance={"robot": "r"})
    with pytest.raises(mcws.UsageError, match="^provenance: "):
        mcws.write_pcd(path, np.zeros((2, 3)), provenance={
            "robot": "r", "file": "r.yaml", "sha256": "0" * 63, "length_unit": "cm"})
    assert not path.exists()
