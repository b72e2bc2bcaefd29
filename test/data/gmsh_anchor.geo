// CGAL's anchor (data/meshes/anchor.off of Debian's libcgal-demo, written as
// ASCII STL by scripts/make_benchmark_meshes.sh), remeshed by Gmsh 4.8 at a
// uniform size, the bounding-box diagonal / 15, for the sharp-feature tests:
//   gmsh -3 gmsh_anchor.geo -format mesh -o gmsh_anchor.mesh   (beside anchor.stl)
Merge "anchor.stl";
ClassifySurfaces{40 * Pi / 180, 1, 1, Pi};
CreateGeometry;
Surface Loop(1) = Surface{:};
Volume(1) = {1};
Mesh.MeshSizeMax = 1.4575200085748394 / 15;
