// A base plate: bore_A0 at the origin, the chain hinge at B0, its foot at y = -200 mm.
SetFactory("OpenCASCADE");
Box(1) = {-60, -200, -15, 200, 330, 30};
Cylinder(2) = {0, 0, -20, 0, 0, 40, 12};
Cylinder(3) = {75, 88.23529411764706, -20, 0, 0, 40, 8};
BooleanDifference(4) = {Volume{1}; Delete;}{Volume{2, 3}; Delete;};
e = 0.5;
Physical Surface("bore_A0") = Surface In BoundingBox{-12-e, -12-e, -15-e, 12+e, 12+e, 15+e};
Physical Surface("hinge") = Surface In BoundingBox{75-8-e, 88.235-8-e, -15-e, 75+8+e, 88.235+8+e, 15+e};
Physical Surface("foot") = Surface In BoundingBox{-60-e, -200-e, -15-e, 140+e, -200+e, 15+e};
Physical Volume("frame") = {4};
