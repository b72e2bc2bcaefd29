// A unit box with a cylindrical hole, meshed by Gmsh for the reader tests:
//   gmsh -3 box.geo -format mesh -o gmsh_box_with_hole.mesh
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Cylinder(2) = {0.5, 0.5, -0.1, 0, 0, 1.2, 0.2};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.MeshSizeMax = 0.25;
