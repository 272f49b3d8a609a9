// Rocker 3 of the crank-slider gripper (SPEC §6; cases/gripper_parts/README.md):
// ground pivot O at the origin, bore A (the rod and the jaw) at (r, 0); mm,
// pin axes along z. The crank radius r is the mechanism's; the rest is the
// part's design (README: pins, bosses, web).
DefineConstant[
  length = {67.0, Name "rocker/r: O to A (mm)"},
  d0 = {12.0, Name "rocker/bore O diameter (mm)"},
  D0 = {24.0, Name "rocker/boss O diameter (mm)"},
  d1 = {10.0, Name "rocker/bore A diameter (mm)"},
  D1 = {20.0, Name "rocker/boss A diameter (mm)"},
  L = {14.0, Name "rocker/boss length along the pins (mm)"},
  w = {16.0, Name "rocker/web width (mm)"},
  t = {10.0, Name "rocker/web thickness (mm)"}
];
Include "bar_shape.geo";
Physical Volume("body") = part();
Physical Surface("bore_O") = bore_0();
Physical Surface("bore_A") = bore_1();
