"""mcws.Robot: its description, fk against mcws_fk and a hand composition of the D-H table,
the Jacobian against finite differences of fk, ik against fk, and the errors for bad input."""

import math

import numpy as np
import pytest

import mcws
from conftest import robot_path, run_tool, tool_json

DEG = math.pi / 180


def rz(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def rx(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def ry(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]])


def trans(x, y, z):
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def dh(a, alpha, d, theta):
    """One row of a standard D-H table: Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    return rz(theta) @ trans(0, 0, d) @ trans(a, 0, 0) @ rx(alpha)


# robots/ta1400.yaml: a [mm], alpha [deg], d [mm]; tool xyz [mm], rpy [deg]
TA1400_DH = [(150, -90, 0), (560, 0, 0), (130, -90, 0), (0, 90, 600), (0, -90, 0), (0, 0, 0)]


def ta1400_by_hand(q):
    T = np.eye(4)
    for (a, alpha, d), qi in zip(TA1400_DH, q):
        T = T @ dh(a, alpha * DEG, d, qi)
    return T @ trans(90, 0, 330) @ ry(30 * DEG)


def random_q(robot, count, seed):
    rng = np.random.default_rng(seed)
    lower, upper = robot.limits[:, 0], robot.limits[:, 1]
    return lower + (upper - lower) * rng.random((count, robot.dof))


def test_description_of_ta1400(ta1400):
    assert ta1400.name == "ta1400"
    assert ta1400.dof == 6
    assert ta1400.joint_names == ["j1", "j2", "j3", "j4", "j5", "j6"]
    assert ta1400.joint_units == ["rad"] * 6
    assert ta1400.length_unit == "mm"
    assert ta1400.has_collision_model
    limits_deg = [(-170, 170), (-180, 50), (-120, 90), (-180, 180), (-90, 150), (-180, 180)]
    assert ta1400.limits.shape == (6, 2)
    assert ta1400.limits.dtype == np.float64
    np.testing.assert_allclose(ta1400.limits, np.array(limits_deg) * DEG, rtol=1e-15)


def test_description_of_deicing(deicing):
    assert deicing.joint_names == ["theta3", "theta1", "theta2", "a2"]
    assert deicing.joint_types == ["revolute"] * 3 + ["prismatic"]
    assert deicing.joint_units == ["rad", "rad", "rad", "cm"]
    assert deicing.length_unit == "cm"
    np.testing.assert_allclose(deicing.limits[3], [25, 70])  # the forearm's stroke [cm]


@pytest.mark.parametrize("name", ["ta1400.yaml", "deicing.yaml"])
def test_fk_is_mcws_fk(name):
    robot = mcws.Robot(robot_path(name))
    for q in random_q(robot, 4, seed=3):
        text = " ".join(repr(float(v)) for v in q)
        expected = tool_json("fk", "--robot", robot_path(name), "--q", text)
        assert expected["length_unit"] == robot.length_unit
        np.testing.assert_array_equal(robot.fk(q), np.array(expected["pose"]))
        flange = tool_json("fk", "--robot", robot_path(name), "--q", text, "--frame", "flange")
        np.testing.assert_array_equal(robot.fk(q, frame="flange"), np.array(flange["pose"]))


def test_fk_is_the_dh_table_composed_by_hand(ta1400):
    for q in random_q(ta1400, 20, seed=5):
        # 1e-9 mm on poses of about 1500 mm: rounding of two different products
        np.testing.assert_allclose(ta1400.fk(q), ta1400_by_hand(q), rtol=0, atol=1e-9)


def test_fk_of_the_deicing_arm_is_its_closed_form(deicing):
    # eq. (1) of Yin, Wang & Yu 2010: radial reach 50 cos t1 + a2 cos(t1 + t2) [cm]
    for t3, t1, t2, a2 in random_q(deicing, 20, seed=7):
        radial = 50 * math.cos(t1) + a2 * math.cos(t1 + t2)
        p = deicing.fk([t3, t1, t2, a2])[:3, 3]
        np.testing.assert_allclose(p[0], math.cos(t3) * radial, atol=1e-12)
        np.testing.assert_allclose(math.hypot(p[0], p[1]), abs(radial), atol=1e-12)
        np.testing.assert_allclose(p[2], 50 * math.sin(t1) + a2 * math.sin(t1 + t2), atol=1e-12)


def test_fk_of_many_rows_is_fk_of_each(ta1400):
    q = random_q(ta1400, 7, seed=11)
    poses = ta1400.fk(q)
    assert poses.shape == (7, 4, 4)
    for row, pose in zip(q, poses):
        np.testing.assert_array_equal(pose, ta1400.fk(row))


def test_fk_accepts_any_float_dtype_and_layout(ta1400):
    q = random_q(ta1400, 5, seed=13)
    expected = ta1400.fk(q)
    np.testing.assert_array_equal(ta1400.fk(np.asfortranarray(q)), expected)
    wide = np.zeros((5, 12))
    wide[:, ::2] = q
    np.testing.assert_array_equal(ta1400.fk(wide[:, ::2]), expected)  # strided view
    q32 = q.astype(np.float32)
    np.testing.assert_array_equal(ta1400.fk(q32), ta1400.fk(q32.astype(np.float64)))


def test_jacobian_is_the_derivative_of_fk(ta1400):
    h = 1e-6  # rad; central differences err by O(h^2) * 1e3 mm
    for q in random_q(ta1400, 5, seed=17):
        J = ta1400.jacobian(q)
        assert J.shape == (6, 6)
        T = ta1400.fk(q, check_limits=False)
        for i in range(6):
            dq = np.zeros(6)
            dq[i] = h
            plus, minus = ta1400.fk(q + dq, check_limits=False), ta1400.fk(q - dq, check_limits=False)
            np.testing.assert_allclose(J[:3, i], (plus[:3, 3] - minus[:3, 3]) / (2 * h), atol=1e-5)
            W = (plus[:3, :3] - minus[:3, :3]) / (2 * h) @ T[:3, :3].T  # skew(omega)
            np.testing.assert_allclose(J[3:, i], [W[2, 1], W[0, 2], W[1, 0]], atol=1e-8)
    assert ta1400.jacobian(random_q(ta1400, 3, seed=1)).shape == (3, 6, 6)


def test_ik_reaches_an_fk_pose_and_refuses_an_unreachable_one(ta1400):
    goal = random_q(ta1400, 1, seed=19)[0]
    pose = ta1400.fk(goal)
    q = ta1400.ik(pose)
    assert q is not None and q.shape == (6,)
    reached = ta1400.fk(q)
    assert np.linalg.norm(reached[:3, 3] - pose[:3, 3]) <= 1e-6  # mm, the default tolerance
    np.testing.assert_allclose(reached[:3, :3], pose[:3, :3], atol=1e-5)
    far = pose.copy()
    far[:3, 3] = (5000.0, 0.0, 0.0)  # 5 m away: the arm reaches about 1.6 m
    assert ta1400.ik(far) is None


def test_ik_agrees_with_mcws_ik(deicing):
    goal = [0.2, 0.1, -0.3, 40.0]
    pose = deicing.fk(goal)
    expected = tool_json(
        "ik", "--robot", robot_path("deicing.yaml"), "--position-only",
        "--pose", " ".join(repr(float(v)) for v in pose[:3, 3]) + " 0 0 0")
    q = deicing.ik(pose, position_only=True)
    np.testing.assert_allclose(q, expected["q"], rtol=0, atol=1e-12)


def test_urdf_chain_by_base_and_tip():
    robot = mcws.Robot(robot_path("inspection6.urdf"))
    assert robot.length_unit == "m"
    with pytest.raises(mcws.UsageError, match="base and tip need a .urdf robot"):
        mcws.Robot(robot_path("ta1400.yaml"), tip="link6")
    with pytest.raises(mcws.Error, match="nope"):
        mcws.Robot(robot_path("inspection6.urdf"), tip="nope")


def test_errors_are_the_tools_messages(tmp_path):
    missing = str(tmp_path / "missing.yaml")
    with pytest.raises(mcws.Error) as error:
        mcws.Robot(missing)
    assert isinstance(error.value, RuntimeError) and not isinstance(error.value, mcws.UsageError)
    _, _, err = run_tool("fk", "--robot", missing, "--q", "0", expect=1)
    assert err == f"mcws_fk: --robot: {error.value}\n"


def test_bad_joint_vectors(ta1400):
    with pytest.raises(mcws.UsageError, match=r"^q: robot 'ta1400' has 6 joints but 3 joint values were given$"):
        ta1400.fk([0, 0, 0])
    with pytest.raises(mcws.UsageError, match=r"^q: joint 'j6' value nan is not a finite number$"):
        ta1400.fk([0, 0, 0, 0, 0, float("nan")])
    with pytest.raises(mcws.UsageError, match=r"^q\[1\]: joint 'j2' value 1 is outside its limits"):
        ta1400.fk([[0] * 6, [0, 1, 0, 0, 0, 0]])
    with pytest.raises(ValueError, match=r"shape \(2, 2, 6\)"):
        ta1400.fk(np.zeros((2, 2, 6)))
    with pytest.raises(mcws.UsageError, match="is not an array of numbers"):
        ta1400.fk(["a"] * 6)
    with pytest.raises(mcws.UsageError, match="frame: 'elbow'"):
        ta1400.fk(np.zeros(6), frame="elbow")
    with pytest.raises(mcws.UsageError, match="pose: an array of shape"):
        ta1400.ik(np.eye(3))
    with pytest.raises(mcws.UsageError, match="last row"):
        ta1400.ik(np.ones((4, 4)))


def test_same_message_as_mcws_fk_for_out_of_limits(ta1400):
    q = "0 1 0 0 0 0"
    _, _, err = run_tool("fk", "--robot", robot_path("ta1400.yaml"), "--q", q, expect=2)
    with pytest.raises(mcws.UsageError) as error:
        ta1400.fk([0, 1, 0, 0, 0, 0])
    assert err == f"mcws_fk: --{error.value} (see --help)\n"


BOX_STL = """solid box
facet normal 0 0 -1
outer loop
vertex -0.05 -0.05 0
vertex 0.05 0.05 0
vertex 0.05 -0.05 0
endloop
endfacet
facet normal 0 0 1
outer loop
vertex -0.05 -0.05 0.1
vertex 0.05 -0.05 0.1
vertex 0.05 0.05 0.1
endloop
endfacet
endsolid box
"""

PACKAGED_URDF = """<robot name="packaged">
  <link name="base"/>
  <link name="arm"><collision><geometry>
    <mesh filename="package://my_meshes/meshes/box.stl"/></geometry></collision></link>
  <link name="hand"><collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="arm"/><child link="hand"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>
