"""mcws.behave against mcws_behave on the same model, discs and faults (the summary, the log and
timeline files byte for byte), the run against its plan (Wang et al. 2018: CB1 and CB2 per disc
down the string, CB3 per disc back up), and bad input."""

import json
import os
from pathlib import Path

import pytest

import mcws
from conftest import ROBOTS, run_tool

MODEL = str(ROBOTS / "insulator_cleaner_behaviors.yaml")
FAULTS = str(Path(os.environ.get("MCWS_SCENARIOS_DIR",
                                 Path(__file__).resolve().parents[2] / "scenarios"))
             / "faults" / "link_lost.yaml")


def test_behave_is_mcws_behave(tmp_path):
    log, timeline = tmp_path / "tool.jsonl", tmp_path / "tool.csv"
    _, out, _ = run_tool("behave", "--model", MODEL, "--insulators", 2, "--faults", FAULTS,
                         "--log", log, "--timeline", timeline, "--json")
    own_log, own_timeline = tmp_path / "own.jsonl", tmp_path / "own.csv"
    run = mcws.behave(MODEL, 2, FAULTS, log=own_log, timeline=own_timeline)
    assert dict(run) == json.loads(out)
    assert own_log.read_bytes() == log.read_bytes()
    assert own_timeline.read_bytes() == timeline.read_bytes()
    lines = log.read_text().splitlines()
    assert run.log == [json.loads(line) for line in lines[1:]]
    assert any(r["event"] == "fault_injected" for r in run.log) and run.faults


def test_behave_runs_its_plan():
    run = mcws.behave(MODEL, 3)
    assert run.status == "completed" and run.failure is None
    assert run.discs_cleaned == 3 and run.final_disc == 0
    assert [s["cb"] for s in run.plan] == ["CB1", "CB2"] * 3 + ["CB3"] * 3
    assert run.log[0]["event"] == "run_start" and run.log[-1]["event"] == "run_end"
    seqs = [r["seq"] for r in run.log if r["event"] == "command"]
    assert seqs == list(range(1, run.commands_sent + 1))
    assert run.invariant["holds"] is True


def test_behave_errors(tmp_path):
    with pytest.raises(mcws.UsageError, match=r"insulators: 0 is not in 1 \.\. 200"):
        mcws.behave(MODEL, 0)
    with pytest.raises(mcws.UsageError, match=r"timeline_period: "):
        mcws.behave(MODEL, 1, timeline_period=0.015)
    with pytest.raises(mcws.UsageError, match=r"^timeline_period: inf is not a finite time > 0"):
        mcws.behave(MODEL, 1, timeline_period=float("inf"))
    with pytest.raises(mcws.Error, match=r"missing.yaml"):
        mcws.behave(tmp_path / "missing.yaml", 1)
