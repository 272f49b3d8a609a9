// The welded parts of the lever (four-bar) manipulator as built
// (cases/lever_manipulator_as_built), written as STEP files in millimetres, one file per part,
// each file holding the part's solids as separate, touching volumes (the welds are made by
// kinetofem when it meshes the part):
//
//   cd cases/lever_manipulator_as_built/parts && gmsh -0 make_parts.geo
//
// Every dimension and the reason for it is in ../README.md. Pin axes along z. Each file is
// in its body frame (x, y as the case's [[point]]s) with z = 0 on the part's own mid-plane,
// except the frame, which is in world coordinates; the case places each part at its z by
// [[part]] offset_mm. Solids touch face to face: a plate that meets a hub is cut by the hub's
// outer cylinder, so the seam is a shared surface, as a weld preparation would make it.
SetFactory("OpenCASCADE");
Geometry.OCCTargetUnit = "MM";

// A hub (boss around a bore): outer diameter hD, bore hd, axis z through (hx, hy),
// from z = hz0 to hz1.
Macro Hub
  hub_o = newv; Cylinder(hub_o) = {hx, hy, hz0, 0, 0, hz1 - hz0, hD/2};
  hub_i = newv; Cylinder(hub_i) = {hx, hy, hz0 - 1, 0, 0, hz1 - hz0 + 2, hd/2};
  hub() = BooleanDifference{ Volume{hub_o}; Delete; }{ Volume{hub_i}; Delete; };
Return

// The four-bar equivalent to the SPEC §1 example (SPEC §2) in mm: A0 = (0, 0), A = (0, a),
// B = (r, a), B0 = (r, a - b0).
a = 500; c = 350; h = 100; r = 75; b0 = a*c/(c + r);
xB0 = r; yB0 = a - b0;                      // B0 = (75, 88.235) mm, rocker BB0 = b0 = 411.765 mm

// The dimensions the sensitivity band varies (cases/sensitivity/as_built_band), with the
// values of this case; e.g. gmsh -0 make_parts.geo -setnumber rocker_plate_t 20
// -setstring prefix "$PWD/rocker20_" writes rocker20_rocker.step and so on (an absolute
// prefix: Gmsh saves relative names beside this file).
DefineConstant[ lever_plate_t = 16 ];       // lever plate thickness (z)
DefineConstant[ rocker_plate_t = 12 ];      // rocker plate thickness (z)
DefineConstant[ prefix = "" ];              // prefix of the written files' names

// ---------------------------------------------------------------------------------------
// Frame (the ground's part), world coordinates: A0 at the origin.
foot_y = -500;                              // foundation 500 mm below A0
foot = newv; Box(foot) = {-160, foot_y, -160, 320, 20, 320};
col_o = newv; Box(col_o) = {-80, foot_y + 20, -80, 160, 100 - (foot_y + 20), 160};
col_i = newv; Box(col_i) = {-72, foot_y + 19, -72, 144, 100 - (foot_y + 20) + 2, 144};
column() = BooleanDifference{ Volume{col_o}; Delete; }{ Volume{col_i}; Delete; };
cap = newv; Box(cap) = {-80, 100, -80, 160, 10, 160};
head_box = newv; Box(head_box) = {-80, -100, 80, 200, 240, 15};
shaft_hole = newv; Cylinder(shaft_hole) = {0, 0, 70, 0, 0, 40, 40/2};   // the drive shaft passes the head plate
head() = BooleanDifference{ Volume{head_box}; Delete; }{ Volume{shaft_hole}; Delete; };
hx = 0; hy = 0; hz0 = 95; hz1 = 145; hD = 80; hd = 40; Call Hub;
hub_A0() = hub();
post_bar = newv; Cylinder(post_bar) = {xB0, yB0, 95, 0, 0, 215 - 95, 30};
post_hole = newv; Cylinder(post_hole) = {xB0, yB0, 195, 0, 0, 30, 25/2};  // the pin's clearance beyond the hub
post() = BooleanDifference{ Volume{post_bar}; Delete; }{ Volume{post_hole}; Delete; };
hx = xB0; hy = yB0; hz0 = 215; hz1 = 250; hD = 60; hd = 25; Call Hub;
hub_B0() = hub();
Save StrCat(prefix, "frame.step");

