"""mcws.measure's column cross-check, column method, leave-one-out and triangulation choices
against mcws_measure --json on the same cloud and boundary."""

import copy
import math

import numpy as np
import pytest

import mcws
from conftest import run_tool, tool_json


@pytest.fixture(scope="module")
def disk(tmp_path_factory):
    """20000 points of the unit disk, its boundary (mcws_boundary's file and mask), both files."""
    folder = tmp_path_factory.mktemp("measure")
    points = mcws.sample_shape("disk", 20000, seed=5)
    path = folder / "disk.pcd"
    mcws.write_pcd(path, points)
    rim = folder / "rim.pcd"
    run_tool("boundary", "--input", path, "--output", rim, "--plane", "xy")
    return points, path, mcws.boundary(points, "xy"), rim


@pytest.fixture(scope="module")
def ball(tmp_path_factory):
    points = mcws.sample_shape("ball", 5000, seed=6)
    path = tmp_path_factory.mktemp("ball") / "ball.pcd"
    mcws.write_pcd(path, points)
    return points, path


def assert_same(result, expected):
    """Every number of the tool's JSON, to 1e-12 relative, and its other values exactly."""
    expected = copy.deepcopy(expected)
    del expected["input"], expected["seconds"], expected["units"]["seconds"]
    assert dict(result).keys() == expected.keys()
    for key, value in expected.items():
        if isinstance(value, float):
            assert math.isclose(result[key], value, rel_tol=1e-12), key
        elif isinstance(value, dict) and key != "units":
            for name, inner in value.items():
                if isinstance(inner, float):
                    assert math.isclose(result[key][name], inner, rel_tol=1e-12), (key, name)
                else:
                    assert result[key][name] == inner, (key, name)
        else:
            assert result[key] == value, key


@pytest.mark.parametrize("settings,flags", [
    ({}, []),
    ({"column_width": 0.03}, ["--column-width", "0.03"]),
    ({"leave_one_out": "reinsert"}, ["--leave-one-out", "reinsert"]),
    ({"triangulate": "all", "correction": "none"}, ["--triangulate", "all", "--correction", "none"]),
])
def test_cross_check_is_mcws_measure_boundary(disk, settings, flags):
    points, path, mask, rim = disk
    expected = tool_json("measure", "--input", path, "--plane", "xy", "--boundary", rim, *flags)
    assert expected["cross_check"]["method"] == "column"
    assert_same(mcws.measure(points, "xy", boundary=mask, **settings), expected)
    # The boundary as points (the tool's file read back) gives the same.
    assert_same(mcws.measure(points, "xy", boundary=mcws.read_pcd(rim), **settings), expected)
    # The unit disk's area is pi; the column method reads high (its note), by well under 2 %.
    assert 0 < mcws.measure(points, "xy", boundary=mask)["cross_check"]["area"] / math.pi - 1 < 0.02


@pytest.mark.parametrize("width", [None, 0.03])
def test_column_method_is_mcws_measure_column(disk, width):
    points, path, mask, rim = disk
    flags = ["--column-width", width] if width else []
    expected = tool_json("measure", "--input", path, "--plane", "xy", "--boundary", rim,
                         "--method", "column", *flags)
    result = mcws.measure(points, "xy", boundary=mask, method="column", column_width=width)
    assert_same(result, expected)
    assert result.method == "column" and result.columns > 0


@pytest.mark.parametrize("settings,flags", [
    ({"leave_one_out": "reinsert"}, ["--leave-one-out", "reinsert"]),
    ({"triangulate": "all"}, ["--triangulate", "all"]),
])
def test_volume_choices_are_mcws_measure(ball, settings, flags):
    points, path = ball
    result = mcws.measure(points, **settings)
    assert_same(result, tool_json("measure", "--input", path, *flags))
    # Every choice counts the same: the default's numbers, to the rounding of the sum.
    default = mcws.measure(points)
    assert math.isclose(result.volume, default.volume, rel_tol=1e-12)
    assert result.outside == default.outside
    # Both triangulate every point (reinsert needs all of them), the default a shell.
    assert result.triangulated == len(points) > default.triangulated


def test_measure_choice_errors(disk, ball):
    points, _, mask, _ = disk
    cases = [
        (dict(plane="xy", method="columns"), r"^method: 'columns' is not delaunay or column$"),
        (dict(plane="xy", method="column"), r"^method 'column' measures an area: give plane and"),
        (dict(plane="xy", leave_one_out="star2"), r"^leave_one_out: 'star2' is not star or"),
        (dict(plane="xy", triangulate="some"), r"^triangulate: 'some' is not shell or all$"),
        (dict(plane="xy", column_width=0.1), r"^column_width applies to the column method"),
        (dict(plane="xy", boundary=mask, column_width=50), r"^column_width: 50 is not 0 or in"),
        (dict(plane="xy", boundary=mask, column_width=float("nan")),
         r"^column_width: nan is not a finite length$"),
        (dict(plane="xy", boundary=mask, column_width=-1), r"^column_width: -1 is less than 0$"),
        (dict(plane="xy", boundary=mask[:10]), r"^boundary: a mask of shape \(10,\), not"),
        (dict(plane="xy", boundary=mask, method="column", alpha=3),
         r"^alpha does not apply to method 'column'$"),
        (dict(boundary=mask), r"^boundary: the column cross-check measures an area: give plane"),
    ]
    for settings, message in cases:
        with pytest.raises(mcws.UsageError, match=message):
            mcws.measure(points, **settings)
    elsewhere = mcws.sample_shape("disk", 100, seed=9)
    with pytest.raises(mcws.Error, match=r"^boundary: point 0 \(.*\) is not one of points"):
        mcws.measure(points, "xy", boundary=elsewhere)


def test_measure_in_pieces_is_mcws_measure(tmp_path):
    # 100000 points of a disk, all triangulated: with the Ctrl-C check set (always in Python) the
    # points are sorted once and inserted in 2 pieces of at most 65536, the tool's in one call:
    # the same triangulation, so the same numbers.
    points = mcws.sample_shape("disk", 100000, seed=8)
    path = tmp_path / "disk.pcd"
    mcws.write_pcd(path, points)
    expected = tool_json("measure", "--input", path, "--plane", "xy", "--triangulate", "all")
    result = mcws.measure(points, "xy", triangulate="all")
    assert result.triangulated == 100000
    assert_same(result, expected)
