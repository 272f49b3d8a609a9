// Link 1 (the lever) of the SPEC §4 two-link Q-manipulator, in mm, in its body
// frame: bore O (the ground pivot, the seat of the motor shaft and of the
// frame's fixed pulley's shaft) at the origin, bore A (link 2's pivot, the seat
// of link 2's pulley shaft) at (length, 0); pin axes along z, symmetric about
// z = 0. Two bosses joined by a plate (|y| <= width/2, |z| <= thickness/2).
// The dimensions are ONELAB constants: change them in Gmsh's GUI or with
//   gmsh -setnumber length 250 link1.geo
// (kinetofem meshes the file with these defaults).
SetFactory("OpenCASCADE");
DefineConstant[
  length = {200, Min 50, Max 2000, Name "Link 1/length O-A (mm)"},
  boss_diameter = {40, Min 10, Max 200, Name "Link 1/boss outer diameter (mm)"},
  bore_diameter = {20, Min 4, Max 150, Name "Link 1/bore diameter (mm)"},
  boss_length = {30, Min 5, Max 200, Name "Link 1/boss length along the pins (mm)"},
  width = {25, Min 5, Max 200, Name "Link 1/plate width (mm)"},
  thickness = {12, Min 2, Max 100, Name "Link 1/plate thickness (mm)"}
];
D = boss_diameter; d = bore_diameter; L = boss_length; e = 0.5;
boss_O = newv; Cylinder(boss_O) = {0, 0, -L/2, 0, 0, L, D/2};
boss_A = newv; Cylinder(boss_A) = {length, 0, -L/2, 0, 0, L, D/2};
plate = newv; Box(plate) = {0, -width/2, -thickness/2, length, width, thickness};
solid() = BooleanUnion{ Volume{boss_O}; Delete; }{ Volume{boss_A, plate}; Delete; };
hole_O = newv; Cylinder(hole_O) = {0, 0, -L, 0, 0, 2*L, d/2};
hole_A = newv; Cylinder(hole_A) = {length, 0, -L, 0, 0, 2*L, d/2};
link() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{hole_O, hole_A}; Delete; };
// The bores as face sets: the surfaces inside each bore cylinder grown by e.
Physical Surface("bore_O") = Surface In BoundingBox{-d/2-e, -d/2-e, -L/2-e, d/2+e, d/2+e, L/2+e};
Physical Surface("bore_A") = Surface In BoundingBox{length-d/2-e, -d/2-e, -L/2-e, length+d/2+e, d/2+e, L/2+e};
Physical Volume("link1") = {link()};
