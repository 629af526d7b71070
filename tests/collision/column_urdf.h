#pragma once
// A small URDF robot of boxes whose allowed collision pairs are worked out by hand, for the SRDF
// tests (tests/collision/srdf_test.cpp, srdf_app_test.cpp).
#include <string>

namespace mcws::test {

/// Three joints on a column of 10 cm boxes, each centred on the z axis, which every joint turns
/// about or slides along, so heights [m] decide every overlap:
/// - base_link z in [-0.1, 0.1] (a 20 cm box); link1 (j1 about z at 0.2) z in [0.15, 0.25];
/// - link2 (j2 about z, 0.3 above j1) z in [0.45, 0.55], with link2_cap fixed to it (5 cm box at
///   z 0.54): one body, so link2 - link2_cap is Adjacent;
/// - link3 (j3 sliding 0 .. 5 cm along z, 0.1 above j2) has its box 0.4 below its frame: z in
///   [0.15 + q3, 0.25 + q3], so it always overlaps link1 (and at the default q = 0: Default);
/// - post, fixed to the base 1 m away along x: an environment object, Adjacent to base_link,
///   never reached (the arm stays within 0.08 m of the axis).
/// So: Adjacent base_link-link1, link1-link2, link1-link2_cap, link2-link3, link2_cap-link3,
/// link2-link2_cap, base_link-post; Default link1-link3; Never every other pair with a moving link
/// (the base below 0.1 m, link2 and its cap above 0.45 m, link3 between 0.15 and 0.30 m).
inline const std::string kColumnUrdf = R"(<?xml version="1.0"?>
<robot name="column">
  <link name="base_link"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="link1"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="link2"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="link2_cap"><collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>
  </link>
  <link name="link3"><collision><origin xyz="0 0 -0.4"/>
    <geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="post"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="marker"/>
  <joint name="j1" type="revolute"><parent link="base_link"/><child link="link1"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>
    <limit lower="-3.14" upper="3.14" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="link1"/><child link="link2"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="cap" type="fixed"><parent link="link2"/><child link="link2_cap"/>
    <origin xyz="0 0 0.04"/></joint>
  <joint name="j3" type="prismatic"><parent link="link2"/><child link="link3"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.05" effort="1" velocity="1"/></joint>
  <joint name="post_joint" type="fixed"><parent link="base_link"/><child link="post"/>
    <origin xyz="1 0 0"/></joint>
  <joint name="marker_joint" type="fixed"><parent link="link3"/><child link="marker"/></joint>
</robot>
)";

}  // namespace mcws::test
