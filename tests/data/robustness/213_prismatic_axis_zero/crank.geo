// Crank of the slider-crank: bore O at the origin, bore B on +x.
SetFactory("OpenCASCADE");
s = 1;
length = 100*s; D = 40*s; d = 20*s; L = 30*s; w = 25*s; t = 12*s; e = 0.5*s;
Cylinder(1) = {0, 0, -L/2, 0, 0, L, D/2};
Cylinder(2) = {length, 0, -L/2, 0, 0, L, D/2};
Box(3) = {0, -w/2, -t/2, length, w, t};
BooleanUnion(4) = {Volume{1}; Delete;}{Volume{2, 3}; Delete;};
Cylinder(5) = {0, 0, -L, 0, 0, 2*L, d/2};
Cylinder(6) = {length, 0, -L, 0, 0, 2*L, d/2};
BooleanDifference(7) = {Volume{4}; Delete;}{Volume{5, 6}; Delete;};
Physical Surface("bore_O") = Surface In BoundingBox{-d/2-e, -d/2-e, -L/2-e, d/2+e, d/2+e, L/2+e};
Physical Surface("bore_B") = Surface In BoundingBox{length-d/2-e, -d/2-e, -L/2-e, length+d/2+e, d/2+e, L/2+e};
Physical Volume("crank") = {7};
