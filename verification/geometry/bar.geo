// The bar of the `kinetofem verify` check fem.bar_tension, compiled into the
// verification library (verification/CMakeLists.txt). Same geometry as
// tests/data/cases/bar_tension/bar.geo (the fe_static case test); keep the two in step.
// Straight bar 100 x 20 x 20 mm (in metres) for the fe_static pipeline test.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.02, 0.02};
eps = 1e-6;
Physical Volume("bar") = {1};
Physical Surface("x0") = Surface In BoundingBox{-eps, -eps, -eps, eps, 0.02 + eps, 0.02 + eps};
Physical Surface("x1") = Surface In BoundingBox{0.1 - eps, -eps, -eps, 0.1 + eps, 0.02 + eps, 0.02 + eps};
Physical Point("origin") = Point In BoundingBox{-eps, -eps, -eps, eps, eps, eps};
Physical Point("corner_y") = Point In BoundingBox{-eps, 0.02 - eps, -eps, eps, 0.02 + eps, eps};
