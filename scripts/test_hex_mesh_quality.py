#!/usr/bin/env python3
"""Tests of hex_mesh_quality.py (standard library only).

Run from the repository root:
  python3 -m unittest discover -s scripts -p 'test_*.py'

The OVM files are written the way HexEx writes them: HexEx passes the corners
of a unit parameter cube to OpenVolumeMesh's HexahedralMeshTopologyKernel::
add_cell(8 vertices) in the order [c001 c101 c111 c011 c000 c010 c110 c100]
(cUVW: corner at u, v, w), i.e. in VTK numbering [4 5 6 7 0 3 2 1], and
add_cell makes the half-faces below from that list (normals pointing into the
cell); a face shared with an earlier cell is reused with the opposite
orientation (odd half-face id).
"""
import contextlib
import io
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import hex_mesh_quality as hmq  # noqa: E402

VTK_TO_OVM_ADD_CELL = (4, 5, 6, 7, 0, 3, 2, 1)
OVM_ADD_CELL_FACES = ((3, 2, 1, 0), (7, 6, 5, 4), (1, 2, 6, 7),
                      (4, 5, 3, 0), (1, 7, 4, 0), (2, 3, 5, 6))
UNIT_CUBE = ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
             (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))


def hex_loops(h):
    """The 6 half-face vertex loops OVM's add_cell makes for the hex h (VTK order)."""
    o = [h[i] for i in VTK_TO_OVM_ADD_CELL]
    return [[o[i] for i in f] for f in OVM_ADD_CELL_FACES]


def ovm_text(points, cells, shuffle=False):
    """OVM ASCII text; cells: lists of half-face vertex loops."""
    edges, edge_id, faces, face_id, polys = [], {}, [], {}, []

    def halfedge(a, b):
        key = (min(a, b), max(a, b))
        if key not in edge_id:
            edge_id[key] = len(edges)
            edges.append((a, b))
        e = edge_id[key]
        return 2 * e if edges[e] == (a, b) else 2 * e + 1

    def halfface(loop):
        key = frozenset(loop)
        if key not in face_id:
            face_id[key] = len(faces)
            faces.append([halfedge(loop[i], loop[(i + 1) % len(loop)]) for i in range(len(loop))])
            return 2 * face_id[key]
        f = face_id[key]
        return 2 * f if halfedge(loop[0], loop[1]) in faces[f] else 2 * f + 1

    rng = random.Random(1)
    for loops in cells:
        hfs = [halfface(l) for l in loops]
        if shuffle:
            rng.shuffle(hfs)
        polys.append(hfs)
    out = ["OVM ASCII", "# written by test_hex_mesh_quality", "Vertices", str(len(points))]
    out += ["%.17g %.17g %.17g" % tuple(p) for p in points]
    out += ["Edges", str(len(edges))] + ["%d %d" % e for e in edges]
    out += ["Faces", str(len(faces))] + ["%d %s" % (len(f), " ".join(map(str, f))) for f in faces]
    out += ["Polyhedra", str(len(polys))] + ["%d %s" % (len(c), " ".join(map(str, c))) for c in polys]
    return "\n".join(out) + "\n"


def grid(nx, ny, nz, hx=1.0, hy=1.0, hz=1.0):
    """Points and hexes (VTK order) of an nx x ny x nz block of boxes."""
    idx = lambda i, j, k: i + (nx + 1) * (j + (ny + 1) * k)
    points = [(i * hx, j * hy, k * hz) for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)]
    hexes = [[idx(i + a, j + b, k + c) for a, b, c in UNIT_CUBE]
             for k in range(nz) for j in range(ny) for i in range(nx)]
    return points, hexes


# The box [0,2]x[0,1]x[0,1] as a Medit tet mesh (each unit cube as 6
# positively oriented tets around its diagonal), with comments, counts on the next line, and sections
# that must be skipped.
BOX_MESH = """MeshVersionFormatted
2
# a comment line
Dimension 3
Vertices
12
0 0 0 1   1 0 0 1   2 0 0 1
0 1 0 1   1 1 0 1   2 1 0 1   # a trailing comment
0 0 1 1   1 0 1 1   2 0 1 1
0 1 1 1   1 1 1 1   2 1 1 1
Corners 2
1 12
Ridges
1
1
RequiredVertices 1 3
Triangles
2
1 2 5 7
1 5 4 7
Edges 1
1 2 3
Tetrahedra
12
1 2 5 11 0   1 8 2 11 0   1 5 4 11 0   1 4 10 11 0   1 7 8 11 0   1 10 7 11 0
2 3 6 12 0   2 9 3 12 0   2 6 5 12 0   2 5 11 12 0   2 8 9 12 0   2 11 8 12 0
End
"""


