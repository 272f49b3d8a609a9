// Parallel link 5 of the crank-slider gripper's parallelogram dyad (SPEC §6;
// cases/gripper_parts/README.md): ground pivot P at the origin, bore C (the
// jaw) at (r, 0), as long as the rocker so that the jaw keeps its
// orientation; mm, pin axes along z. The rest is the part's design (README).
DefineConstant[
  length = {67.0, Name "link/r: P to C (mm)"},
  d0 = {12.0, Name "link/bore P diameter (mm)"},
  D0 = {24.0, Name "link/boss P diameter (mm)"},
  d1 = {10.0, Name "link/bore C diameter (mm)"},
  D1 = {20.0, Name "link/boss C diameter (mm)"},
  L = {12.0, Name "link/boss length along the pins (mm)"},
  w = {12.0, Name "link/web width (mm)"},
  t = {8.0, Name "link/web thickness (mm)"}
];
Include "bar_shape.geo";
Physical Volume("body") = part();
Physical Surface("bore_P") = bore_0();
Physical Surface("bore_C") = bore_1();
