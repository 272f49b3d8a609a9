// spherical_sleeve.geo — link 2 (the tilting sleeve) of the spherical-
// coordinate manipulator of SPEC §5. Units: metres.
//
// Frame: origin at B on the tilt pin axis, x along the arm axis towards the
// gripper point M, y along the tilt pin. A tube of diameter d2 and length l2
// centred at B; its bore is the guide diameter D_g over l_g at each end (the
// lands the arm slides in: "pair_32_front" at x > 0, "pair_32_rear" at
// x < 0) and a relief of radius d2/2 - t2 between them; two trunnions along
// +-y, a shoulder d_s out to |y| = y_in and a journal d_pin over
// y_in <= |y| <= y_in + t_c that sits in the column's fork ("pair_21").
//
// The C++ side (kinetofem::meshes::mesh_spherical_part) sets every parameter
// through its ONELAB name "Sleeve/<name>"; the defaults below are variant A of
// SPEC §5. Dimensions and the reasons for them:
// docs/spherical_manipulator_parts.md.
SetFactory("OpenCASCADE");

DefineConstant[
  l2    = {0.8118, Name "Sleeve/l2",    Help "sleeve length [m]"},
  d2    = {0.2435, Name "Sleeve/d2",    Help "sleeve outer diameter [m]"},
  t2    = {0.0229, Name "Sleeve/t2",    Help "wall between the guide lands [m]"},
  D_g   = {0.1461, Name "Sleeve/D_g",   Help "guide land bore diameter [m]"},
  l_g   = {0.0731, Name "Sleeve/l_g",   Help "guide land length [m]"},
  d_pin = {0.0609, Name "Sleeve/d_pin", Help "trunnion journal diameter [m]"},
  d_s   = {0.0792, Name "Sleeve/d_s",   Help "trunnion shoulder diameter [m]"},
  y_in  = {0.1340, Name "Sleeve/y_in",  Help "start of each journal, |y| [m]"},
  t_c   = {0.0365, Name "Sleeve/t_c",   Help "journal length [m]"}
];

r2 = d2/2;  r_g = D_g/2;  r_rel = r2 - t2;  y_out = y_in + t_c;
If (r_rel <= r_g || 2*l_g >= l2 || d_s/2 >= r2 || d_s/2 >= l2/2 - l_g || d_pin >= d_s || y_in <= r2)
  Error("spherical_sleeve.geo: inconsistent dimensions");
EndIf

Cylinder(1) = {-l2/2, 0, 0,  l2, 0, 0,  r2};
// Shoulders and journals start on the axis; the bore cut takes what lies
// inside the tube.
Cylinder(2) = {0, 0, 0,  0, y_in, 0,  d_s/2};
Cylinder(3) = {0, 0, 0,  0, -y_in, 0,  d_s/2};
Cylinder(4) = {0, 0, 0,  0, y_out, 0,  d_pin/2};
Cylinder(5) = {0, 0, 0,  0, -y_out, 0,  d_pin/2};
solid() = BooleanUnion{ Volume{1}; Delete; }{ Volume{2, 3, 4, 5}; Delete; };

// The guide bore cutter overshoots the ends by 10 mm.
Cylinder(10) = {-l2/2 - 0.01, 0, 0,  l2 + 0.02, 0, 0,  r_g};
Cylinder(11) = {-l2/2 + l_g, 0, 0,  l2 - 2*l_g, 0, 0,  r_rel};
sleeve() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{10, 11}; Delete; };
If (#sleeve() != 1)
  Error("spherical_sleeve.geo: the pieces did not fuse into one solid (%g volumes)", #sleeve());
EndIf

e = 1e-6;
x_g = l2/2 - l_g;
front() = Surface In BoundingBox{x_g-e, -r_g-e, -r_g-e,  l2/2+e, r_g+e, r_g+e};
rear() = Surface In BoundingBox{-l2/2-e, -r_g-e, -r_g-e,  -x_g+e, r_g+e, r_g+e};
rj = d_pin/2;
// The box about each journal also holds its flat end face, taken out again.
journals() = Surface In BoundingBox{-rj-e, y_in-e, -rj-e,  rj+e, y_out+e, rj+e};
journals() -= Surface In BoundingBox{-rj-e, y_out-e, -rj-e,  rj+e, y_out+e, rj+e};
journals() += Surface In BoundingBox{-rj-e, -y_out-e, -rj-e,  rj+e, -y_in+e, rj+e};
journals() -= Surface In BoundingBox{-rj-e, -y_out-e, -rj-e,  rj+e, -y_out+e, rj+e};

Physical Volume("sleeve") = {sleeve()};
Physical Surface("pair_21") = {journals()};
Physical Surface("pair_32_front") = {front()};
Physical Surface("pair_32_rear") = {rear()};
