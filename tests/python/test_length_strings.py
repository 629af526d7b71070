"""Lengths written with their unit ("10cm", "0.1m") in reach_map(), reach_study() and place(),
against mcws_reach and mcws_place given the same text, and their errors against the tools'
messages."""

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool, tool_json


def without(summary, *names):
    return {k: v for k, v in summary.items() if k not in names}


def test_reach_map_resolution_and_length_with_units(ta1400, tmp_path):
    # The TA1400's unit is mm: "10cm" is 100 mm, "1.5m" 1500 mm.
    map_file = tmp_path / "tool.bin"
    summary = tool_json("reach", "--robot", robot_path("ta1400.yaml"), "--resolution", "10cm",
                        "--length", "1.5m", "--samples", 5000, "--seed", 3, "--orientations",
                        20, "--map", map_file, "--output", tmp_path / "tool.pcd")
    own = mcws.reach_map(ta1400, "10cm", 5000, seed=3, orientations=20, length="1.5m")
    assert own.resolution == 100.0 and summary["resolution"] == 100.0
    own.save(tmp_path / "own.bin")
    assert (tmp_path / "own.bin").read_bytes() == map_file.read_bytes()
    # The same map as the lengths given as numbers in the robot's unit.
    plain = mcws.reach_map(ta1400, 100.0, 5000, seed=3, orientations=20, length=1500.0)
    plain.save(tmp_path / "plain.bin")
    assert (tmp_path / "plain.bin").read_bytes() == map_file.read_bytes()


def test_place_and_reach_study_lengths_with_units(tmp_path):
    planar2 = mcws.Robot(robot_path("planar2.yaml"))  # unit cm
    points = np.array([[50.0, 0.0, 0.0], [0.0, 60.0, 0.0], [-30.0, 20.0, 0.0]])
    normals = np.tile([0.0, 0.0, -1.0], (3, 1))
    path = tmp_path / "targets.csv"
    path.write_text("x,y,z,normal_x,normal_y,normal_z\n" + "".join(
        ",".join(repr(float(v)) for v in (*p, *n)) + "\n" for p, n in zip(points, normals)))
    expected = tool_json("place", "--robot", robot_path("planar2.yaml"), "--targets", path,
                         "--seed", 2, "--along", "-20 20 20", "--resolution", "50mm",
                         "--standoff", "0.01m", "--samples", 20000, "--map-cache", "off",
                         "--output", tmp_path / "bases.pcd")
    result = mcws.place(planar2, path, [-20, 0, 20], resolution="50mm", standoff="0.01m",
                        samples=20000, seed=2)
    assert dict(result) == without(expected, "output", "seconds", "map_cache")
    assert dict(result) == dict(mcws.place(planar2, path, [-20, 0, 20], resolution=5.0,
                                           standoff=1.0, samples=20000, seed=2))
    study = mcws.reach_study(planar2, path, standoff="10mm", seed=2)
    assert dict(study) == dict(mcws.reach_study(planar2, path, standoff=1.0, seed=2))
    assert dict(study) == without(tool_json("reach", "--robot", robot_path("planar2.yaml"),
                                            "--targets", path, "--seed", 2, "--standoff", "10mm",
                                            "--output", tmp_path / "heat.pcd"),
                                  "output", "seconds")


@pytest.mark.parametrize("text", ["2xx", "-1cm", "0cm", "0.5 m", "1e400mm", "cm"])
def test_bad_length_strings_are_the_tools_messages(ta1400, tmp_path, text):
    with pytest.raises(mcws.UsageError) as raised:
        mcws.reach_map(ta1400, text, 10)
    # mcws_reach's one line (exit 2), its --flag named as the argument.
    _, _, err = run_tool("reach", "--robot", robot_path("ta1400.yaml"), "--resolution", text,
                         "--samples", 10, "--map", tmp_path / "m.bin", "--output",
                         tmp_path / "m.pcd", expect=2)
    tool_line = err.splitlines()[0].removeprefix("mcws_reach: ").removesuffix(" (see --help)")
    assert str(raised.value) == tool_line.replace("--resolution", "resolution")
    assert "\n" not in str(raised.value)


def test_standoff_string_may_be_zero_but_not_negative():
    planar2 = mcws.Robot(robot_path("planar2.yaml"))
    target = np.array([[50.0, 0.0, 0.0]]), np.array([[0.0, 0.0, -1.0]])
    assert mcws.reach_study(planar2, *target, standoff="0cm").targets == 1
    with pytest.raises(mcws.UsageError, match=r"^standoff: -1 is less than 0$"):
        mcws.reach_study(planar2, *target, standoff="-1cm")
    with pytest.raises(mcws.UsageError, match=r"^length: 'fifty' is not a finite number$"):
        mcws.place(planar2, target[0], [0.0], normals=target[1], resolution=5.0, samples=100,
                   quality_task="full", length="fifty")
