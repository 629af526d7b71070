"""The tools' gnuplot pictures from Python: Envelope.save_drawing / save_plot, ReachMap.save_halfcut
/ save_histogram and Placement.save_plot against mcws_envelope --drawing / --plot, mcws_reach
--halfcut / --histogram and mcws_place --plot on the same inputs, byte for byte."""

import re
import shutil

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool

pytestmark = pytest.mark.skipif(shutil.which("gnuplot") is None, reason="gnuplot not installed")


@pytest.fixture(scope="module")
def ball(tmp_path_factory):
    points = mcws.sample_shape("ball", 4000, seed=7)
    path = tmp_path_factory.mktemp("pictures") / "ball.pcd"
    mcws.write_pcd(path, points)
    return points, path


def without_scratch_dir(picture):
    """An SVG's bytes with the name of gnuplot's scratch directory (a new temporary name each run,
    which gnuplot writes into the plots' <title> elements) made one fixed name."""
    return re.sub(rb"/mcws_plot_[A-Za-z0-9]{6}/", b"/mcws_plot_XXXXXX/", picture)


def test_envelope_pictures_are_mcws_envelopes(ball, tmp_path):
    points, path = ball
    run_tool("envelope", "--input", path, "--drawing", tmp_path / "tool.svg", "--azimuth", 30,
             "--plot", tmp_path / "tool.png")
    run_tool("envelope", "--input", path, "--drawing", tmp_path / "tool_drawing.png")
    shape = mcws.envelope(points)
    shape.save_drawing(tmp_path / "own.svg", azimuth=30, source=str(path))
    shape.save_plot(tmp_path / "own.png", source=path)
    shape.save_drawing(tmp_path / "own_drawing.png", source=path)
    for own, tool in (("own.svg", "tool.svg"), ("own.png", "tool.png"),
                      ("own_drawing.png", "tool_drawing.png")):
        assert (without_scratch_dir((tmp_path / own).read_bytes()) ==
                without_scratch_dir((tmp_path / tool).read_bytes())), own
    # The title names the cloud's file name when no robot is known, the numbers drawing() gives.
    svg = (tmp_path / "own.svg").read_text()
    assert "ball.pcd: working range" in svg
    assert f"{shape.drawing(30).max_reach:.3g}"[:3] in svg
    with pytest.raises(mcws.UsageError, match=r"drawing\.gif"):
        shape.save_drawing(tmp_path / "drawing.gif")
    with pytest.raises(mcws.UsageError, match=r"^azimuth: nan is not finite$"):
        shape.save_drawing(tmp_path / "d.png", azimuth=float("nan"))


def test_reach_and_place_pictures_are_the_tools(tmp_path):
    planar2 = mcws.Robot(robot_path("planar2.yaml"))
    run_tool("reach", "--robot", robot_path("planar2.yaml"), "--resolution", 5, "--samples",
             20000, "--seed", 2, "--map", tmp_path / "map.bin", "--output", tmp_path / "v.pcd",
             "--halfcut", tmp_path / "halfcut.png", "--histogram", tmp_path / "histogram.png")
    own = mcws.reach_map(planar2, 5, 20000, seed=2)
    own.save_halfcut(tmp_path / "own_halfcut.png")
    own.save_histogram(tmp_path / "own_histogram.png")
    assert (tmp_path / "own_halfcut.png").read_bytes() == (tmp_path / "halfcut.png").read_bytes()
    assert ((tmp_path / "own_histogram.png").read_bytes() ==
            (tmp_path / "histogram.png").read_bytes())
    # A map read back from the tool's file draws the same pictures.
    loaded = mcws.ReachMap.load(tmp_path / "map.bin")
    loaded.save_halfcut(tmp_path / "loaded.png")
    assert (tmp_path / "loaded.png").read_bytes() == (tmp_path / "halfcut.png").read_bytes()

    targets = tmp_path / "targets.csv"
    targets.write_text("x,y,z,normal_x,normal_y,normal_z\n50,0,0,0,0,-1\n0,60,0,0,0,-1\n"
                       "-30,20,0,0,0,-1\n")
    run_tool("place", "--robot", robot_path("planar2.yaml"), "--targets", targets, "--seed", 2,
             "--along", "-40 40 20", "--resolution", 5, "--samples", 20000, "--map-cache", "off",
             "--output", tmp_path / "bases.pcd", "--plot", tmp_path / "place.png")
    placed = mcws.place(planar2, targets, np.arange(-40, 41, 20), resolution=5, samples=20000,
                        seed=2)
    placed.save_plot(tmp_path / "own_place.png")
    assert (tmp_path / "own_place.png").read_bytes() == (tmp_path / "place.png").read_bytes()
    assert (tmp_path / "own_place.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plan_pictures_are_mcws_plans(tmp_path):
    scenario = robot_path("../scenarios/planar2.yaml")
    run_tool("plan", "--scenario", scenario, "--seed", 3, "--validation-poses", 50, "--threads",
             1, "--output", tmp_path / "path.csv", "--plot", tmp_path / "cspace.png", "--cells",
             40, "--plot-offsets", tmp_path / "offsets.png")
    planned = mcws.plan(scenario, seed=3, validation_poses=50, threads=1)
    planned.save_plot(tmp_path / "own_cspace.png", cells=40)
    planned.save_offsets_plot(tmp_path / "own_offsets.png")
    assert (tmp_path / "own_cspace.png").read_bytes() == (tmp_path / "cspace.png").read_bytes()
    assert (tmp_path / "own_offsets.png").read_bytes() == (tmp_path / "offsets.png").read_bytes()
    with pytest.raises(mcws.UsageError, match=r"^cells: 3 is not in 4 \.\. 2000$"):
        planned.save_plot(tmp_path / "x.png", cells=3)
