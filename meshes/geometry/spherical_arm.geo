// spherical_arm.geo — link 3 (the sliding arm) of the spherical-coordinate
// manipulator of SPEC §5. Units: metres.
//
// Frame: origin at the gripper point M on the front end face, x along the arm
// axis pointing forward (towards the payload), so the arm lies in
// -l1 <= x <= 0. A tube of diameter D3 and wall t3, open at the rear, solid
// over the front -t_p <= x <= 0 (the end plate whose face x = 0 is
// "gripper_mount"). The tube is made of three conformal pieces split at
// x_s0 and x_s1 so that the outer cylinder over x_s0 <= x <= x_s1 (the length
// that can be in the sleeve) is a face of its own, "slide".
//
// The C++ side (kinetofem::meshes::mesh_spherical_part) sets every parameter
// through its ONELAB name "Arm3/<name>"; the defaults below are variant A of
// SPEC §5. Dimensions and the reasons for them:
// docs/spherical_manipulator_parts.md.
SetFactory("OpenCASCADE");

DefineConstant[
  l1   = {2.7059, Name "Arm3/l1",   Help "arm length [m]"},
  D3   = {0.1461, Name "Arm3/D3",   Help "outer diameter [m]"},
  t3   = {0.0051, Name "Arm3/t3",   Help "wall [m]"},
  t_p  = {0.0146, Name "Arm3/t_p",  Help "front end plate thickness [m]"},
  x_s0 = {-2.6059, Name "Arm3/x_s0", Help "rear end of the slide face [m]"},
  x_s1 = {-0.7941, Name "Arm3/x_s1", Help "front end of the slide face [m]"}
];

R3 = D3/2;  ri = R3 - t3;
If (t3 >= R3 || t_p >= -x_s1 || x_s0 <= -l1 || x_s0 >= x_s1)
  Error("spherical_arm.geo: inconsistent dimensions");
EndIf

// Rear, slide and front pieces; the front one holds the end plate.
Cylinder(1) = {-l1, 0, 0,  x_s0 + l1, 0, 0,  R3};
Cylinder(2) = {x_s0, 0, 0,  x_s1 - x_s0, 0, 0,  R3};
Cylinder(3) = {x_s1, 0, 0,  -x_s1, 0, 0,  R3};
// The bore cutter overshoots the open rear end by 10 mm.
Cylinder(4) = {-l1 - 0.01, 0, 0,  l1 + 0.01 - t_p, 0, 0,  ri};
pieces() = BooleanDifference{ Volume{1, 2, 3}; Delete; }{ Volume{4}; Delete; };
arm() = BooleanFragments{ Volume{pieces()}; Delete; }{};
If (#arm() != 3)
  Error("spherical_arm.geo: expected three conformal pieces, got %g volumes", #arm());
EndIf

e = 1e-6;
// The box about the slide piece holds its outer and inner cylinders and the
// two annuli it shares with the other pieces: keep the outer one only.
slide() = Surface In BoundingBox{x_s0-e, -R3-e, -R3-e,  x_s1+e, R3+e, R3+e};
slide() -= Surface In BoundingBox{x_s0-e, -ri-e, -ri-e,  x_s1+e, ri+e, ri+e};
slide() -= Surface In BoundingBox{x_s0-e, -R3-e, -R3-e,  x_s0+e, R3+e, R3+e};
slide() -= Surface In BoundingBox{x_s1-e, -R3-e, -R3-e,  x_s1+e, R3+e, R3+e};
mount() = Surface In BoundingBox{-e, -R3-e, -R3-e,  e, R3+e, R3+e};

// Elements no longer than 3 walls: a tube wall of a few mm meshed with
// elements many times longer than it is thick gives TET10 so flat that Gmsh's
// high-order untangling fails (seen for variant B at 30 mm). The field only
// lowers the size the caller asks for (Gmsh takes the smallest size).
Field[1] = MathEval;
Field[1].F = Sprintf("%g", 3*t3);
Background Field = 1;

Physical Volume("arm") = {arm()};
Physical Surface("slide") = {slide()};
Physical Surface("gripper_mount") = {mount()};
