// A unit box with a cylindrical hole in two physical volumes (7 and 9) and a
// physical surface (3), for the .msh reader tests; make_files.sh writes the
// files from it with Gmsh (4.8.4 here).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Cylinder(2) = {0.5, 0.5, -0.1, 0, 0, 1.2, 0.2};
BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Physical Volume(7) = {1};
Physical Volume(9) = {1};
Physical Surface(3) = {1, 2, 3};
Mesh.MeshSizeMax = 0.5;
