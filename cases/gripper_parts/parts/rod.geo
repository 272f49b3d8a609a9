// Rod 2 of the crank-slider gripper (SPEC §6; cases/gripper_parts/README.md):
// bore A (rocker and jaw) at the origin, bore B (slider) at (l, 0); mm, pin
// axes along z. l = r / sigma = 67 / 1.1 mm is the mechanism's; the rest is
// the part's design (README).
DefineConstant[
  length = {60.909091, Name "rod/l: A to B (mm)"},
  d0 = {10.0, Name "rod/bore A diameter (mm)"},
  D0 = {20.0, Name "rod/boss A diameter (mm)"},
  d1 = {10.0, Name "rod/bore B diameter (mm)"},
  D1 = {20.0, Name "rod/boss B diameter (mm)"},
  L = {10.0, Name "rod/boss length along the pins (mm)"},
  w = {12.0, Name "rod/web width (mm)"},
  t = {8.0, Name "rod/web thickness (mm)"}
];
Include "bar_shape.geo";
Physical Volume("body") = part();
Physical Surface("bore_A") = bore_0();
Physical Surface("bore_B") = bore_1();
