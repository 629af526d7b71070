"""mcws.plan and mcws.Plan (imported into mcws)."""

import json as _json
import os as _os

from ._mcws import _plan
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
    """

    def __init__(self, core):
        super().__init__(_json.loads(core.report()))
        self._core = core
        self.path = core.path()

    def save(self, path):
        """Writes the chosen path as mcws_plan --output does: D (the distance along it, scaled
        as the report's distance_unit says) then one column per joint, units in the names."""
        self._core.save(_os.fspath(path))


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
        each stage (roadmap, validation) on the calling thread; Ctrl-C interrupts there.

    Returns a Plan (the report as a dict, .path, .save(path)): the report of mcws_plan --json
    and the file of --output for the same scenario, seed and validation poses. When no path is
    accepted (the tool's exit 1) the report's status says why and .path is None.

    Raises mcws.Error naming the scenario file (and line) for a missing or malformed scenario or
    robot; mcws.UsageError for a bad seed, validation_poses or threads.
    """
    return Plan(_plan(_os.fspath(scenario), seed, validation_poses, threads, progress))
