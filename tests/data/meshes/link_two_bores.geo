// A straight link 300 x 60 x 20 mm (metres) with two pin bores of diameter
// 30 mm at x = 0 and x = 0.24, pin axes along z. For coupling and load
// transfer tests. Physical groups: volume "link"; surfaces "bore_1", "bore_2".
SetFactory("OpenCASCADE");
Box(1) = {-0.03, -0.03, -0.01, 0.30, 0.06, 0.02};
Cylinder(2) = {0, 0, -0.02, 0, 0, 0.04, 0.015};
Cylinder(3) = {0.24, 0, -0.02, 0, 0, 0.04, 0.015};
BooleanDifference(4) = { Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
eps = 1e-5;
Physical Volume("link") = {4};
Physical Surface("bore_1") = Surface In BoundingBox{-0.015 - eps, -0.015 - eps, -0.01 - eps, 0.015 + eps, 0.015 + eps, 0.01 + eps};
Physical Surface("bore_2") = Surface In BoundingBox{0.225 - eps, -0.015 - eps, -0.01 - eps, 0.255 + eps, 0.015 + eps, 0.01 + eps};
