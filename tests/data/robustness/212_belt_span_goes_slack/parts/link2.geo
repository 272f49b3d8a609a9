// Link 2 (the arm) of the SPEC §4 two-link Q-manipulator, in mm, in its body
// frame: bore A (its pivot on link 1 and the seat of its pulley, which is keyed
// to it) at the origin, bore H (the payload's mounting pin, the characteristic
// point H) at (length, 0); pin axes along z, symmetric about z = 0. Two bosses
// joined by a plate, as link1.geo.
// The dimensions are ONELAB constants: change them in Gmsh's GUI or with
//   gmsh -setnumber length 250 link2.geo
// (kinetofem meshes the file with these defaults).
SetFactory("OpenCASCADE");
DefineConstant[
  length = {200, Min 50, Max 2000, Name "Link 2/length A-H (mm)"},
  boss_diameter = {36, Min 10, Max 200, Name "Link 2/boss outer diameter (mm)"},
  bore_diameter = {16, Min 4, Max 150, Name "Link 2/bore diameter (mm)"},
  boss_length = {24, Min 5, Max 200, Name "Link 2/boss length along the pins (mm)"},
  width = {20, Min 5, Max 200, Name "Link 2/plate width (mm)"},
  thickness = {10, Min 2, Max 100, Name "Link 2/plate thickness (mm)"}
];
D = boss_diameter; d = bore_diameter; L = boss_length; e = 0.5;
boss_A = newv; Cylinder(boss_A) = {0, 0, -L/2, 0, 0, L, D/2};
boss_H = newv; Cylinder(boss_H) = {length, 0, -L/2, 0, 0, L, D/2};
plate = newv; Box(plate) = {0, -width/2, -thickness/2, length, width, thickness};
solid() = BooleanUnion{ Volume{boss_A}; Delete; }{ Volume{boss_H, plate}; Delete; };
hole_A = newv; Cylinder(hole_A) = {0, 0, -L, 0, 0, 2*L, d/2};
hole_H = newv; Cylinder(hole_H) = {length, 0, -L, 0, 0, 2*L, d/2};
link() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{hole_A, hole_H}; Delete; };
Physical Surface("bore_A") = Surface In BoundingBox{-d/2-e, -d/2-e, -L/2-e, d/2+e, d/2+e, L/2+e};
Physical Surface("bore_H") = Surface In BoundingBox{length-d/2-e, -d/2-e, -L/2-e, length+d/2+e, d/2+e, L/2+e};
Physical Volume("link2") = {link()};