def medit_tets(points, hexes):
    """A Medit tet mesh of hexes (VTK order), each split into the 6 tets
    around its diagonal 0-6 (conforming when all hexes of a grid do so)."""
    tets = [[h[a], h[b], h[c], h[d]] for h in hexes
            for a, b, c, d in ((0, 1, 2, 6), (0, 5, 1, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 4, 5, 6), (0, 7, 4, 6))]
    return ("MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n%s\nTetrahedra\n%d\n%s\nEnd\n" % (
        len(points), "\n".join("%.17g %.17g %.17g 0" % p for p in points),
        len(tets), "\n".join("%d %d %d %d 0" % tuple(v + 1 for v in t) for t in tets)))


def ball_grid(n):
    """An n x n x n grid of [-1,1]^3 mapped radially onto the unit ball (the
    cube's faces onto the sphere): points and hexes (VTK order)."""
    points, hexes = grid(n, n, n, 2.0 / n, 2.0 / n, 2.0 / n)
    mapped = []
    for p in points:
        q = [x - 1.0 for x in p]
        r = math.sqrt(sum(x * x for x in q))
        s = max(abs(x) for x in q) / r if r > 0 else 0.0
        mapped.append(tuple(x * s for x in q))
    return mapped, hexes


def on_ball_grid_boundary(p, tpoints, m):
    """p if it is inside the unit sphere, else p moved along its ray onto the
    boundary of ball_grid(m) (points tpoints): onto the triangle, of the two
    the grid's quad splits into either way, that the ray meets."""
    if sum(x * x for x in p) < 1 - 1e-12:
        return p
    k = max(range(3), key=lambda i: abs(p[i]))
    uvw = [x / abs(p[k]) for x in p]  # on the cube's face: uvw[k] = +-1
    cell = [min(m - 1, int((x + 1) * m / 2)) for x in uvw]
    corners = []
    for a in (0, 1):
        for b in (0, 1):
            ijk = list(cell)
            ijk[k] = 0 if uvw[k] < 0 else m
            ijk[(k + 1) % 3] += a
            ijk[(k + 2) % 3] += b
            corners.append(tpoints[ijk[0] + (m + 1) * (ijk[1] + (m + 1) * ijk[2])])
    c00, c10, c01, c11 = corners
    for tri in ((c00, c10, c11), (c00, c11, c01), (c00, c10, c01), (c10, c11, c01)):
        # p * t on the triangle's plane, inside it
        nrm = hmq.cross(hmq.sub(tri[1], tri[0]), hmq.sub(tri[2], tri[0]))
        t = hmq.dot(nrm, tri[0]) / hmq.dot(nrm, p)
        q = tuple(t * x for x in p)
        if all(hmq.dot(hmq.cross(hmq.sub(tri[(i + 1) % 3], tri[i]), hmq.sub(q, tri[i])), nrm) >= -1e-15
               for i in range(3)):
            return q
    raise AssertionError("no facet on the ray of %s" % (p,))


class HexMeshQualityTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def path(self, name, text=None):
        p = os.path.join(self.tmp.name, name)
        if text is not None:
            with open(p, "w") as f:
                f.write(text)
        return p

    def ovm(self, points, hexes, extra_cells=(), shuffle=False):
        cells = [hex_loops(h) for h in hexes] + list(extra_cells)
        return self.path("hex.ovm", ovm_text(points, cells, shuffle))

    def report(self, points, hexes, tets_text=None, **kw):
        tets = self.path("tets.mesh", tets_text) if tets_text else None
        return hmq.evaluate(self.ovm(points, hexes, **kw), tets)[0]

    def run_main(self, *argv):
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = hmq.main(list(argv))
        return rc, out.getvalue(), err.getvalue()

    def assertError(self, argv, *needles):
        rc, out, err = self.run_main(*argv)
        self.assertEqual(rc, 1)
        self.assertEqual(out, "")
        self.assertEqual(len(err.strip().splitlines()), 1, err)
        for n in needles:
            self.assertIn(n, err)

    # --- scaled Jacobian and volume of single hexes

    def test_unit_cube_is_exactly_one(self):
        r = self.report(*grid(1, 1, 1))
        self.assertEqual((r["hexahedra"], r["other_cells"]), (1, 0))
        self.assertEqual(r["scaled_jacobian"]["min"], 1.0)
        self.assertEqual(r["scaled_jacobian"]["max"], 1.0)
        self.assertEqual(r["scaled_jacobian_corners_only"]["min"], 1.0)
        self.assertAlmostEqual(r["hex_volume"]["total"], 1.0, places=14)
        self.assertEqual(r["edge_length"]["count"], 12)

    def test_mirrored_cube_is_minus_one(self):
        points, hexes = grid(1, 1, 1)
        r = self.report([(-x, y, z) for x, y, z in points], hexes)
        self.assertEqual(r["scaled_jacobian"]["min"], -1.0)
        self.assertEqual(r["scaled_jacobian"]["count_le_0"], 1)
        self.assertAlmostEqual(r["hex_volume"]["total"], -1.0, places=14)
        self.assertEqual(r["hex_volume"]["negative_hexes"], 1)

    def test_sheared_hex(self):
        s = 0.5  # x += s z: every corner frame has det 1 and one edge sqrt(1+s^2)
        r = self.report([(x + s * z, y, z) for x, y, z in UNIT_CUBE], [list(range(8))])
        self.assertAlmostEqual(r["scaled_jacobian"]["min"], 1 / math.sqrt(1 + s * s), places=14)
        self.assertAlmostEqual(r["hex_volume"]["total"], 1.0, places=14)

    def test_distorted_hex(self):
        # corner 6 moved from (1,1,1) to (1.5,1.5,1.5): at corner 6 the edges
        # are -(.5,1.5,.5), -(1.5,.5,.5), -(.5,.5,1.5): det 2.5, lengths sqrt(2.75);
        # X = x + uvw (.5,.5,.5) gives det J = 1 + (vw+uw+uv)/2, volume 1 + 3/8
        P = list(UNIT_CUBE)
        P[6] = (1.5, 1.5, 1.5)
        sj, corners, degenerate = hmq.scaled_jacobians(P)
        self.assertAlmostEqual(sj, 2.5 / 2.75 ** 1.5, places=14)
        self.assertEqual(sj, corners)  # the centre frame (88 / 20.75^1.5) is better
        self.assertFalse(degenerate)
        self.assertAlmostEqual(hmq.hex_volume(P), 1.375, places=14)
        r = self.report(P, [list(range(8))])
        self.assertAlmostEqual(r["scaled_jacobian"]["min"], 2.5 / 2.75 ** 1.5, places=14)
        self.assertEqual(r["scaled_jacobian"]["count_lt_0_5"], 0)

    def test_centre_frame_counts(self):
        # a tangled hex (top edge 6-7 crossed) whose centre frame is worse than
        # every corner: principal axes (-1,0,0), (1,4,0), (1,0,4) give -16/17
        # (VTK's vtkMeshQuality agrees), the corners only -0.2
        P = list(UNIT_CUBE)
        P[6], P[7] = (-1, 1, 1), (3, 1, 1)
        sj, corners, _ = hmq.scaled_jacobians(P)
        self.assertAlmostEqual(sj, -16 / 17, places=14)
        self.assertAlmostEqual(corners, -0.2, places=14)

    def test_collapsed_edge_counts_zero(self):
        # a zero-length frame vector counts 0 (Verdict would return 1e30)
        P = list(UNIT_CUBE)
        P[6] = P[7]
        sj, _, degenerate = hmq.scaled_jacobians(P)
        self.assertEqual(sj, 0.0)
        self.assertTrue(degenerate)
        r = self.report(P, [list(range(8))])
        self.assertEqual((r["scaled_jacobian"]["degenerate"], r["scaled_jacobian"]["count_le_0"]), (1, 1))

    # --- blocks, coverage, edge statistics

    def test_block_volume_and_coverage(self):
        points, hexes = grid(2, 1, 1)
        r = self.report(points, hexes, BOX_MESH, shuffle=True)
        self.assertEqual(r["hexahedra"], 2)  # shared face: one cell uses the odd half-face
        self.assertAlmostEqual(r["hex_volume"]["total"], 2.0, places=14)
        self.assertEqual(r["tets"]["tetrahedra"], 12)
        self.assertEqual(r["tets"]["negative_tets"], 0)
        self.assertAlmostEqual(r["tets"]["volume"], 2.0, places=14)
        self.assertAlmostEqual(r["coverage"], 1.0, places=14)
        self.assertEqual(r["edge_length"]["count"], 20)
        # flat faces and right-angled creases: nothing cut, a ceiling of exactly 1
        c = r["coverage_ceiling"]
        self.assertEqual((c["integral_2H"], c["estimate"], c["non_manifold_edges"]), (0.0, 1.0, 0))
        self.assertEqual(c["feature_edges"], 16)  # the box's 12 edges, those along x in two
        self.assertEqual(c["boundary_quad_edges"], 20)
        # one hex of the two: half the box is covered
        r = self.report(points, hexes[:1], BOX_MESH)
        self.assertAlmostEqual(r["coverage"], 0.5, places=14)

    def test_coverage_ceiling_of_a_ridge_and_a_valley(self):
        # Two unit boxes whose top middle edge is raised (a convex ridge) or
        # lowered (a concave valley) by d: the only boundary edge turning by
        # less than 40 degrees, by 2 atan(d), over length 1.
        for d in (0.1, -0.1):
            points, hexes = grid(2, 1, 1)
            points = [(x, y, z + d if (x, z) == (1, 1) else z) for x, y, z in points]
            r = self.report(points, hexes, medit_tets(points, hexes))
            self.assertAlmostEqual(r["coverage"], 1.0, places=14)  # planar faces: hexes fill the tets
            c = r["coverage_ceiling"]
            self.assertAlmostEqual(c["integral_2H"], 2 * math.atan(d), places=14)
            l2 = (4 + 4 * (1 + d * d) + 6 + 4 + 2 * (1 + d) ** 2) / 20
            self.assertAlmostEqual(c["boundary_quad_edge_rms"] ** 2, l2, places=14)
            self.assertAlmostEqual(c["estimate"], 1 - l2 / 12 * 2 * math.atan(d) / (2 + d), places=14)
            self.assertLess(c["estimate"], 1) if d > 0 else self.assertGreater(c["estimate"], 1)
            # at 5 degrees the ridge is a crease that hexes follow
            r = hmq.evaluate(self.path("hex.ovm"), self.path("tets.mesh"), feature_angle_deg=5)[0]
            self.assertEqual(r["coverage_ceiling"]["estimate"], 1.0)

    def test_coverage_ceiling_predicts_a_ball(self):
        # The unit ball as an n x n x n grid mapped radially, its boundary
        # vertices moved along their rays onto the facets of a tet mesh of the
        # m x m x m one (anywhere on them, as HexEx's are): their bilinear
        # quads cut below the tets' boundary by what the ceiling says, to
        # within its second-order accuracy.
        for n, m in ((6, 13), (5, 12), (7, 16)):
            points, hexes = ball_grid(n)
            tpoints, thexes = ball_grid(m)
            points = [on_ball_grid_boundary(p, tpoints, m) for p in points]
            r = self.report(points, hexes, medit_tets(tpoints, thexes))
            c = r["coverage_ceiling"]
            self.assertEqual((c["feature_edges"], c["non_manifold_edges"]), (0, 0))
            self.assertAlmostEqual(c["integral_2H"], 8 * math.pi, delta=0.005 * 8 * math.pi)
            self.assertLess(r["coverage"], 0.98)  # the curvature costs hexes of this size 2 to 5%
            self.assertAlmostEqual(c["estimate"], r["coverage"], delta=0.005)
        # the ceiling at a given hex size: the same formula at that edge
        rc, out, err = self.run_main(self.path("hex.ovm"), "--tets", self.path("tets.mesh"), "--json",
                                     "--hex-size", "%.17g" % c["boundary_quad_edge_rms"])
        self.assertEqual((rc, err), (0, ""))
        at = json.loads(out)["coverage_ceiling"]["at_hex_size"]
        self.assertAlmostEqual(at["estimate"], c["estimate"], places=14)
        rc, out, err = self.run_main(self.path("hex.ovm"), "--tets", self.path("tets.mesh"), "--hex-size", "0.2")
        self.assertIn("coverage ceiling for boundary quads of edge 0.2 (--hex-size)", out)
        self.assertError([self.path("hex.ovm"), "--hex-size", "-1"], "--hex-size -1: not a positive length")
        self.assertError([self.path("hex.ovm"), "--feature-angle", "200"], "--feature-angle 200: not in [0, 180]")

    def test_anisotropic_edges_and_families(self):
        r = self.report(*grid(2, 3, 1, 0.2, 0.1, 0.4))
        a = r["edge_length_by_axis"]
        self.assertEqual((a["x"]["count"], a["y"]["count"], a["z"]["count"], a["unaligned"]),
                         (2 * 4 * 2, 3 * 3 * 2, 3 * 4, 0))
        for axis, h in (("x", 0.2), ("y", 0.1), ("z", 0.4)):
            self.assertAlmostEqual(a[axis]["mean"], h, places=14)
            self.assertAlmostEqual(a[axis]["median"], h, places=14)
        f = r["edge_families"]
        for name, h in (("shortest", 0.1), ("middle", 0.2), ("longest", 0.4)):
            self.assertAlmostEqual(f[name]["mean"], h, places=14)
        self.assertAlmostEqual(f["longest_over_shortest"]["max"], 4.0, places=12)

    def test_sizes_against_the_hex_size_asked_for(self):
        points, hexes = grid(2, 1, 1)
        tets = self.path("box.mesh", BOX_MESH)
        ovm = self.ovm(points, hexes)
        # unit cubes asked for: each hex is one, the box needs 2
        z = hmq.evaluate(ovm, tets, hex_size=1.0)[0]["size"]
        self.assertAlmostEqual(z["edge_ratio"]["median"], 1.0, places=14)
        self.assertEqual(z["within_25_percent"], 1.0)
        self.assertAlmostEqual(z["expected_hexes"], 2.0, places=14)
        self.assertAlmostEqual(z["hexes_over_expected"], 1.0, places=14)
        # edges of 0.5 asked for: hexes twice as long, an eighth of the count
        z = hmq.evaluate(ovm, tets, hex_size=0.5)[0]["size"]
        self.assertAlmostEqual(z["edge_ratio"]["min"], 2.0, places=14)
        self.assertAlmostEqual(z["edge_ratio"]["max"], 2.0, places=14)
        self.assertEqual(z["within_25_percent"], 0.0)
        self.assertAlmostEqual(z["hexes_over_expected"], 2 / 16, places=14)
        # the volume decides, not the shape: a 0.2 x 0.1 x 0.4 box is 0.2 cubed
        z = hmq.evaluate(self.ovm(*grid(2, 3, 1, 0.2, 0.1, 0.4)), hex_size=0.2)[0]["size"]
        self.assertAlmostEqual(z["edge_ratio"]["median"], 1.0, places=12)
        self.assertNotIn("expected_hexes", z)  # no tet mesh, no count
        # a hex of twice the volume next to one of half: 2^(1/3) and 2^(-1/3), 1.26 and 0.79
        points = [({0: 0.0, 1: 0.5, 2: 2.5}[x], y, z) for x, y, z in grid(2, 1, 1)[0]]
        z = hmq.evaluate(self.ovm(points, hexes), hex_size=1.0)[0]["size"]
        self.assertAlmostEqual(z["edge_ratio"]["min"], 0.5 ** (1 / 3), places=12)
        self.assertAlmostEqual(z["edge_ratio"]["max"], 2.0 ** (1 / 3), places=12)
        self.assertEqual(z["within_25_percent"], 0.0)
        rc, text, err = self.run_main(self.ovm(*grid(2, 1, 1)), "--tets", tets, "--hex-size", "0.5")
        self.assertEqual((rc, err), (0, ""))
        self.assertIn("cube root of hex volume / 0.5: min 2  median 2", text)
        self.assertIn("2 hexes for 16 expected", text)

    def test_rotated_edges_leave_the_axis_cones(self):
        t = math.radians(40)  # x and y edges 40 deg off their axes: counted for none
        points, hexes = grid(1, 1, 1)
        rot = [(math.cos(t) * x - math.sin(t) * y, math.sin(t) * x + math.cos(t) * y, z)
               for x, y, z in points]
        r = self.report(rot, hexes)
        a = r["edge_length_by_axis"]
        self.assertEqual((a["x"]["count"], a["y"]["count"], a["z"]["count"], a["unaligned"]),
                         (0, 0, 4, 8))
        self.assertAlmostEqual(r["scaled_jacobian"]["min"], 1.0, places=14)

    # --- command line, errors, VTU

    def test_cli_json_and_text(self):
        points, hexes = grid(2, 1, 1)
        ovm = self.ovm(points, hexes)
        tets = self.path("box.mesh", BOX_MESH)
        script = os.path.join(HERE, "hex_mesh_quality.py")
        out = subprocess.run([sys.executable, script, ovm, "--tets", tets, "--json"],
                             check=True, capture_output=True, text=True).stdout
        j = json.loads(out)
        self.assertEqual(j["hexahedra"], 2)
        self.assertAlmostEqual(j["coverage"], 1.0, places=12)
        rc, text, err = self.run_main(ovm, "--tets", tets)
        self.assertEqual((rc, err), (0, ""))
        self.assertIn("scaled Jacobian", text)
        self.assertIn("coverage", text)

    def test_non_hex_cell_is_reported_not_fatal(self):
        points, hexes = grid(1, 1, 1)
        points = points + [(0.5, 0.5, 2.0)]
        apex = len(points) - 1
        # a tet on the top face 4 5 6: half-face normals pointing into it
        tet = [[4, 5, 6], [4, apex, 5], [5, apex, 6], [6, apex, 4]]
        self.ovm(points, hexes, extra_cells=[tet])
        rc, out, err = self.run_main(self.path("hex.ovm"))
        self.assertEqual(rc, 0)
        self.assertIn("1 other cells", out)
        self.assertIn("not hexahedra", err)
        self.assertIn("hex.ovm", err)

    def test_errors(self):
        self.assertError([self.path("missing.ovm")], "missing.ovm", "No such file")
        self.assertError([self.path("a.ovm", "OFF\n3 1 0\n")], "a.ovm", "OVM ASCII")
        points, hexes = grid(1, 1, 1)
        text = ovm_text(points, [hex_loops(hexes[0])])
        self.assertError([self.path("b.ovm", text[:text.index("Polyhedra") + 12])],
                         "b.ovm", "unexpected end of file")
        bad_id = text.rstrip("\n").rsplit(" ", 1)[0] + " 99\n"  # only 12 half-faces
        self.assertError([self.path("c.ovm", bad_id)], "c.ovm", "half-face id")
        lines = text.split("\n")
        i = lines.index("Edges") + 2
        lines[i] = " ".join(reversed(lines[i].split()))  # breaks the loops of its faces
        self.assertError([self.path("d.ovm", "\n".join(lines))], "d.ovm", "closed loop")
        tet_only = ovm_text([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)],
                            [[[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]]])
        self.assertError([self.path("e.ovm", tet_only)], "e.ovm", "no hexahedral cells")
        good = self.path("good.ovm", text)
        unknown = "MeshVersionFormatted 2\nDimension 3\nVertices 0\nPrisms7 0\nEnd\n"
        self.assertError([good, "--tets", self.path("u.mesh", unknown)], "u.mesh:4", "Prisms7")
        bad_tet = BOX_MESH.replace("2 11 8 12 0", "2 11 8 13 0")
        self.assertError([good, "--tets", self.path("v.mesh", bad_tet)], "v.mesh:", "vertex number")
        truncated = BOX_MESH[:BOX_MESH.index("Tetrahedra") + 15]
        self.assertError([good, "--tets", self.path("w.mesh", truncated)], "w.mesh", "end of file")

    def test_vtu(self):
        points, hexes = grid(2, 1, 1)
        vtu = self.path("out.vtu")
        rc, _, _ = self.run_main(self.ovm(points, hexes, shuffle=True), "--vtu", vtu)
        self.assertEqual(rc, 0)
        piece = ET.parse(vtu).getroot().find("UnstructuredGrid/Piece")
        self.assertEqual((piece.get("NumberOfPoints"), piece.get("NumberOfCells")), ("12", "2"))
        arrays = {a.get("Name"): a.text.split() for a in piece.iter("DataArray")}
        self.assertEqual(arrays["types"], ["12", "12"])
        self.assertEqual(arrays["offsets"], ["8", "16"])
        xyz = [float(v) for v in arrays["Points"]]
        conn = [int(v) for v in arrays["connectivity"]]
        cubes = set()
        for c in range(2):
            # VTK order (any of the 24 rotations of the labels): p1-p0, p3-p0,
            # p4-p0 a right-handed frame, the other corners their sums
            P = [tuple(xyz[3 * v:3 * v + 3]) for v in conn[8 * c:8 * c + 8]]
            a, b, d = (hmq.sub(P[i], P[0]) for i in (1, 3, 4))
            self.assertEqual(hmq.det3(a, b, d), 1.0)
            for i, (ka, kb, kd) in enumerate(UNIT_CUBE):
                self.assertEqual(P[i], tuple(P[0][k] + ka * a[k] + kb * b[k] + kd * d[k] for k in range(3)))
            cubes.add(min(P))
        self.assertEqual(cubes, {(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)})
        self.assertEqual([float(v) for v in arrays["scaled_jacobian"]], [1.0, 1.0])


if __name__ == "__main__":
    unittest.main()
