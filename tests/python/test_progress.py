"""progress= of the long calls: a callable gets (done, total) rising to total, on the calling
thread; what it raises ends the call; True writes the tools' lines on stderr only for calls
over a second; anything else is refused."""

import subprocess
import sys
import threading
import time

import pytest

import mcws
from conftest import robot_path


def recorder():
    calls = []

    def progress(done, total):
        calls.append((done, total, threading.get_ident()))

    return calls, progress


def assert_rising_to(calls, total):
    assert calls, "progress was never called"
    done = [c[0] for c in calls]
    assert done == sorted(done) and done[-1] == total
    assert all(c[1] == total for c in calls)
    assert {c[2] for c in calls} == {threading.get_ident()}  # on the calling thread


def test_progress_callbacks(ta1400):
    calls, progress = recorder()
    points = mcws.sample(ta1400, 200_000, seed=1, threads=2, progress=progress)
    assert_rising_to(calls, 200_000)
    assert len(calls) == 4  # every 65536 samples: 65536, 131072, 196608, 200000
    # The same points as without progress.
    assert points.tobytes() == mcws.sample(ta1400, 200_000, seed=1).tobytes()

    calls, progress = recorder()
    mcws.refine(ta1400, points[:100], 1000, progress=progress)
    assert_rising_to(calls, 1000)

    calls, progress = recorder()
    mcws.reach_map(ta1400, 200.0, 5000, progress=progress)
    assert_rising_to(calls, 5000)

    calls, progress = recorder()
    targets = mcws.sample(ta1400, 20, seed=5)
    xyz = [[p["x"], p["y"], p["z"]] for p in targets]
    mcws.reach_study(ta1400, xyz, [[0, 0, 1]] * 20, threads=1, progress=progress)
    assert_rising_to(calls, 20)


def test_progress_that_raises_ends_the_call(ta1400):
    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop(f"{done}/{total}")

    with pytest.raises(Stop, match=r"^65536/1000000$"):  # after the first piece
        mcws.sample(ta1400, 1_000_000, progress=stop)


def test_progress_true_writes_lines_for_long_calls():
    # 1e6 samples labelled against meshes: about 2 s of CPU, lines "mcws.sample: N% (...)".
    script = ("import mcws\n"
              f"robot = mcws.Robot({robot_path('ta1400_mesh.yaml')!r})\n"
              "mcws.sample(robot, 1_000_000, threads=1, collision=True, progress=True)\n"
              "mcws.sample(robot, 1000, progress=True)\n")
    err = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True).stderr
    lines = err.splitlines()
    assert lines and all(line.startswith("mcws.sample: ") for line in lines), err
    assert lines[-1] == "mcws.sample: 100% (1000000/1000000 samples)"  # the short call is silent


def test_bad_progress(ta1400):
    with pytest.raises(mcws.UsageError, match=r"progress: 'yes' is not True, False, None or a"):
        mcws.sample(ta1400, 10, progress="yes")


def test_sample_releases_the_gil(ta1400):
    # Another Python thread runs while sample() computes: its counter moves between two progress
    # calls (2^16 samples apart). The spinning thread gives the GIL back at every turn
    # (time.sleep(0)) and the switch interval is made 100 s, so it can run only where sample()
    # has released the GIL: held through the call, the counter could not move in between.
    counter, seen, done = [0], [], threading.Event()

    def spin():
        while not done.is_set():
            counter[0] += 1
            time.sleep(0)

    interval = sys.getswitchinterval()
    sys.setswitchinterval(100)
    spinner = threading.Thread(target=spin)
    spinner.start()
    try:
        mcws.sample(ta1400, 400_000, threads=1, progress=lambda d, n: seen.append(counter[0]))
    finally:
        done.set()
        spinner.join()
        sys.setswitchinterval(interval)
    assert len(seen) == 7
    assert max(b - a for a, b in zip(seen, seen[1:])) > 0
