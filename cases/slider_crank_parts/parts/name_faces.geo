// Naming the faces of a STEP part that has no names: an example to copy.
//
// A STEP file from a CAD program carries the solid but no names for its
// faces. This script imports crank.step and makes the bores physical
// surfaces (by bounding box, in the file's mm) and the solid a physical
// volume. Check it in Gmsh:
//
//   cd cases/slider_crank_parts/parts && gmsh name_faces.geo -3
//
// (writes name_faces.msh here), or use it as a part file in a case instead
// of the STEP: file = "parts/name_faces.geo", length_unit = "mm" (a .geo
// carries no unit). kinetofem then finds the sets bore_O and bore_B
// without [[face_set]] boxes.
SetFactory("OpenCASCADE");

// Coordinates in mm: OpenCASCADE converts the STEP file's unit to this one.
Geometry.OCCTargetUnit = "MM";
v() = ShapeFromFile("crank.step");

// A surface is taken when it lies ENTIRELY inside the box (xmin, ymin,
// zmin, xmax, ymax, zmax): make the box a little larger than the face
// (eps), but not so large that it holds a neighbouring face too. Here the
// bores have radius 10 and length 30 (|z| <= 15); the boss ends (annuli
// out to radius 20) stick out of these boxes and are not taken.
eps = 0.5;
r = 10; half_length = 15;
Physical Surface("bore_O") = Surface In BoundingBox{-r - eps, -r - eps, -half_length - eps,
                                                    r + eps, r + eps, half_length + eps};
Physical Surface("bore_B") = Surface In BoundingBox{100 - r - eps, -r - eps, -half_length - eps,
                                                    100 + r + eps, r + eps, half_length + eps};
Physical Volume("crank") = v();

// For "gmsh name_faces.geo -3" only: element size 4 mm, quadratic
// tetrahedra. kinetofem replaces every Mesh.* option by its [mesh] section.
Mesh.MeshSizeMax = 4;
Mesh.MeshSizeFromCurvature = 16;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
