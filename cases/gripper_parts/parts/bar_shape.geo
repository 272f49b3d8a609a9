// The shape of a two-pin bar, included by rod.geo, rocker.geo and link.geo
// after they set its dimensions (mm): bore 0 (diameter d0, boss diameter D0)
// at the origin, bore 1 (d1, D1) at (length, 0), bosses of length L along the
// pin axis z, symmetric about z = 0, joined by a web of width w (along y) and
// thickness t (along z) on the x axis.
//
// Leaves: part() the volume, bore_0() and bore_1() the bore surfaces.
SetFactory("OpenCASCADE");
Geometry.OCCTargetUnit = "MM";

boss_0 = newv; Cylinder(boss_0) = {0, 0, -L/2, 0, 0, L, D0/2};
boss_1 = newv; Cylinder(boss_1) = {length, 0, -L/2, 0, 0, L, D1/2};
web = newv; Box(web) = {0, -w/2, -t/2, length, w, t};
solid() = BooleanUnion{ Volume{boss_0}; Delete; }{ Volume{boss_1, web}; Delete; };
hole_0 = newv; Cylinder(hole_0) = {0, 0, -L, 0, 0, 2*L, d0/2};
hole_1 = newv; Cylinder(hole_1) = {length, 0, -L, 0, 0, 2*L, d1/2};
part() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{hole_0, hole_1}; Delete; };

// A bore is the only surface inside its pin's cylinder box (the boss ends
// reach out to the boss radius, beyond the box).
eps = 1e-3 * length;
bore_0() = Surface In BoundingBox{-d0/2 - eps, -d0/2 - eps, -L/2 - eps, d0/2 + eps, d0/2 + eps, L/2 + eps};
bore_1() = Surface In BoundingBox{length - d1/2 - eps, -d1/2 - eps, -L/2 - eps,
                                  length + d1/2 + eps, d1/2 + eps, L/2 + eps};
