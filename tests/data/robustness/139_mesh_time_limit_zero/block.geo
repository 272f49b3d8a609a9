// A block 100 x 20 x 10 mm (OpenCASCADE), after a loop that would keep Gmsh
// busy for many minutes: stopped by mesh.time_limit_s.
SetFactory("OpenCASCADE");
x = 0;
For i In {1:2000000000}
  x = x + 1;
EndFor
Box(1) = {0, -10, -5, 100, 20, 10};
