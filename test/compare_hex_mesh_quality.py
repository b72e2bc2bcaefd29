#!/usr/bin/env python3
"""Checks the C++ hex quality (hex_mesh_quality_dump: read_ovm_hex_mesh and
hex_mesh_quality) against scripts/hex_mesh_quality.py, an independent
implementation, on random hexahedra; and against VTK's vtkMeshQuality when
the `vtk` module is there (python3-vtk9; not needed in CI).

  python3 test/compare_hex_mesh_quality.py build/test/hex_mesh_quality_dump

The hexahedra: arbitrary ones (8 random points: most are inverted or
twisted), jittered grids (shared faces, a boundary), ones with collapsed
edges (degenerate), flat ones, and cells that are not hexahedra.
"""
import math
import os
import random
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
import hex_mesh_quality as hmq  # noqa: E402
from test_hex_mesh_quality import hex_loops, ovm_text, grid  # noqa: E402

HEX_SIZE = 0.7


def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(1.0, abs(a), abs(b))


def random_meshes(rng):
    """(name, points, cells as loops, hexes in VTK order or None for non-hex cells)."""
    meshes = []
    points, hexes = [], []
    for _ in range(300):  # arbitrary hexes, own vertices
        base = len(points)
        points += [tuple(rng.uniform(-1, 1) for _ in range(3)) for _ in range(8)]
        hexes.append(list(range(base, base + 8)))
    meshes.append(("arbitrary", points, hexes))
    for jitter in (0.05, 0.3):
        p, h = grid(5, 4, 3, 1.0, 0.8, 1.3)
        p = [tuple(x + rng.uniform(-jitter, jitter) for x in q) for q in p]
        meshes.append(("grid jitter %g" % jitter, p, h))
    p, h = grid(3, 3, 2)
    p = [tuple(x + rng.uniform(-0.2, 0.2) for x in q) for q in p]
    for hx in h[::3]:  # collapse an edge of every third hex: equal positions, distinct vertices
        p[hx[1]] = p[hx[0]]
    meshes.append(("collapsed edges", p, h))
    p, h = grid(4, 1, 1, 1.0, 1.0, 1e-9)  # nearly flat
    meshes.append(("flat", p, h))
    return meshes


def run_tool(tool, path):
    out = subprocess.run([tool, path, repr(HEX_SIZE)], check=True, capture_output=True, text=True).stdout
    hexes, others, summary = [], [], {}
    for line in out.splitlines():
        w = line.split()
        if w[0] == "hex":
            hexes.append(([int(x) for x in w[1:9]], float(w[9]), float(w[10]), w[11] == "1", float(w[12])))
        elif w[0] == "other":
            others.append((int(w[1]), " ".join(w[2:])))
        else:
            summary[w[1]] = float(w[2])
    return hexes, others, summary


def vtk_scaled_jacobians(points, hexes):
    import vtk  # noqa: F401
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, VTK_HEXAHEDRON
    from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
    g = vtkUnstructuredGrid()
    pts = vtkPoints()
    pts.SetDataTypeToDouble()  # the default, float, would round the points
    for q in points:
        pts.InsertNextPoint(*q)
    g.SetPoints(pts)
    for h in hexes:
        g.InsertNextCell(VTK_HEXAHEDRON, 8, h)
    mq = vtkMeshQuality()
    mq.SetInputData(g)
    mq.SetHexQualityMeasureToScaledJacobian()
    mq.Update()
    a = mq.GetOutput().GetCellData().GetArray("Quality")
    return [a.GetValue(i) for i in range(len(hexes))]


