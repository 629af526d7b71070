"""mcws.plan and mcws.Plan, mcws.behave and mcws.Behavior (imported into mcws)."""

import json as _json
import os as _os
import tempfile as _tempfile

from ._mcws import _behave, _plan
from ._record import _Record


class Plan(_Record):
    """An arm plan under base sway, as mcws_plan gives it: a dict of its --json report (keys also
    attributes; every number's unit in its key or under "units"): status, accepted_round, the
    rounds with their candidates and shared-node decisions, chosen (the accepted path's
    length, probability, vertices, waypoints, collision counts and interval), validation, ...

    path: the chosen path, a float64 (K, dof) array of joint values [rad | length unit] (the
        waypoints of mcws_plan --output), or None when no path was accepted.
    save(path): the path's CSV, byte for byte mcws_plan --output (raises mcws.Error naming the
        file and the status when no path was accepted).
    save_plot(path, cells=120), save_offsets_plot(path): mcws_plan --plot's and --plot-offsets'
        pictures.
    """

    def __init__(self, core):
        super().__init__(_json.loads(core.report()))
        self._core = core
        self.path = core.path()

    def save(self, path):
        """Writes the chosen path as mcws_plan --output does: D (the distance along it, scaled
        as the report's distance_unit says) then one column per joint, units in the names."""
        self._core.save(_os.fspath(path))

    def save_plot(self, path, cells=120):
        """Writes the configuration space of a two-joint robot as a PNG, as mcws_plan --plot
        does (gnuplot): each of cells x cells cells (4 .. 2000, default 120) coloured by the
        fraction of the base poses for which it collides [1], with the candidate paths, the
        chosen path, the shared nodes and the decision taken at each (joint values in rad or the
        length unit): the tool's bytes for the same scenario and seed.

        Raises mcws.UsageError for a robot of another joint count or a bad cells; mcws.Error
        naming the file when no path was accepted, gnuplot fails or path cannot be written.
        """
        self._core.save_plot(_os.fspath(path), cells)

    def save_offsets_plot(self, path):
        """Writes P, the whole-path free fraction and the lower end of its 95 % interval [1] of
        each base offset's best path against the offset [length unit] as a PNG, as mcws_plan
        --plot-offsets does (every offset's round planned again, with the GIL released: seconds
        to minutes): the tool's bytes for the same scenario and seed.

        Raises mcws.Error naming the file when no path was accepted, gnuplot fails or path
        cannot be written.
        """
        self._core.save_offsets_plot(_os.fspath(path))


def plan(scenario, seed=None, validation_poses=None, threads=0, progress=None):
    """Plans the arm of a robot whose base sways on the line, as mcws_plan: candidate paths
    through a roadmap for the measured base pose, their segments checked for base poses drawn
    from the scenario's sway, the dominant path taken at every shared node, the base shifted
    along the line until a path is accepted; the chosen path validated on fresh base poses.

    scenario: the scenario file (str or os.PathLike, .yaml; see scenarios/).
    seed: seed of the base poses and the roadmap, a whole number >= 0 (None: the scenario's).
    validation_poses: fresh base poses of the validation (None: the scenario's; 0 skips it).
    threads: worker threads, 0 = all cores.
    progress: True for progress lines on stderr, or a callable called with (done, total) of
        each stage (roadmap, validation) on the calling thread. Ctrl-C interrupts within a
        fraction of a second (within the roadmap's growth, the segments' checks and the
        validation too).

    Returns a Plan (the report as a dict, .path, .save(path)): the report of mcws_plan --json
    and the file of --output for the same scenario, seed and validation poses. When no path is
    accepted (the tool's exit 1) the report's status says why and .path is None.

    Raises mcws.Error naming the scenario file (and line) for a missing or malformed scenario or
    robot; mcws.UsageError for a bad seed, validation_poses or threads.
    """
    return Plan(_plan(_os.fspath(scenario), seed, validation_poses, threads, progress))


class Behavior(_Record):
    """A rehearsal of the cleaning job, as mcws_behave gives it: a dict of its --json summary
    (keys also attributes; units in the key names): status, discs_requested, discs_cleaned,
    final_disc, duration_s, steps, subtasks_completed, behaviors_run, commands_sent,
    phase_one_s, phase_two_s, battery_voltage_end_V, battery_charge_used_Ah, battery_alarm_t_s,
    faults, invariant, safety_stop, plan.

    log: the event log as a list of dicts, one per record ("t" [s], "step", "subtask",
        "task_state", "cb", "state", "event", "behavior", "disc", "detail", ...), the records of
        mcws_behave --log after its header line.
    failure: why the run failed (mcws_behave's exit 1: a violated invariant, an empty battery, a
        safety stop, the time limit), or None.
    pose_findings: the model's pose-check messages (mcws_behave prints them on stderr).
    """


def behave(model, insulators, faults=None, *, log=None, timeline=None, timeline_period=0.1):
    """Rehearses the cleaning job of Wang et al. 2018 on the simulated insulator-cleaning robot,
    as mcws_behave --insulators: the task plan for the discs run by the task machine, the
    combined behaviours' state machines and the basic behaviours on a time-stepped robot (dt
    0.01 s), the faults injected and the safety invariant checked at every step.

    model: the behaviour model file (.yaml, see robots/).
    insulators: discs to clean, 1 .. 200.
    faults: a fault file (.yaml, see scenarios/faults/), or None.
    log: also write the event log there (JSON lines, mcws_behave --log's bytes), or None.
    timeline: write the timeline there (CSV, --timeline), or None; timeline_period: between its
        rows [s], a whole multiple of 0.01 s (default 0.1).

    Returns a Behavior (the summary as a dict, .log, .failure, .pose_findings): the summary
    and files of mcws_behave with the same arguments. A failed run is returned, not raised.

    Raises mcws.Error naming the file (and line) for a missing or malformed model or fault
    file; mcws.UsageError for a bad insulators or timeline_period.
    """
    model, faults = _os.fspath(model), None if faults is None else _os.fspath(faults)
    timeline = None if timeline is None else _os.fspath(timeline)
    with _tempfile.TemporaryDirectory() as folder:
        log_file = _os.fspath(log) if log is not None else _os.path.join(folder, "log.jsonl")
        summary, failure, findings = _behave(model, insulators, faults, log_file, timeline,
                                             timeline_period)
        with open(log_file, encoding="utf-8") as lines:
            records = [_json.loads(line) for line in lines][1:]  # after the header
    result = Behavior(_json.loads(summary))
    result.log = records
    result.failure = failure or None
    result.pose_findings = findings
    return result
