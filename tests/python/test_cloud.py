"""mcws.read_pcd, mcws.read_provenance and mcws.write_pcd: the library's reader and writer, the
provenance line, and the errors naming the file."""

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool


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
    # sample()'s defaults, as mcws_sample records them without --point, --collision, --fix.
    assert provenance["sampling"] == {"point": "tool", "collision": False, "fix": {}}


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


def test_write_pcd_with_robot_is_the_file_mcws_sample_writes(tmp_path, deicing):
    own, tools = tmp_path / "own.pcd", tmp_path / "tool.pcd"
    mcws.write_pcd(own, mcws.sample(deicing, 3000, seed=5), robot=deicing)
    # measure() of the re-read cloud names the tip measure(robot=) names.
    direct = mcws.measure(mcws.sample(deicing, 3000, seed=5), "xz", robot=deicing)
    reread = mcws.measure(mcws.read_pcd(own), "xz", provenance=mcws.read_provenance(own))
    assert reread.tip == direct.tip == "tool"
    run_tool("sample", "--robot", robot_path("deicing.yaml"), "--samples", 3000, "--seed", 5,
             "--output", tools)
    assert own.read_bytes() == tools.read_bytes()
    # With sample()'s fix, collision and point given as sampling: mcws_sample's file again.
    points = mcws.sample(deicing, 3000, seed=5, fix={"theta3": 0.0}, collision=True,
                         point="flange")
    mcws.write_pcd(own, points, robot=deicing,
                   sampling={"point": "flange", "collision": True, "fix": {"theta3": 0.0}})
    run_tool("sample", "--robot", robot_path("deicing.yaml"), "--samples", 3000, "--seed", 5,
             "--fix", "theta3=0", "--collision", "--point", "flange", "--output", tools)
    assert own.read_bytes() == tools.read_bytes()
    # mcws_refine reads the boundary of the file written with robot= (it refused it before).
    mcws.write_pcd(own, mcws.sample(deicing, 3000, seed=5, fix={"theta3": 0.0}), robot=deicing,
                   sampling={"fix": {"theta3": 0.0}})
    boundary, refined = tmp_path / "boundary.pcd", tmp_path / "refined.pcd"
    run_tool("boundary", "--input", own, "--plane", "xz", "--output", boundary)
    run_tool("refine", "--robot", robot_path("deicing.yaml"), "--input", boundary, "--samples",
             100, "--output", refined)
    assert len(mcws.read_pcd(refined)) == 100


def test_write_pcd_with_robot_refuses_what_it_cannot_record(tmp_path, deicing):
    path = tmp_path / "x.pcd"
    planar2 = mcws.Robot(robot_path("planar2.yaml"))
    cloud = mcws.sample(deicing, 5)
    with pytest.raises(mcws.UsageError,
                       match=rf"points: point 0 has q3 = {float(cloud['q3'][0])!r}, but robot "
                             r"'planar2' has 2 joints"):
        mcws.write_pcd(path, cloud, robot=planar2)
    with pytest.raises(mcws.UsageError,
                       match=r"points: 2 joint fields \(q1..q2\), but robot 'deicing' has 4 "):
        mcws.write_pcd(path, mcws.sample(planar2, 5), robot=deicing)
    labelled = mcws.sample(deicing, 5)
    labelled["label"][3] = 2
    with pytest.raises(mcws.UsageError, match=r"points: point 3 has label 2, a collision label"):
        mcws.write_pcd(path, labelled, robot=deicing)
    with pytest.raises(mcws.UsageError,
                       match=r"sampling.point: 'wrist' is not one of tool, flange"):
        mcws.write_pcd(path, mcws.sample(deicing, 5), robot=deicing, sampling={"point": "wrist"})
    with pytest.raises(mcws.UsageError, match=r"sampling.fix: .*'elbow'"):
        mcws.write_pcd(path, mcws.sample(deicing, 5), robot=deicing,
                       sampling={"fix": {"elbow": 0}})
    with pytest.raises(mcws.UsageError, match=r"sampling.speed: not a key of a sampling record"):
        mcws.write_pcd(path, mcws.sample(deicing, 5), robot=deicing, sampling={"speed": 1})
    with pytest.raises(mcws.UsageError, match=r"sampling: give robot too"):
        mcws.write_pcd(path, mcws.sample(deicing, 5), sampling={"point": "tool"})
    assert not path.exists()


def test_write_pcd_refuses_an_empty_cloud_as_read_pcd_does(tmp_path, deicing):
    path = tmp_path / "empty.pcd"
    with pytest.raises(mcws.UsageError, match=r"points: none given"):
        mcws.write_pcd(path, mcws.sample(deicing, 0))
    with pytest.raises(mcws.UsageError, match=r"points: none given"):
        mcws.write_pcd(path, np.zeros((0, 3)))
    assert not path.exists()
    # What it would have written: a file read_pcd refuses.
    path.write_text("VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 0\n"
                    "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\nDATA ascii\n")
    with pytest.raises(mcws.Error, match=r"no points"):
        mcws.read_pcd(path)


def test_a_bytes_path_is_the_file_it_names(tmp_path, monkeypatch, deicing):
    monkeypatch.chdir(tmp_path)
    mcws.write_pcd(b"out.pcd", np.ones((2, 3)))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.pcd"]
    assert len(mcws.read_pcd(b"out.pcd")) == 2
    assert mcws.Robot(robot_path("deicing.yaml").encode()).name == "deicing"
    with pytest.raises(TypeError, match=r"^path: 5 \(int\) is not a path"):
        mcws.read_pcd(5)
    with pytest.raises(TypeError, match=r"^package_path: 5 \(int\) is neither a folder"):
        mcws.Robot(robot_path("deicing.yaml"), package_path=5)


def test_a_provenance_value_of_the_wrong_type_is_named(tmp_path, deicing):
    path = tmp_path / "x.pcd"
    good = {"robot": "deicing", "file": "deicing.yaml", "sha256": "0" * 64, "length_unit": "cm",
            "sampling": {"point": "tool", "collision": False, "fix": {"theta3": 0.5}}}
    mcws.write_pcd(path, np.ones((1, 3)), provenance=good)
    assert mcws.read_provenance(path)["sampling"]["fix"] == {"theta3": 0.5}
    path.unlink()
    cases = [
        ({"sampling": {**good["sampling"], "fix": {"theta3": "0.5"}}},
         r"^provenance: sampling.fix.theta3: '0.5' \(str\) is not a number"),
        ({"sampling": {**good["sampling"], "collision": "no"}},
         r"^provenance: sampling.collision: 'no' \(str\) is not a bool"),
        ({"robot": 7}, r"^provenance: robot: 7 \(int\) is not a str"),
        ({"input": {"points": -1, "sha256": "0" * 64, "boundary_points": 1}},
         r"^provenance: input.points: -1 \(int\) is not a whole number >= 0"),
        ({"sampling": {"point": "tool", "collision": False}},
         r"^provenance: no key 'sampling.fix'"),
    ]
    for change, message in cases:
        with pytest.raises(mcws.UsageError, match=message):
            mcws.write_pcd(path, np.ones((1, 3)), provenance={**good, **change})
    bare = dict(good)
    del bare["sha256"]
    with pytest.raises(mcws.UsageError, match=r"^provenance: no key 'sha256'"):
        mcws.write_pcd(path, np.ones((1, 3)), provenance=bare)
    assert not path.exists()
