"""Shared fixtures of the Python API tests: the robots and the tools (CTest passes their paths in
MCWS_*_EXE, as tests/CMakeLists.txt passes them to test_apps), and a runner for a tool."""

import json
import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROBOTS = Path(os.environ.get("MCWS_ROBOTS_DIR", Path(__file__).resolve().parents[2] / "robots"))


@pytest.fixture(autouse=True, scope="session")
def _own_map_cache(tmp_path_factory):
    """The tools the tests run store their map cache here (mcws_place keeps the maps it builds under
    $XDG_CACHE_HOME), never in the home directory."""
    os.environ["XDG_CACHE_HOME"] = str(tmp_path_factory.mktemp("cache"))


def robot_path(name):
    """The path of robots/<name>."""
    return str(ROBOTS / name)


def tool(name):
    """The path of tool mcws_<name>, from $MCWS_<NAME>_EXE (set by CTest)."""
    path = os.environ.get(f"MCWS_{name.upper()}_EXE")
    if not path:
        pytest.skip(f"MCWS_{name.upper()}_EXE is not set (run through ctest -R python_api)")
    return path


def run_tool(name, *args, expect=0):
    """Runs mcws_<name> with args; returns (exit code, stdout, stderr), checking the exit code."""
    result = subprocess.run([tool(name), *map(str, args)], capture_output=True, text=True)
    assert result.returncode == expect, result.stderr
    return result.returncode, result.stdout, result.stderr


def tool_json(name, *args):
    """The JSON object mcws_<name> ... --json prints."""
    return json.loads(run_tool(name, *args, "--json")[1])


def interrupted_cpu(robot_file, call):
    """Runs `call` (Python text using `mcws` and `robot`, an mcws.Robot of robot_file) in a child
    interpreter, sends it SIGINT 0.3 s after the call starts and checks that the call ends with
    KeyboardInterrupt before it returns; returns the child's CPU time [s], to compare with the
    whole call's (without the checks for signals inside the call, Python would raise
    KeyboardInterrupt only after all of it)."""
    script = (
        "import mcws\n"
        f"robot = mcws.Robot({robot_file!r})\n"
        "print('started', flush=True)\n"
        f"{call}\n"
        "print('finished', flush=True)\n"
    )
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline() == "started\n"
    time.sleep(0.3)
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=120)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    assert "finished" not in out
    assert err.rstrip().endswith("KeyboardInterrupt")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


@pytest.fixture(scope="session")
def ta1400():
    import mcws

    return mcws.Robot(robot_path("ta1400.yaml"))


@pytest.fixture(scope="session")
def deicing():
    import mcws

    return mcws.Robot(robot_path("deicing.yaml"))
