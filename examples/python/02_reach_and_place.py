"""Example 02 (Python): a reachability map and where to stop the base, for the planar 2R arm.

robots/planar2.yaml: links 40 and 30 cm, |q2| <= 160 deg, so its tool point reaches the ring
R_MIN <= r <= 70 cm of the plane z = 0 (law of cosines), with manipulability 40 * 30 |sin q2| cm^2.
The map (5 cm voxels) must lie on that ring; three targets on the line (x = 95, 105, 125 cm,
approached from above) and the base moved along x from 0 to 180 cm: each position must reach the
targets the ring says, with the closed form's mean manipulability, and the best must be the
closed form's best. Usage: python3 02_reach_and_place.py   (PYTHONPATH=build/python)
"""
import math
import os
import sys

import numpy as np

import mcws

robots = os.environ.get("MCWS_ROBOTS_DIR", os.path.join(os.path.dirname(__file__), "../../robots"))
arm = mcws.Robot(os.path.join(robots, "planar2.yaml"))
R_MIN = math.sqrt(40**2 + 30**2 + 2 * 40 * 30 * math.cos(math.radians(160)))  # 15.6 cm

reach = mcws.reach_map(arm, 5.0, 30_000, seed=2, quality_task="position")
radius = np.hypot(reach.centres[:, 0], reach.centres[:, 1])
half_diagonal = 5.0 * math.sqrt(3) / 2  # a voxel meets the ring: its centre is this close to it
on_ring = (radius > R_MIN - half_diagonal) & (radius < 70 + half_diagonal)
print(f"map: {len(reach)} voxels, centres at r in [{radius.min():.1f}, {radius.max():.1f}] cm")

targets = np.array([[95.0, 0, 0], [105.0, 0, 0], [125.0, 0, 0]])
normals = np.tile([0.0, 0, -1], (3, 1))  # the tool's z axis against the normal: +z
offsets = np.arange(0.0, 181.0, 10.0)
placed = mcws.place(arm, targets, offsets, normals=normals, map=reach, quality_task="position",
                    collision=False, confirm=None)  # confirm every position by IK


def closed_form(offset):
    """(share reached, mean manipulability [cm^2], 0 for a target not reached) from x = offset."""
    r = np.abs(targets[:, 0] - offset)
    ok = (r >= R_MIN) & (r <= 70)
    c2 = np.clip((r**2 - 40**2 - 30**2) / (2 * 40 * 30), -1, 1)
    return ok.mean(), np.where(ok, 1200 * np.sqrt(1 - c2**2), 0).mean()


expected = [closed_form(o) for o in offsets]
right = len(placed.candidates) == len(offsets) and all(
    c["ik_share"] == share and abs(c["ik_score"] - score) < 0.1
    for c, (share, score) in zip(placed.candidates, expected))
best = offsets[int(np.argmax([share * 1e6 + score for share, score in expected]))]
print(f"best base offset {placed.best['offset'][0]} cm (closed form {best} cm), reaching "
      f"{placed.best['reached']} of 3, mean manipulability {placed.best['ik_score']:.1f} cm^2")
sys.exit(0 if on_ring.all() and right and placed.best["offset"][0] == best else 1)