// ---------------------------------------------------------------------------------------
// Lever 1: A0 at the origin, A = (0, a); plate mid-plane z = 0 (placed at z = 175).
Recursive Delete { Volume{:}; }
hx = 0; hy = 0; hz0 = -25; hz1 = 25; hD = 80; hd = 40; Call Hub;
hub_A0() = hub();
hx = 0; hy = a; hz0 = -20; hz1 = 20; hD = 70; hd = 30; Call Hub;
hub_A() = hub();
plate_box = newv; Box(plate_box) = {-30, 0, -lever_plate_t/2, 60, a, lever_plate_t};
cut_0 = newv; Cylinder(cut_0) = {0, 0, -100, 0, 0, 200, 80/2};
cut_1 = newv; Cylinder(cut_1) = {0, a, -100, 0, 0, 200, 70/2};
plate() = BooleanDifference{ Volume{plate_box}; Delete; }{ Volume{cut_0, cut_1}; Delete; };
Save StrCat(prefix, "lever.step");

// ---------------------------------------------------------------------------------------
// Coupler 2 (the arm): A at the origin, B = (r, 0), C = (-c, 0), H = (-c, h); mid-plane
// z = 0 (placed at z = 225). Head: one flame-cut lug holding bores A and B; the arm web
// welded to it; the gripper pad on the web's end.
Recursive Delete { Volume{:}; }
hd_A = newv; Cylinder(hd_A) = {0, 0, -25, 0, 0, 50, 35};
hd_B = newv; Cylinder(hd_B) = {r, 0, -25, 0, 0, 50, 35};
hd_M = newv; Box(hd_M) = {0, -35, -25, r, 70, 50};
head_full() = BooleanUnion{ Volume{hd_A}; Delete; }{ Volume{hd_B, hd_M}; Delete; };
bore_A = newv; Cylinder(bore_A) = {0, 0, -26, 0, 0, 52, 30/2};
bore_B = newv; Cylinder(bore_B) = {r, 0, -26, 0, 0, 52, 25/2};
head() = BooleanDifference{ Volume{head_full()}; Delete; }{ Volume{bore_A, bore_B}; Delete; };
web_box = newv; Box(web_box) = {-c - 40, -30, -6, c + 40, 60, 12};
cut_0 = newv; Cylinder(cut_0) = {0, 0, -100, 0, 0, 200, 35};
web() = BooleanDifference{ Volume{web_box}; Delete; }{ Volume{cut_0}; Delete; };
pad = newv; Box(pad) = {-c - 40, 30, -40, 80, 15, 80};
Save StrCat(prefix, "coupler.step");

// ---------------------------------------------------------------------------------------
// Rocker 3: B0 at the origin, B = (0, b0); plate mid-plane z = 0 (placed at z = 275).
Recursive Delete { Volume{:}; }
hx = 0; hy = 0; hz0 = -20; hz1 = 20; hD = 60; hd = 25; Call Hub;
hub_B0() = hub();
hx = 0; hy = b0; hz0 = -20; hz1 = 20; hD = 60; hd = 25; Call Hub;
hub_B() = hub();
plate_box = newv; Box(plate_box) = {-25, 0, -rocker_plate_t/2, 50, b0, rocker_plate_t};
cut_0 = newv; Cylinder(cut_0) = {0, 0, -100, 0, 0, 200, 30};
cut_1 = newv; Cylinder(cut_1) = {0, b0, -100, 0, 0, 200, 30};
plate() = BooleanDifference{ Volume{plate_box}; Delete; }{ Volume{cut_0, cut_1}; Delete; };
Save StrCat(prefix, "rocker.step");

// ---------------------------------------------------------------------------------------
// Gripper: H at the origin (the coupler's (-c, h)); mid-plane z = 0 (placed at z = 225, the
// coupler's web plane). Carrier plate on the coupler's pad, rotary module, parallel gripper unit.
Recursive Delete { Volume{:}; }
carrier = newv; Box(carrier) = {-60, -55, -40, 120, 15, 80};
rotary = newv; Cylinder(rotary) = {0, -40, 0, 0, 80, 0, 50};
grip = newv; Box(grip) = {-60, 40, -40, 120, 60, 80};
Save StrCat(prefix, "gripper.step");

// Stop here: gmsh -0 would otherwise also write untitled.geo_unrolled.
Exit;