"""


def test_package_path_and_srdf_as_the_tools_flags(tmp_path):
    # The package lies beside the robot's folder, not above it: only package_path finds it.
    package = tmp_path / "packages" / "my_meshes"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package><name>my_meshes</name></package>\n")
    (package / "meshes" / "box.stl").write_text(BOX_STL)
    (tmp_path / "robot").mkdir()
    urdf = tmp_path / "robot" / "packaged.urdf"
    urdf.write_text(PACKAGED_URDF)

    with pytest.raises(mcws.Error, match="package://my_meshes/meshes/box.stl"):
        mcws.Robot(urdf).has_collision_model
    for folders in (tmp_path / "packages", [str(tmp_path / "packages")]):
        robot = mcws.Robot(urdf, package_path=folders)
        assert robot.has_collision_model
        assert robot.dof == 2

    # An SRDF is read with the collision model, and a pair naming no link is refused.
    srdf = tmp_path / "packaged.srdf"
    srdf.write_text('<robot name="packaged"><disable_collisions link1="arm" link2="hand" '
                    'reason="Adjacent"/></robot>\n')
    robot = mcws.Robot(urdf, package_path=tmp_path / "packages", srdf=srdf)
    assert robot.has_collision_model
    bad = tmp_path / "bad.srdf"
    bad.write_text('<robot name="packaged"><disable_collisions link1="arm" link2="nowhere" '
                   'reason="Never"/></robot>\n')
    with pytest.raises(mcws.Error, match="nowhere"):
        mcws.Robot(urdf, package_path=tmp_path / "packages", srdf=bad).has_collision_model

    with pytest.raises(mcws.UsageError, match="package_path: '.*' is not a folder"):
        mcws.Robot(urdf, package_path=tmp_path / "none")
    with pytest.raises(mcws.UsageError, match="srdf: '.*' is not a file"):
        mcws.Robot(urdf, srdf=tmp_path / "none.srdf")
    with pytest.raises(mcws.UsageError, match="package_path needs a .urdf robot"):
        mcws.Robot(robot_path("ta1400.yaml"), package_path=tmp_path)
