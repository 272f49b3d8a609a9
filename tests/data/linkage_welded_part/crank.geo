// The welded crank of tests/data/linkage_welded_part (mm): the arm (boss O with its bore and the
// plate, up to the hub) and the hub (boss B with its bore), two solids touching on the hub's
// cylinder. Written with: gmsh crank.geo -0 -o crank.brep (the two volumes, not fragmented).
SetFactory("OpenCASCADE");
length = 100; D = 40; d = 20; L = 30; w = 25; t = 12;
Cylinder(1) = {0, 0, -L/2, 0, 0, L, D/2};
Box(2) = {0, -w/2, -t/2, length, w, t};
BooleanUnion(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
Cylinder(4) = {length, 0, -L/2, 0, 0, L, D/2};
Cylinder(5) = {length, 0, -L/2, 0, 0, L, D/2};
BooleanDifference(6) = {Volume{3}; Delete;}{Volume{5}; Delete;};
Cylinder(7) = {0, 0, -L, 0, 0, 2*L, d/2};
BooleanDifference(8) = {Volume{6}; Delete;}{Volume{7}; Delete;};
Cylinder(9) = {length, 0, -L, 0, 0, 2*L, d/2};
BooleanDifference(10) = {Volume{4}; Delete;}{Volume{9}; Delete;};
