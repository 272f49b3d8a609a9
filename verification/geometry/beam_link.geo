// The link of the load-transfer check (`kinetofem verify` loads.accelerated_link
// and tests/verification/loads), compiled into the verification library
// (verification/CMakeLists.txt). Same geometry as tests/data/meshes/beam_link.geo
// (tests/unit/solver/test_couplings.cpp); keep the two in step.
// A slender link for the load-transfer verification: a bar 640 x 40 x 20 mm
// (x from -20 to 620 mm, depth y 40, thickness z 20, metres below) with two
// pin bores of 16 mm at x = 0 and x = 0.6 (span L = 600 mm, L/h = 15).
// Physical groups: volume "link", surfaces "bore_1", "bore_2".
SetFactory("OpenCASCADE");
Box(1) = {-0.02, -0.02, -0.01, 0.64, 0.04, 0.02};
Cylinder(2) = {0, 0, -0.02, 0, 0, 0.04, 0.008};
Cylinder(3) = {0.6, 0, -0.02, 0, 0, 0.04, 0.008};
BooleanDifference(4) = { Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
eps = 1e-5;
Physical Volume("link") = {4};
Physical Surface("bore_1") = Surface In BoundingBox{-0.008 - eps, -0.008 - eps, -0.01 - eps, 0.008 + eps, 0.008 + eps, 0.01 + eps};
Physical Surface("bore_2") = Surface In BoundingBox{0.592 - eps, -0.008 - eps, -0.01 - eps, 0.608 + eps, 0.008 + eps, 0.01 + eps};
