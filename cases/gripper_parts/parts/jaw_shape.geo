// The shape of a jaw (link 4) of the crank-slider gripper, included by
// jaw_lower.geo and jaw_upper.geo after they set `side` (-1: the jaw below
// the slider line, +1: above; the upper jaw is the lower one mirrored in y).
// mm, pin axes along z, symmetric about z = 0. Frame: bore A (the rocker's
// pin) at the origin, axes parallel to the world's (the jaw translates).
//
//            A o                     (side = -1; the slider line is above)
//   pad      ___\___
//   ========|   o C |   finger: x in [-a - finger_length, -a + F/2],
//   ========|_______|           |y - side k| <= F/2; its face toward the
//                                slider line (the pad) is at |y| = k - F/2
// Bore C is at (-a, side k): a = the ground pivots' spacing along x, k the
// offset that puts the pad face_offset beyond the pin line (README).
//
// Leaves: part() the volume, bore_A(), bore_C() and pad() surfaces.
SetFactory("OpenCASCADE");
Geometry.OCCTargetUnit = "MM";
DefineConstant[
  a = {50.0, Name "jaw/pin spacing A to C along x (mm)"},
  face_offset = {14.65, Name "jaw/pad face beyond the pin line A (mm)"},
  finger_length = {60.0, Name "jaw/finger length ahead of C (mm)"},
  F = {24.0, Name "jaw/finger depth in the plane (mm)"},
  T = {14.0, Name "jaw/finger thickness along the pins (mm)"},
  d = {10.0, Name "jaw/bore diameter A and C (mm)"},
  D = {20.0, Name "jaw/boss A diameter (mm)"},
  L = {14.0, Name "jaw/boss A length along the pins (mm)"},
  w = {14.0, Name "jaw/arm A-C width (mm)"},
  t = {10.0, Name "jaw/arm A-C thickness (mm)"}
];
k = face_offset + F/2;
cy = side * k;
boss = newv; Cylinder(boss) = {0, 0, -L/2, 0, 0, L, D/2};
arm_length = Sqrt(a^2 + k^2);
arm = newv; Box(arm) = {0, -w/2, -t/2, arm_length, w, t};
Rotate {{0, 0, 1}, {0, 0, 0}, Atan2(cy, -a)} { Volume{arm}; }
finger = newv; Box(finger) = {-a - finger_length, cy - F/2, -T/2, finger_length + F/2, F, T};
solid() = BooleanUnion{ Volume{boss}; Delete; }{ Volume{arm, finger}; Delete; };
hole_A = newv; Cylinder(hole_A) = {0, 0, -L, 0, 0, 2*L, d/2};
hole_C = newv; Cylinder(hole_C) = {-a, cy, -T, 0, 0, 2*T, d/2};
part() = BooleanDifference{ Volume{solid()}; Delete; }{ Volume{hole_A, hole_C}; Delete; };

eps = 1e-3;
bore_A() = Surface In BoundingBox{-d/2 - eps, -d/2 - eps, -L/2 - eps, d/2 + eps, d/2 + eps, L/2 + eps};
bore_C() = Surface In BoundingBox{-a - d/2 - eps, cy - d/2 - eps, -T/2 - eps, -a + d/2 + eps, cy + d/2 + eps, T/2 + eps};
// The pad: the finger's face toward the slider line (the arm joins it above
// bore C, so it is the whole face less the arm's footprint).
pad_y = side * face_offset;
pad() = Surface In BoundingBox{-a - finger_length - eps, pad_y - eps, -T/2 - eps, -a + F/2 + eps, pad_y + eps, T/2 + eps};
