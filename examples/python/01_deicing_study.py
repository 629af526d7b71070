"""Example 01 (Python): the de-icing arm's workspace study, as the tools run it.

The de-icing arm of Yin, Wang & Yu 2010 (robots/deicing.yaml, lengths in cm) in the X-Z plane
(shoulder yaw theta3 pinned at 0): sample, the boundary points, refine near them (a uniform cloud
leaves the edge sparse: -4.6 % here without), the area, the 3-D envelope of the whole arm, and a
picture (deicing_xz.png in the working directory) when matplotlib is installed.
Checks the area against the region's true 16352.5 cm^2 (its closed-form membership integrated on
a 0.1 cm grid: tests/deicing_region.h, docs/measure.md; the paper's own value reads 3.44 % off).
Usage: python3 01_deicing_study.py   (PYTHONPATH=build/python, MCWS_ROBOTS_DIR=robots)
"""
import os
import sys

import numpy as np

import mcws

EXACT_AREA = 16352.5  # cm^2
robots = os.environ.get("MCWS_ROBOTS_DIR", os.path.join(os.path.dirname(__file__), "../../robots"))
robot = mcws.Robot(os.path.join(robots, "deicing.yaml"))

# 50000 samples in the X-Z plane (same seed, same cloud for any thread count), their edge, 50000
# more near it, and the area of all (no edge correction: the refined edge is dense).
cloud = mcws.sample(robot, 50_000, seed=1, fix={"theta3": 0.0})
edge = mcws.boundary(cloud, "xz")
cloud = np.concatenate([cloud, mcws.refine(robot, cloud[edge], 50_000, seed=2)])
edge = np.concatenate([edge, np.zeros(50_000, bool)])
area = mcws.measure(cloud, "xz", correction="none", length_unit=robot.length_unit)
error = 100 * (area.area / EXACT_AREA - 1)
print(f"{len(cloud)} samples, {edge.sum()} on the first boundary; area {area.area:.1f} "
      f"{area.units['area']} (true {EXACT_AREA} cm^2, error {error:+.3f} %)")

# The whole arm (theta3 free): its envelope, a closed triangle mesh, and its volume.
env = mcws.envelope(mcws.sample(robot, 20_000, seed=3), length_unit=robot.length_unit)
print(f"envelope: {len(env.vertices)} vertices, {len(env.triangles)} triangles, "
      f"volume {env.volume:.0f} {env.units['volume']}")

try:
    import matplotlib
    matplotlib.use("Agg")  # no display needed
    import matplotlib.pyplot as plt
    plt.scatter(cloud["x"], cloud["z"], s=0.2, c="0.7")
    plt.scatter(cloud["x"][edge], cloud["z"][edge], s=1, c="r")
    plt.gca().set(aspect="equal", xlabel="x [cm]", ylabel="z [cm]", title="de-icing arm, X-Z")
    plt.savefig("deicing_xz.png", dpi=100)
    print("picture: deicing_xz.png")
except ImportError:
    print("matplotlib is not installed (Debian: python3-matplotlib): no picture")

# Check: the area within 0.5 % of the true one (-0.004 % with these seeds); every boundary point
# within the reach 50 + 70 cm.
reach = np.hypot(cloud["x"][edge], cloud["z"][edge])
sys.exit(0 if abs(error) < 0.5 and reach.max() <= 120 + 1e-3 else 1)
