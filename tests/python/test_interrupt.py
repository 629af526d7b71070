"""Ctrl-C within a second in the calls that run long between their stages (mcws.envelope,
mcws.plan, mcws.measure): SIGINT sent from a timer thread while the call runs on the main thread ends it with
KeyboardInterrupt within about a second; after an interrupted envelope the next one in the same
interpreter gives what a fresh one gives (nothing half-done is left behind). The envelope, whose Python call inserts the
points in pieces so it can stop between them, is the tool's mesh byte for byte on a cloud of
several pieces."""

import json
import os
import subprocess
import sys
from pathlib import Path

import mcws
from conftest import run_tool

SCENARIOS = Path(os.environ.get("MCWS_SCENARIOS_DIR",
                                Path(__file__).resolve().parents[2] / "scenarios"))

# From the signal to KeyboardInterrupt [s]: the library checks every few milliseconds of work,
# the bindings look at most every 50 ms, and an uninterruptible step (the envelope's local
# spacing, a piece of 65536 points of its triangulation) lasts well under a second on two cores;
# the rest is headroom for a loaded machine. A functional bound, not a speed benchmark.
LATENCY_BOUND = 1.5
SIGNAL_AFTER = 0.5  # [s] into the call

# A child interpreter: `setup`, then `call` on the main thread with SIGINT sent by a timer
# thread SIGNAL_AFTER s after it starts; prints the seconds from the signal to KeyboardInterrupt
# (or "finished"), then runs `after` (which prints its result on the next line).
CHILD = """\
import json, signal, threading, time
import mcws
{setup}
main = threading.get_ident()
sent = []
def interrupt():
    sent.append(time.monotonic())
    signal.pthread_kill(main, signal.SIGINT)
timer = threading.Timer({delay}, interrupt)
timer.start()
try:
    {call}
    print("finished", flush=True)
except KeyboardInterrupt:
    print(time.monotonic() - sent[0], flush=True)
timer.join()
{after}
"""


def interrupted(setup, call, after, delay=SIGNAL_AFTER):
    """(seconds from SIGINT to KeyboardInterrupt, the line `after` printed) in a child
    interpreter (see CHILD); `delay`: when the signal is sent [s], a number or an expression of
    what `setup` defined."""
    script = CHILD.format(setup=setup, call=call, after=after, delay=delay)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    latency, after_line = result.stdout.splitlines()
    assert latency != "finished"
    return float(latency), after_line


def test_ctrl_c_interrupts_an_envelope():
    # 6 x 10^5 points of the ball: about 8 s of CPU, 6 s on two cores, uninterrupted; SIGINT at
    # 0.5 s lands in the local spacing (which cannot stop; longer with more points) or the
    # triangulation's first pieces.
    latency, after = interrupted(
        "points = mcws.sample_shape('ball', 600_000, seed=1)\n"
        "small = mcws.sample_shape('ball', 2000, seed=5)",
        "mcws.envelope(points)",
        "print(json.dumps(dict(mcws.envelope(small))))")
    assert latency < LATENCY_BOUND
    fresh = dict(mcws.envelope(mcws.sample_shape("ball", 2000, seed=5)))
    assert json.loads(after) == fresh


def test_ctrl_c_interrupts_a_plan():
    # The maintenance arm's scenario: about 25 s uninterrupted (a roadmap of 1200 milestones
    # grown for 3.6 s, then 3 validations of 10^4 base poses, 6 to 8 s each); SIGINT at 0.5 s
    # lands in the roadmap's growth.
    latency, _ = interrupted("", f"mcws.plan({str(SCENARIOS / 'maintenance4.yaml')!r})",
                             "print('done')")
    assert latency < LATENCY_BOUND


def test_ctrl_c_interrupts_a_measure_within_its_phases():
    # 6 x 10^5 points of the ball, measured once uninterrupted (2 to 4 s on two cores: local
    # spacing, exposed points, the shell's triangulation, the alpha test, the edge correction),
    # then again with SIGINT at 40 % of that time, in the triangulation or the alpha test, whose
    # stretches without a check lasted seconds before the library checked within them. The call
    # ends within the latency bound and long before the uninterrupted call would have (it had
    # 60 % of its time to go).
    latency, whole = interrupted(
        "import time\n"
        "points = mcws.sample_shape('ball', 600_000, seed=1)\n"
        "start = time.monotonic()\n"
        "mcws.measure(points)\n"
        "whole = time.monotonic() - start",
        "mcws.measure(points)",
        "print(whole)",
        delay="0.4 * whole")
    assert latency < LATENCY_BOUND
    assert latency < 0.5 * float(whole)


def test_envelope_in_pieces_is_the_tools(tmp_path):
    # 80000 points: the Python call inserts them in 2 pieces of at most 65536 (the tool in one
    # call); the Delaunay triangulation does not depend on the order, so the mesh is the same.
    path = tmp_path / "ball.pcd"
    mcws.write_pcd(path, mcws.sample_shape("ball", 80000, seed=7))
    tool_mesh = tmp_path / "tool.ply"
    run_tool("envelope", "--input", path, "--output", tool_mesh)
    own = tmp_path / "own.ply"
    mcws.envelope(mcws.read_pcd(path)).save(own, source=str(path))
    assert own.read_bytes() == tool_mesh.read_bytes()
