// spherical_column.geo — link 1 (the column) of the spherical-coordinate
// manipulator of SPEC §5. Units: metres.
//
// Frame: origin on the floor on the base rotation axis, z up, y along the
// tilt pin at B = (0, 0, z_B), x towards the arm. A floor flange, a tube
// closed by the flange and a top plate (a sealed cavity inside), a bearing
// collar (the seat of the base rotation, "pair_10"), and a fork of two lugs
// whose bores carry the sleeve's trunnions ("pair_21").
//
// The C++ side (kinetofem::meshes::mesh_spherical_part) sets every parameter
// through its ONELAB name "Column/<name>"; the defaults below are variant A of
// SPEC §5 as spherical_part_dimensions sizes it. Dimensions and the reasons
// for them: docs/spherical_manipulator_parts.md.
SetFactory("OpenCASCADE");

DefineConstant[
  R_f    = {0.4375, Name "Column/R_f",    Help "floor flange radius [m]"},
  t_f    = {0.020,  Name "Column/t_f",    Help "floor flange thickness [m]"},
  R1     = {0.1970, Name "Column/R1",     Help "tube outer radius [m]"},
  t1     = {0.042,  Name "Column/t1",     Help "tube wall [m]"},
  z_top  = {0.464,  Name "Column/z_top",  Help "height of the top plate's upper face [m]"},
  t_top  = {0.025,  Name "Column/t_top",  Help "top plate thickness [m]"},
  z_seat = {0.414,  Name "Column/z_seat", Help "centre height of the bearing seat [m]"},
  h_seat = {0.050,  Name "Column/h_seat", Help "bearing seat height [m]"},
  h_c    = {0.010,  Name "Column/h_c",    Help "bearing collar radial height [m]"},
  z_B    = {0.700,  Name "Column/z_B",    Help "height of the tilt pin axis [m]"},
  d_pin  = {0.0609, Name "Column/d_pin",  Help "pin bore diameter [m]"},
  y_in   = {0.1340, Name "Column/y_in",   Help "inner face of each lug, |y| [m]"},
  t_c    = {0.0365, Name "Column/t_c",    Help "lug thickness along y [m]"},
  w      = {0.152,  Name "Column/w",      Help "lug width along x [m]"}
];

y_out = y_in + t_c;
// The C++ side checks these (and more) with messages naming the dimension;
// this guard is for runs of the file on its own.
If (t1 >= R1 || z_top - t_top <= t_f || z_seat - h_seat/2 <= t_f || z_seat + h_seat/2 >= z_top ||
    Sqrt(y_out^2 + w^2/4) >= R1 || d_pin >= w || z_B - z_top < w/2 || R_f <= R1 + h_c)
  Error("spherical_column.geo: inconsistent dimensions");
EndIf

Cylinder(1) = {0, 0, 0,  0, 0, t_f,  R_f};
// The tube starts inside the flange so that no face is coplanar with it.
Cylinder(2) = {0, 0, t_f/2,  0, 0, z_top - t_f/2,  R1};
Cylinder(3) = {0, 0, z_seat - h_seat/2,  0, 0, h_seat,  R1 + h_c};
// Lugs: a box standing in the top plate (from half its thickness) and the
// rounding cylinder about the pin axis.
Box(4) = {-w/2, y_in, z_top - t_top/2,  w, t_c, z_B - z_top + t_top/2};
Box(5) = {-w/2, -y_out, z_top - t_top/2,  w, t_c, z_B - z_top + t_top/2};
Cylinder(6) = {0, y_in, z_B,  0, t_c, 0,  w/2};
Cylinder(7) = {0, -y_out, z_B,  0, t_c, 0,  w/2};
solid() = BooleanUnion{ Volume{2}; Delete; }{ Volume{1, 3, 4, 5, 6, 7}; Delete; };

Cylinder(10) = {0, 0, t_f,  0, 0, z_top - t_top - t_f,  R1 - t1};
// The pin cutter overshoots the lugs by 10 mm so that no face is coplanar.
Cylinder(11) = {0, -y_out - 0.01, z_B,  0, 2*y_out + 0.02, 0,  d_pin/2};
column() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{10, 11}; Delete; };
If (#column() != 1)
  Error("spherical_column.geo: the pieces did not fuse into one solid (%g volumes)", #column());
EndIf

// Named surfaces, picked by bounding boxes (tolerance e).
e = 1e-6;
foundation() = Surface In BoundingBox{-R_f-e, -R_f-e, -e,  R_f+e, R_f+e, e};
Rc = R1 + h_c;  z0 = z_seat - h_seat/2;  z1 = z_seat + h_seat/2;
seat() = Surface In BoundingBox{-Rc-e, -Rc-e, z0-e,  Rc+e, Rc+e, z1+e};
// The box about the collar also holds its two flat annular faces and may hold
// the cavity's roof (radius R1 - t1 < R1): all taken out again.
seat() -= Surface In BoundingBox{-R1-e, -R1-e, z0-e,  R1+e, R1+e, z1+e};
seat() -= Surface In BoundingBox{-Rc-e, -Rc-e, z0-e,  Rc+e, Rc+e, z0+e};
seat() -= Surface In BoundingBox{-Rc-e, -Rc-e, z1-e,  Rc+e, Rc+e, z1+e};
rb = d_pin/2;
bores() = Surface In BoundingBox{-rb-e, y_in-e, z_B-rb-e,  rb+e, y_out+e, z_B+rb+e};
bores() += Surface In BoundingBox{-rb-e, -y_out-e, z_B-rb-e,  rb+e, -y_in+e, z_B+rb+e};

Physical Volume("column") = {column()};
Physical Surface("foundation") = {foundation()};
Physical Surface("pair_10") = {seat()};
Physical Surface("pair_21") = {bores()};
