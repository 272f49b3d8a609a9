// A guide bar 400 x 20 x 20 mm: its top face (y = 0) the guide, its end
// x = 0 the foot it is held by.
SetFactory("OpenCASCADE");
Box(1) = {0, -20, -10, 400, 20, 20};
Physical Surface("foot") = {1};
Physical Surface("top") = {4};
Physical Volume("bar") = {1};
