// arm.geo — link 2 (the arm carrying the gripper) of the two manipulators of
// SPEC §1/§2, in one of two variants. Units: metres.
//
// Frame: origin at the centre of pin bore A (the joint with lever 1), pin axes
// along Z, the part symmetric about z = 0. In the design position the
// mechanism's x axis is this x axis, so C = (-c, 0) and the gripper's
// reference point H = (-c, h).
//
//   with_roller = 1: arm of the lever-chain manipulator (SPEC §1). A chain
//     roller (disc of radius r, thickness e_roller) and a hub boss on A,
//     bore A through both.
//   with_roller = 0: coupler AB of the lever manipulator (SPEC §2). Bores A
//     and B = (d_B, 0) in one hub plate: two bosses joined by their common
//     tangent planes y = +-D_boss/2 (a stadium of thickness L_boss).
//
// Both variants: an arm plate w (along y) x t (along z) from A to C, a
// gripper bracket (w_bracket along x, t_bracket along z) at C rising from the
// arm's lower face to the mounting pad, and the mounting pad (l_mount along
// x, t_mount along y, w_mount along z) whose top face y = h, centred on
// x = -c, is the gripper mount (outward normal +Y).
//
//   view along -Z:
//               H
//      +--------+--------+  y = h            mounting pad; its top face is
//      +--+-----------+--+  y = h - t_mount  "gripper_mount"
//         |  bracket  |                                  ___
//         |           +---------------------------+   /     \
//         |     C           arm plate             +--(   A   )--> x
//         +---------------------------------------+   \ ___ /
//               x = -c                       y = -w/2    x = 0, roller r
//                                                       (or the hub with B)
//
// The C++ side (kinetofem::meshes::mesh_arm) overrides every parameter
// through its ONELAB name "Arm/<name>" before this file is parsed; opened in
// the Gmsh GUI the defaults below (the lever-chain arm of the SPEC §1
// example) apply. Dimensions and the design reasons for them:
// meshes/geometry/README.md, section "Link 2".
SetFactory("OpenCASCADE");

DefineConstant[
  with_roller = {1, Choices{0 = "coupler (bores A and B)", 1 = "chain arm (roller at A)"},
                 Name "Arm/with_roller", Help "1: lever-chain arm with roller, 0: lever coupler"},
  c         = {0.350, Name "Arm/c",         Help "distance A-C along -x [m]"},
  h         = {0.100, Name "Arm/h",         Help "y of the gripper mount face through H [m]"},
  r         = {0.075, Name "Arm/r",         Help "roller radius (with_roller = 1) [m]"},
  e_roller  = {0.030, Name "Arm/e_roller",  Help "roller thickness along z (with_roller = 1) [m]"},
  d_B       = {0.075, Name "Arm/d_B",       Help "x of bore B (with_roller = 0) [m]"},
  w         = {0.080, Name "Arm/w",         Help "arm plate depth along y [m]"},
  t         = {0.025, Name "Arm/t",         Help "arm plate thickness along z [m]"},
  d_bore    = {0.040, Name "Arm/d_bore",    Help "pin bore diameter (A and B) [m]"},
  D_boss    = {0.090, Name "Arm/D_boss",    Help "boss outer diameter [m]"},
  L_boss    = {0.050, Name "Arm/L_boss",    Help "boss length along z [m]"},
  w_bracket = {0.080, Name "Arm/w_bracket", Help "gripper bracket width along x [m]"},
  t_bracket = {0.025, Name "Arm/t_bracket", Help "gripper bracket thickness along z [m]"},
  l_mount   = {0.080, Name "Arm/l_mount",   Help "mounting pad length along x [m]"},
  w_mount   = {0.060, Name "Arm/w_mount",   Help "mounting pad width along z [m]"},
  t_mount   = {0.015, Name "Arm/t_mount",   Help "mounting pad thickness along y [m]"}
];

R = D_boss/2;  rb = d_bore/2;
If (with_roller)
  R_hub = r;
