"""Example 03 (Python): an arm path planned under base sway, checked on fresh base poses.

scenarios/maintenance4.yaml, the maintenance-arm patent's example: the four-joint arm turns from
[0, 0, 0, 0] to [pi rad, 10 cm, 0.5236 rad, 10 cm] beside a twin bundle while its body swings
about the conductor and slides along it. mcws.plan picks, among candidate roadmap paths, one that
stays free for the sampled sway, then validates it against the plain shortest path on 300 fresh
base poses. Checks: the chosen path runs from the start to the goal, is no shorter than the
shortest and collides no more often, and the reported 95 % intervals are Wilson's closed form.
Usage: python3 03_plan_under_sway.py   (PYTHONPATH=build/python)
"""
import math
import os
import sys

import numpy as np

import mcws

scenarios = os.environ.get("MCWS_SCENARIOS_DIR",
                           os.path.join(os.path.dirname(__file__), "../../scenarios"))
plan = mcws.plan(os.path.join(scenarios, "maintenance4.yaml"), seed=1, validation_poses=300)
v = plan.validation
print(f"status {plan.status}; chosen path: {len(plan.path)} waypoints, length D "
      f"{v['chosen_length']:.2f}, collision probability {v['chosen_collision_probability']:.3f}"
      f"; shortest: D {v['shortest_length']:.2f}, {v['shortest_collision_probability']:.3f} "
      f"(on {v['poses']} fresh base poses)")


def wilson(k, n, z=1.959963984540054):
    """The 95 % Wilson score interval of k events in n trials."""
    p, d = k / n, 1 + z * z / n
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
    return (p + z * z / (2 * n)) / d - half, (p + z * z / (2 * n)) / d + half


ends = np.allclose(plan.path[[0, -1]], [[0, 0, 0, 0], [math.pi, 10, 0.5236, 10]], atol=1e-9)
rows = {row["name"]: row for row in v["rows"]}
intervals = all(np.allclose(rows[name]["interval_95"],
                            wilson(rows[name]["colliding_poses"], v["poses"]), atol=1e-12)
                for name in ("chosen", "shortest"))
safer = v["chosen_collision_probability"] <= v["shortest_collision_probability"]
longer = v["chosen_length"] >= v["shortest_length"] - 1e-9
sys.exit(0 if plan.status == "ok" and ends and intervals and safer and longer else 1)
