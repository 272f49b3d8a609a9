// Builds the two FE parts of the slider_crank_parts case and writes them as
// STEP files in millimetres (OpenCASCADE writes STEP in mm by default).
//
//   cd cases/slider_crank_parts/parts && gmsh -0 make_parts.geo
//
// Both parts: pin axes along z, symmetric about z = 0, bores through the
// bosses, a plate joining the bosses along +x. Dimensions in mm.
SetFactory("OpenCASCADE");
// The numbers below are mm: OpenCASCADE's default target unit, set here
// explicitly (the STEP writer converts from it to the file's unit, mm).
Geometry.OCCTargetUnit = "MM";

// A link: boss at (0, 0) and at (length, 0), each of outer diameter D, bore
// diameter d and length L along z (|z| <= L/2), joined by a plate of width w
// along y and thickness t along z (|y| <= w/2, |z| <= t/2, 0 <= x <= length).
Macro Link
  boss_0 = newv; Cylinder(boss_0) = {0, 0, -L/2, 0, 0, L, D/2};
  boss_1 = newv; Cylinder(boss_1) = {length, 0, -L/2, 0, 0, L, D/2};
  plate = newv; Box(plate) = {0, -w/2, -t/2, length, w, t};
  solid() = BooleanUnion{ Volume{boss_0}; Delete; }{ Volume{boss_1, plate}; Delete; };
  bore_0 = newv; Cylinder(bore_0) = {0, 0, -L, 0, 0, 2*L, d/2};
  bore_1 = newv; Cylinder(bore_1) = {length, 0, -L, 0, 0, 2*L, d/2};
  part() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{bore_0, bore_1}; Delete; };
Return

// Crank: bore O (ground pivot and motor shaft) at the origin, bore B at
// x = 100 mm (r of cases/mechanisms/slider_crank).
length = 100; D = 40; d = 20; L = 30; w = 25; t = 12;
Call Link;
Save "crank.step";

Delete All;  // clears the model and the kernel choice
SetFactory("OpenCASCADE");
Geometry.OCCTargetUnit = "MM";

// Rod: bore B at the origin, bore C at x = 300 mm (l of the slider-crank).
length = 300; D = 36; d = 16; L = 24; w = 20; t = 10;
Call Link;
Save "rod.step";

// Stop here: gmsh -0 would otherwise also write untitled.geo_unrolled.
Exit;