def check(tool, name, points, hexes, extra_cells, failures):
    cells = [hex_loops(h) for h in hexes] + extra_cells
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "m.ovm")
        with open(path, "w") as f:
            f.write(ovm_text(points, cells, shuffle=True))
        got, others, summary = run_tool(tool, path)
        report, ref_hexes, _, ref_sjs = hmq.evaluate(path, hex_size=HEX_SIZE)

    def fail(msg):
        failures.append("%s: %s" % (name, msg))

    if [g[0] for g in got] != ref_hexes:
        fail("the hexahedra's vertices (VTK order) differ from the script's")
    if len(others) != len(extra_cells) or [o[1] for o in others] != [
            hmq.cell_to_hex(c)[1] for c in extra_cells]:
        fail("other cells %s" % others)
    for i, (hx, sj, corners, degenerate, volume) in enumerate(got):
        P = [points[v] for v in hx]
        r_sj, r_corners, r_degenerate = hmq.scaled_jacobians(P)
        if not (close(sj, r_sj) and close(corners, r_corners) and degenerate == r_degenerate):
            fail("hex %d: scaled Jacobian %r %r %r, script %r %r %r" % (i, sj, corners, degenerate, r_sj,
                                                                        r_corners, r_degenerate))
        if not close(volume, hmq.hex_volume(P)):
            fail("hex %d: volume %r, script %r" % (i, volume, hmq.hex_volume(P)))
    s, rs = summary, report["scaled_jacobian"]
    pairs = [("scaled_jacobian.min", rs["min"]), ("scaled_jacobian.median", rs["median"]),
             ("scaled_jacobian.mean", rs["mean"]), ("scaled_jacobian.max", rs["max"]),
             ("scaled_jacobian_at_most_0", rs["count_le_0"]), ("scaled_jacobian_below_0_2", rs["count_lt_0_2"]),
             ("scaled_jacobian_below_0_5", rs["count_lt_0_5"]), ("degenerate", rs["degenerate"]),
             ("scaled_jacobian_corners.median", report["scaled_jacobian_corners_only"]["median"]),
             ("volume", report["hex_volume"]["total"]),
             ("negative_volume_hexes", report["hex_volume"]["negative_hexes"]),
             ("edge_length.count", report["edge_length"]["count"]),
             ("edge_length.min", report["edge_length"]["min"]), ("edge_length.median", report["edge_length"]["median"]),
             ("edge_length.mean", report["edge_length"]["mean"]), ("edge_length.max", report["edge_length"]["max"]),
             ("metric_edge_length.median", report["edge_length"]["median"] / HEX_SIZE),
             ("metric_size.min", report["size"]["edge_ratio"]["min"]),
             ("metric_size.median", report["size"]["edge_ratio"]["median"]),
             ("metric_size.max", report["size"]["edge_ratio"]["max"]),
             ("metric_sizes_within_25_percent", report["size"]["within_25_percent"])]
    quad_edges = hmq.boundary_quad_edges(ref_hexes)
    pairs.append(("boundary_edge_rms", math.sqrt(sum(hmq.norm(hmq.sub(points[b], points[a])) ** 2
                                                     for a, b in quad_edges) / len(quad_edges))))
    for key, ref in pairs:
        if not close(s[key], ref, 1e-11):
            fail("%s: %r, script %r" % (key, s[key], ref))
    try:
        vtk_sjs = vtk_scaled_jacobians(points, ref_hexes)
    except ImportError:
        return False
    for i, (g, v) in enumerate(zip(got, vtk_sjs)):
        # VTK gives VERDICT_DBL_MAX (1e30) where a frame vector has length 0; we give 0 and flag it.
        if g[3] and v >= 1e30:
            continue
        if not close(g[1], v, 1e-9):
            fail("hex %d: scaled Jacobian %r, VTK %r" % (i, g[1], v))
    return True


def main():
    tool = sys.argv[1]
    rng = random.Random(7)
    failures, with_vtk = [], False
    # Cells that are not hexahedra: a tetrahedron's 4 triangles, a hex missing a face, one with a face reversed.
    for name, points, hexes in random_meshes(rng):
        n = len(points)
        points = points + [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
        flipped = hex_loops(hexes[1])
        flipped[0] = flipped[0][::-1]  # one face reversed: not consistently oriented
        extra = [[[n, n + 2, n + 1], [n, n + 1, n + 3], [n + 1, n + 2, n + 3], [n, n + 3, n + 2]],
                 hex_loops(hexes[0])[:5], flipped]
        with_vtk = check(tool, name, points, hexes, extra, failures) or with_vtk
        print("%s: %d hexahedra checked" % (name, len(hexes)))
    print("references: scripts/hex_mesh_quality.py%s" % (" and VTK's vtkMeshQuality" if with_vtk else
                                                         " (VTK not installed: its check not run)"))
    for f in failures[:20]:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
