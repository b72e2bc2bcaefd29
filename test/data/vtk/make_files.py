#!/usr/bin/python3
"""Writes the legacy .vtk test files with VTK 9.1 (Debian's python3-vtk9) from
../gmsh/box.mesh (Gmsh's Medit export of a box with a hole): its tetrahedra
and triangles as one unstructured grid, points in double, in the layouts of
file versions 5.1 (VTK 9's default) and 4.2, ASCII and binary; and Gmsh's
own .vtk export of the same mesh. The tests do not need VTK or Gmsh.

  /usr/bin/python3 test/data/vtk/make_files.py
"""
import os
import subprocess

from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, VTK_TETRA, VTK_TRIANGLE
from vtkmodules.vtkIOLegacy import vtkUnstructuredGridWriter

HERE = os.path.dirname(os.path.abspath(__file__))


def read_medit(path):
    t = open(path).read().split()
    def section(name, width):
        i = t.index(name)
        n = int(t[i + 1])
        return [t[i + 2 + width * k:i + 2 + width * (k + 1)] for k in range(n)]
    points = [tuple(map(float, r[:3])) for r in section("Vertices", 4)]
    tets = [[int(x) - 1 for x in r[:4]] for r in section("Tetrahedra", 5)]
    tris = [[int(x) - 1 for x in r[:3]] for r in section("Triangles", 4)]
    return points, tets, tris


points, tets, tris = read_medit(os.path.join(HERE, "..", "gmsh", "box.mesh"))
grid = vtkUnstructuredGrid()
pts = vtkPoints()
pts.SetDataTypeToDouble()
for p in points:
    pts.InsertNextPoint(*p)
grid.SetPoints(pts)
for t in tris:  # the triangles first: the tetrahedra are not the first cells
    grid.InsertNextCell(VTK_TRIANGLE, 3, t)
for t in tets:
    grid.InsertNextCell(VTK_TETRA, 4, t)
for version, name in ((51, "box_51"), (42, "box_42")):
    for binary in (False, True):
        w = vtkUnstructuredGridWriter()
        w.SetInputData(grid)
        w.SetFileVersion(version)
        w.SetFileType(2 if binary else 1)
        w.SetFileName(os.path.join(HERE, name + ("_binary" if binary else "") + ".vtk"))
        w.Write()
gmsh = os.path.join(HERE, "..", "gmsh", "box_41.msh")
subprocess.run(["gmsh", gmsh, "-0", "-format", "vtk", "-o", os.path.join(HERE, "box_gmsh.vtk")], check=True,
               stdout=subprocess.DEVNULL)
