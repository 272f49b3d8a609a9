// The lower jaw of the crank-slider gripper (cases/gripper_parts/README.md):
// jaw_shape.geo with side = -1 (below the slider line).
side = -1;
Include "jaw_shape.geo";
Physical Volume("body") = part();
Physical Surface("bore_A") = bore_A();
Physical Surface("bore_C") = bore_C();
Physical Surface("pad") = pad();