Else
  R_hub = R;
EndIf
// The C++ side checks these (and more) with messages naming the dimension;
// this guard is for runs of the file on its own.
If (d_bore >= D_boss || t > L_boss || h - t_mount < w/2 ||
    c - w_bracket/2 <= R_hub || c - l_mount/2 <= R_hub)
  Error("arm.geo: need d_bore < D_boss, t <= L_boss, h - t_mount >= w/2 and the bracket and pad clear of the hub");
EndIf
If (with_roller && (r <= R || e_roller >= L_boss))
  Error("arm.geo: need r > D_boss/2 and e_roller < L_boss");
EndIf
If (!with_roller && (d_B < R || d_B <= d_bore))
  Error("arm.geo: need d_B >= D_boss/2 and d_B > d_bore");
EndIf

If (with_roller)
  Cylinder(1) = {0, 0, -e_roller/2,  0, 0, e_roller,  r};
  Cylinder(2) = {0, 0, -L_boss/2,  0, 0, L_boss,  R};
  hub() = {1, 2};
Else
  Cylinder(1) = {0, 0, -L_boss/2,  0, 0, L_boss,  R};
  Cylinder(2) = {d_B, 0, -L_boss/2,  0, 0, L_boss,  R};
  Box(3) = {0, -R, -L_boss/2,  d_B, 2*R, L_boss};
  hub() = {1, 2, 3};
EndIf
Box(10) = {-c, -w/2, -t/2,  c, w, t};
Box(11) = {-c - w_bracket/2, -w/2, -t_bracket/2,  w_bracket, h - t_mount + w/2, t_bracket};
Box(12) = {-c - l_mount/2, h - t_mount, -w_mount/2,  l_mount, t_mount, w_mount};
solid() = BooleanUnion{ Volume{10}; Delete; }{ Volume{hub(), 11, 12}; Delete; };

// Bore cutters overshoot the bosses by 10 mm so that no face is coplanar.
Cylinder(20) = {0, 0, -L_boss/2 - 0.01,  0, 0, L_boss + 0.02,  rb};
cutters() = {20};
If (!with_roller)
  Cylinder(21) = {d_B, 0, -L_boss/2 - 0.01,  0, 0, L_boss + 0.02,  rb};
  cutters() += {21};
EndIf
arm() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{cutters()}; Delete; };
If (#arm() != 1)
  Error("arm.geo: the pieces did not fuse into one solid (%g volumes)", #arm());
EndIf

// Named surfaces, picked by bounding boxes (tolerance e) so that they survive
// changes of the parameters.
e = 1e-6;
hb = L_boss/2;
bore_A() = Surface In BoundingBox{-rb-e, -rb-e, -hb-e,  rb+e, rb+e, hb+e};
mount() = Surface In BoundingBox{-c-l_mount/2-e, h-e, -w_mount/2-e,  -c+l_mount/2+e, h+e, w_mount/2+e};

Physical Volume("arm") = {arm()};
Physical Surface("bore_A") = {bore_A()};
Physical Surface("gripper_mount") = {mount()};
If (with_roller)
  // The box about the roller holds its rim and its two flat faces z = +-e_roller/2
  // (the bore and the boss faces reach beyond |z| = e_roller/2); the flat faces
  // are taken out again.
  hr = e_roller/2;
  rim() = Surface In BoundingBox{-r-e, -r-e, -hr-e,  r+e, r+e, hr+e};
  flat() = Surface In BoundingBox{-r-e, -r-e, -hr-e,  r+e, r+e, -hr+e};
  flat() += Surface In BoundingBox{-r-e, -r-e, hr-e,  r+e, r+e, hr+e};
  rim() -= flat();
  Physical Surface("roller_rim") = {rim()};
Else
  bore_B() = Surface In BoundingBox{d_B-rb-e, -rb-e, -hb-e,  d_B+rb+e, rb+e, hb+e};
  Physical Surface("bore_B") = {bore_B()};
EndIf
