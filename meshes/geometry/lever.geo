// lever.geo — lever 1 (A0-A) of the lever-chain manipulator (SPEC §1), a flat
// steel plate with a bored boss (hub) at each pin. Units: metres.
//
// Frame: origin at the centre of bore A0, lever axis along +Y (the design
// position of SPEC §1), so bore A is centred at (0, a, 0); the plate's
// thickness is along Z and the part is symmetric about z = 0 and x = 0.
//
//   z                   plate w x a x t          boss D x L, bore d
//   ^                    ________________________
//   |     ___           |                        |            ___
//   +->y | O |----------|------------------------|-----------| O |
//        |___|          |________________________|           |___|
//         A0                                                   A
//
// The C++ side (kinetofem::meshes::mesh_lever) overrides every parameter
// through its ONELAB name "Lever/<name>" before this file is parsed; opened in
// the Gmsh GUI the defaults below apply. Dimensions and the design reasons
// for them: meshes/geometry/README.md.
SetFactory("OpenCASCADE");

DefineConstant[
  a      = {0.500, Name "Lever/a",      Help "distance A0-A between the bore centres [m]"},
  w      = {0.080, Name "Lever/w",      Help "plate width [m]"},
  t      = {0.025, Name "Lever/t",      Help "plate thickness [m]"},
  d_bore = {0.040, Name "Lever/d_bore", Help "bore diameter of both pins [m]"},
  D_boss = {0.090, Name "Lever/D_boss", Help "outer diameter of both bosses [m]"},
  L_boss = {0.050, Name "Lever/L_boss", Help "length of both bosses along the pin (Z) [m]"}
];

If (d_bore >= D_boss || w >= D_boss || t > L_boss || a <= D_boss)
  Error("lever.geo: need d_bore < D_boss, w < D_boss, t <= L_boss and a > D_boss");
EndIf

Box(1) = {-w/2, 0, -t/2,  w, a, t};
Cylinder(2) = {0, 0, -L_boss/2,  0, 0, L_boss,  D_boss/2};
Cylinder(3) = {0, a, -L_boss/2,  0, 0, L_boss,  D_boss/2};
Cylinder(4) = {0, 0, -L_boss/2 - 0.01,  0, 0, L_boss + 0.02,  d_bore/2};
Cylinder(5) = {0, a, -L_boss/2 - 0.01,  0, 0, L_boss + 0.02,  d_bore/2};
solid() = BooleanUnion{ Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
lever() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{4, 5}; Delete; };

// Named surfaces, picked by bounding boxes (tolerance e) so that they survive
// changes of the parameters.
e = 1e-6;
r = d_bore/2;  R = D_boss/2;  h = L_boss/2;
bore_A0() = Surface In BoundingBox{-r-e, -r-e, -h-e,  r+e, r+e, h+e};
bore_A()  = Surface In BoundingBox{-r-e, a-r-e, -h-e,  r+e, a+r+e, h+e};
ends_A0() = Surface In BoundingBox{-R-e, -R-e, -h-e,  R+e, R+e, -h+e};
ends_A0() += Surface In BoundingBox{-R-e, -R-e, h-e,  R+e, R+e, h+e};
ends_A()  = Surface In BoundingBox{-R-e, a-R-e, -h-e,  R+e, a+R+e, -h+e};
ends_A() += Surface In BoundingBox{-R-e, a-R-e, h-e,  R+e, a+R+e, h+e};

Physical Volume("lever") = {lever()};
Physical Surface("bore_A0") = {bore_A0()};
Physical Surface("bore_A") = {bore_A()};
Physical Surface("boss_ends_A0") = {ends_A0()};
Physical Surface("boss_ends_A") = {ends_A()};
