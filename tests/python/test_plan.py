"""mcws.plan against mcws_plan on the same scenario, seed and validation poses (the report but
for its seconds, the path's CSV byte for byte; the tool on 2 threads, the function on 1), the
path against the scenario's start and goal, and bad input."""

import json
import math
import os
from pathlib import Path

import numpy as np
import pytest

import mcws
from conftest import run_tool

SCENARIOS = Path(os.environ.get("MCWS_SCENARIOS_DIR",
                                Path(__file__).resolve().parents[2] / "scenarios"))
PLANAR2 = SCENARIOS / "planar2.yaml"  # start [-20 deg, 10 deg], goal [-160 deg, -10 deg]


def timeless(report):
    """The report without its wall times (keys ending in "seconds")."""
    if isinstance(report, dict):
        return {k: timeless(v) for k, v in report.items() if not k.endswith("seconds")}
    if isinstance(report, list):
        return [timeless(v) for v in report]
    return report


@pytest.fixture(scope="module")
def planned():
    return mcws.plan(PLANAR2, seed=3, validation_poses=50, threads=1)


def test_plan_is_mcws_plan(planned, tmp_path):
    csv = tmp_path / "tool.csv"
    # The tool on two threads, the function on one: the same plan.
    _, out, _ = run_tool("plan", "--scenario", PLANAR2, "--seed", 3, "--validation-poses", 50,
                         "--threads", 2, "--output", csv, "--json")
    assert timeless(dict(planned)) == timeless(json.loads(out))
    own = tmp_path / "own.csv"
    planned.save(own)
    assert own.read_bytes() == csv.read_bytes()


def test_plan_path_runs_from_start_to_goal(planned):
    path = planned.path
    assert path.dtype == np.float64 and path.shape[1] == 2
    np.testing.assert_allclose(path[0], np.radians([-20, 10]), rtol=0, atol=1e-12)
    np.testing.assert_allclose(path[-1], np.radians([-160, -10]), rtol=0, atol=1e-12)
    np.testing.assert_array_equal(path, np.array(planned.chosen["waypoints"]))
    assert planned.status == "ok"
    assert math.isfinite(planned.chosen["length"])


def test_plan_errors(tmp_path):
    with pytest.raises(mcws.Error, match=r"missing.yaml"):
        mcws.plan(tmp_path / "missing.yaml")
    with pytest.raises(mcws.UsageError, match=r"seed: -1 is negative"):
        mcws.plan(PLANAR2, seed=-1)
    with pytest.raises(mcws.UsageError, match=r"validation_poses: -5 is not in 0 \.\. 100000000"):
        mcws.plan(PLANAR2, validation_poses=-5)
