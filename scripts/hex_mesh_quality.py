#!/usr/bin/env python3
"""Quality report for a hexahedral mesh written by HexEx (OpenVolumeMesh ASCII).

Usage:
  python3 scripts/hex_mesh_quality.py HEX.ovm [--tets TET.mesh] [--hex-size L] [--json] [--vtu OUT.vtu]

Python 3 standard library only.  Reports the hex count (and any other cells),
the scaled Jacobian, the total hex volume, with --tets the volume of the input
tet mesh (Medit .mesh) and the coverage = hex volume / tet volume, edge lengths
(overall and per world axis) and the per-hex edge families.  With --hex-size L
(the hex edge asked for, as `generate --hex-size L` asks for it with the
identity metric): the hexes' sizes, per hex the cube root of its volume over
L (median, range, the fraction within 0.8-1.25), and with --tets the hexes
that hexes of edge L would need to fill the tet mesh's volume, against the
hexes made: a map that coarsens shows there even where the coverage is high.  --json prints the
same as a JSON object; --vtu also writes the hexes as a VTK XML unstructured
grid (VTK_HEXAHEDRON cells, cell data `scaled_jacobian`) for ParaView.
Errors (missing or malformed file) print one line naming the file, exit code 1;
cells that are not hexahedra are counted and reported but are not an error.

OVM ASCII (what OpenVolumeMesh's FileManager writes; '#' lines are comments):
  OVM ASCII
  Vertices n   then n lines "x y z"
  Edges n      then n lines "from to"              (vertex ids)
  Faces n      then n lines "k he_1 .. he_k"       (half-edge ids)
  Polyhedra n  then n lines "k hf_1 .. hf_k"       (half-face ids)
  [property blocks: ignored]
Half-edge 2e runs from->to along edge e, 2e+1 backwards.  Half-face 2f is face
f as listed, 2f+1 the opposite one (opposite half-edges in reverse order).
OVM orients the half-faces of a cell so that their normals (right-hand rule)
point INTO the cell; HexEx adds each hex through OVM's add_cell(8 vertices),
which keeps that convention.

Hex reconstruction.  A cell counts as a hexahedron if its 6 half-faces are
quads forming a closed, consistently oriented surface (each of its 12 edges
used once in each direction, 8 vertices of valence 3).  Its vertices are put
in VTK/Verdict order: 0,1,2,3 = the loop of the first half-face (inward normal,
i.e. counter-clockwise seen from inside, as VTK's bottom face), 4+i = the
neighbour of vertex i off that face.

Scaled Jacobian: the headline value is Verdict's hex_scaled_jacobian (what VTK's
vtkMeshQuality and ParaView report): the minimum over 9 frames of
det(a,b,c)/(|a||b||c|), the 8 corner frames (corner 0: p1-p0, p3-p0, p4-p0,
...) and the centre frame of the three principal axes (sum of the 4 parallel
edges each).  The corners-only minimum is listed too.  Verdict returns a huge
positive value when a frame has a zero-length vector; here such a frame counts
0, so a collapsed hex is reported as bad (and as degenerate).

Volume: exact volume of the trilinear hex (det J integrated with 2x2x2 Gauss
points, exact since det J has degree <= 2 in each variable), signed.  Coverage
uses the signed sum, so a globally inverted mesh shows up as negative.

Coverage ceiling (with --tets): the coverage that hexes with this boundary
edge length can reach at best on the curved parts of the boundary.  A
boundary quad of side l has its corners on the tet mesh's boundary T and is
bilinear in between.  Write T = S - g, with S the smooth surface that T
facets (mean curvature H) and g >= 0 the facets' gap below it, 0 at the
tet vertices.  Below T the quad cuts (S - I(S)) - (g - I(g)) on average, I
the bilinear interpolation of the quad's corners: the first term is
2H l^2 / 12 whatever the quad's orientation (2H = k1 + k2; the mean of
u (l - u) k / 2 over the square), and the second averages to 0 when the
corners fall anywhere on the facets, as HexEx's do (at tet vertices only it
would be the facets' own gap, 2H lt^2 / 16 for facets of mean squared edge
lt^2).  So the hexes miss l^2 / 12 times the integral of 2H, which on the
faceted boundary is sum |e| theta_e over its edges (theta_e: the turning
angle between the two outward normals, negative where concave, where the
quads bulge out); edges turning by more than --feature-angle (default 40,
generate's) are left out, since hex edges follow those creases (unlike
generate, the script keeps lone kinks as creases).  l^2 is the mean squared
length of the edges of the hex mesh's boundary quads (with --hex-size L,
the ceiling for quads of edge L is given too: what hexes of the size asked
for could reach).  ceiling = max(0, 1 - l^2 / 12 * sum |e| theta_e / tet
volume).  A second-order estimate: on unit balls (radially mapped grids of
5 to 7 hexes per side in tet meshes about twice as fine) it lies 0.0025 to
0.0046 above the coverage that hexes with their vertices anywhere on the
tets' facets reach, 0.008 above with 4 hexes per side, and 0.005 below when
every quad corner is a tet vertex.
"""

import argparse
import json
import math
import statistics
import sys

AXIS_ANGLE_DEG = 30.0  # an edge "is along" a world axis within this angle
# The 8 corner frames of Verdict's hex_scaled_jacobian: (corner, a, b, c).
CORNERS = ((0, 1, 3, 4), (1, 2, 0, 5), (2, 3, 1, 6), (3, 0, 2, 7),
           (4, 7, 5, 0), (5, 4, 6, 1), (6, 5, 7, 2), (7, 6, 4, 3))
# The 3 families of 4 parallel edges, all oriented alike (VTK order).
FAMILIES = (((0, 1), (3, 2), (4, 5), (7, 6)),
            ((0, 3), (1, 2), (4, 7), (5, 6)),
            ((0, 4), (1, 5), (2, 6), (3, 7)))
HEX_FACES = ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4),
             (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
_G = 0.5 / math.sqrt(3.0)
GAUSS = (0.5 - _G, 0.5 + _G)
VTK_HEXAHEDRON = 12


class InputError(Exception):
    """A problem with an input file; the message starts with the file name."""


# ------------------------------------------------------------------ reading

class Tokens:
    """Whitespace tokens of a text file ('#' starts a comment), with line
    numbers for error messages."""

    def __init__(self, path):
        self.path, self.toks, self.lines, self.i = path, [], [], 0
        with open(path, encoding="utf-8", errors="replace") as f:
            for n, line in enumerate(f, 1):
                words = line.split("#", 1)[0].split()
                self.toks.extend(words)
                self.lines.extend([n] * len(words))

    def error(self, msg):
        if self.i < len(self.toks):
            return InputError("%s:%d: %s" % (self.path, self.lines[self.i], msg))
        return InputError("%s: %s" % (self.path, msg))

    def at_end(self):
        return self.i >= len(self.toks)

    def word(self, what):
        if self.at_end():
            raise self.error("unexpected end of file, expected %s" % what)
        self.i += 1
        return self.toks[self.i - 1]

    def int(self, what, lo=0, hi=None):
        t = self.word(what)
        try:
            v = int(t)
        except ValueError:
            v = None
        if v is None or v < lo or (hi is not None and v >= hi):
            self.i -= 1
            rng = "" if hi is None else " in [%d, %d)" % (lo, hi)
            raise self.error("expected %s%s, got '%s'" % (what, rng, t))
        return v

    def float(self, what):
        t = self.word(what)
        try:
            return float(t)
        except ValueError:
            self.i -= 1
            raise self.error("expected %s (a number), got '%s'" % (what, t)) from None

    def point(self, dim=3):
        p = [self.float("a coordinate") for _ in range(dim)]
        return tuple(p + [0.0] * (3 - dim))


def read_ovm(path):
    """Return (points, cells): cells are lists of vertex loops, one loop per
    half-face in the half-face's orientation."""
    t = Tokens(path)
    if t.at_end() or t.toks[0].upper() != "OVM":
        raise InputError("%s: not an OpenVolumeMesh file (no 'OVM ASCII' header)" % path)
    t.i = 1
    if t.word("ASCII").upper() != "ASCII":
        raise t.error("only 'OVM ASCII' is supported")

    def section(name):
        if t.word("section '%s'" % name).lower() != name.lower():
            t.i -= 1
            raise t.error("expected section '%s', got '%s'" % (name, t.toks[t.i]))
        return t.int("the number of %s" % name.lower())

    points = [t.point() for _ in range(section("Vertices"))]
    nv = len(points)
    edges = [(t.int("a vertex id", 0, nv), t.int("a vertex id", 0, nv))
             for _ in range(section("Edges"))]
    nhe = 2 * len(edges)
    loops = []  # vertex loop of each face as listed (= its even half-face)
    for f in range(section("Faces")):
        hes = [t.int("a half-edge id", 0, nhe) for _ in range(t.int("a face valence", 1))]
        ends = [edges[h >> 1][::-1] if h & 1 else edges[h >> 1] for h in hes]
        if any(ends[j][1] != ends[(j + 1) % len(ends)][0] for j in range(len(ends))):
            raise InputError("%s: face %d: its half-edges do not form a closed loop" % (path, f))
        loops.append([a for a, _ in ends])
    nhf = 2 * len(loops)
    cells = []
    for _ in range(section("Polyhedra")):
        hfs = [t.int("a half-face id", 0, nhf) for _ in range(t.int("a cell valence", 1))]
        # the opposite half-face of loop (v0 v1 .. vk) is (v0 vk .. v1)
        cells.append([[loops[h >> 1][0]] + loops[h >> 1][:0:-1] if h & 1 else loops[h >> 1]
                      for h in hfs])
    return points, cells


# Entries of Medit sections we skip: tokens per entry (None: per dimension).
MEDIT_SKIP = {"edges": 3, "triangles": 4, "quadrilaterals": 5, "hexahedra": 9,
              "prisms": 7, "pyramids": 6, "corners": 1, "ridges": 1,
              "requiredvertices": 1, "requirededges": 1, "requiredtriangles": 1,
              "requiredquadrilaterals": 1, "normalatvertices": 2,
              "normalattrianglevertices": 3, "normalatquadrilateralvertices": 3,
              "tangentatedges": 3, "tangentatvertices": 2,
              "normals": None, "tangents": None}


def read_medit_tets(path):
    """Vertices and Tetrahedra (0-based) of a Medit .mesh; the sections in
    MEDIT_SKIP are skipped, any other one is an error."""
    t = Tokens(path)
    dim, points, tets = 3, [], []
    while not t.at_end():
        key = t.word("a keyword").lower()
        if key == "end":
            break
        if key == "meshversionformatted":
            t.int("the version", 1)
        elif key == "dimension":
            dim = t.int("the dimension", 2, 4)
        elif key == "vertices":
            for _ in range(t.int("the number of vertices")):
                points.append(t.point(dim))
                t.int("a reference", -2 ** 31)
        elif key == "tetrahedra":
            for _ in range(t.int("the number of tetrahedra")):
                tets.append(tuple(t.int("a vertex number", 1, len(points) + 1) - 1
                                  for _ in range(4)))
                t.int("a reference", -2 ** 31)
        elif key in MEDIT_SKIP:
            n = t.int("the number of entries") * (MEDIT_SKIP[key] or dim)
            if t.i + n > len(t.toks):
                raise t.error("section '%s' is truncated" % key)
            t.i += n
        else:
            t.i -= 1
            raise t.error("unknown Medit section '%s'" % t.toks[t.i])
    return points, tets


# ----------------------------------------------------------------- geometry

def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def det3(a, b, c):
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def norm(a):
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def corner_sum(P, plus, minus):
    """sum of P[i] for i in plus minus sum of P[i] for i in minus."""
    return tuple(sum(P[i][k] for i in plus) - sum(P[i][k] for i in minus) for k in range(3))


def lincomb(*terms):
    """sum of c * p over (c, p) pairs."""
    return tuple(sum(c * p[k] for c, p in terms) for k in range(3))


def cell_to_hex(loops):
    """8 vertex ids in VTK order, or (None, reason) if the cell is no hex."""
    if len(loops) != 6 or any(len(l) != 4 for l in loops):
        return None, "not 6 quadrilaterals"
    directed = {(l[j], l[(j + 1) % 4]) for l in loops for j in range(4)}
    if len(directed) != 24 or any((b, a) not in directed for a, b in directed):
        return None, "faces not closed or not consistently oriented"
    nbr = {}
    for a, b in directed:
        nbr.setdefault(a, set()).add(b)
    if len(nbr) != 8 or any(len(s) != 3 for s in nbr.values()):
        return None, "not 8 vertices of valence 3"
    bottom = loops[0]
    top = [(nbr[v] - set(bottom)) for v in bottom]
    if any(len(s) != 1 for s in top):
        return None, "not a hexahedron"
    h = list(bottom) + [s.pop() for s in top]
    if {frozenset(l) for l in loops} != {frozenset(h[i] for i in f) for f in HEX_FACES}:
        return None, "not a hexahedron"
    return h, None


def scaled_jacobians(P):
    """(Verdict value = min over corners and centre, corners-only min,
    degenerate?) for the 8 points P in VTK order."""
    def frame(a, b, c):
        l = norm(a) * norm(b) * norm(c)
        return (det3(a, b, c) / l, False) if l > 0 else (0.0, True)
    corner = [frame(sub(P[a], P[c]), sub(P[b], P[c]), sub(P[d], P[c])) for c, a, b, d in CORNERS]
    centre = frame(corner_sum(P, (1, 2, 5, 6), (0, 3, 4, 7)), corner_sum(P, (2, 3, 6, 7), (0, 1, 4, 5)),
                   corner_sum(P, (4, 5, 6, 7), (0, 1, 2, 3)))
    corners_min = min(v for v, _ in corner)
    return (min(corners_min, centre[0]), corners_min,
            centre[1] or any(d for _, d in corner))


def hex_volume(P):
    """Signed volume of the trilinear hex X = a + bu + cv + dw + e uv + f vw
    + g uw + h uvw over [0,1]^3 (P in VTK order)."""
    b, c, d = sub(P[1], P[0]), sub(P[3], P[0]), sub(P[4], P[0])
    e, f = corner_sum(P, (2, 0), (1, 3)), corner_sum(P, (7, 0), (3, 4))
    g, h = corner_sum(P, (5, 0), (1, 4)), corner_sum(P, (6, 1, 3, 4), (2, 5, 7, 0))
    vol = 0.0
    for u in GAUSS:
        for v in GAUSS:
            for w in GAUSS:
                xu = lincomb((1, b), (v, e), (w, g), (v * w, h))
                xv = lincomb((1, c), (u, e), (w, f), (u * w, h))
                xw = lincomb((1, d), (v, f), (u, g), (u * v, h))
                vol += det3(xu, xv, xw)
    return vol / 8.0


def nearest_axis(vec, cos_max):
    """0, 1, 2 for x, y, z if vec is within the angle of that axis, else None."""
    n = norm(vec)
    if n == 0:
        return None
    k = max(range(3), key=lambda j: abs(vec[j]))
    return k if abs(vec[k]) >= cos_max * n else None


# --------------------------------------------------------------- evaluation

def summary(vals, keys=("min", "median", "mean", "max")):
    s = {"count": len(vals)}
    if vals:
        s.update({"min": min(vals), "max": max(vals), "mean": sum(vals) / len(vals),
                  "median": statistics.median(vals)})
    return {k: v for k, v in s.items() if k == "count" or k in keys}


def boundary_turning(points, tets, feature_angle_deg):
    """Over the boundary edges of a tet mesh turning by at most
    feature_angle_deg: sum |e| theta_e (theta_e signed, positive where the
    boundary is convex), the integral of twice the mean curvature."""
    faces = {}
    for t in tets:
        for k in range(4):
            f = tuple(sorted(t[:k] + t[k + 1:]))
            faces[f] = None if f in faces else t[k]   # None: shared by two tets
    normals, by_edge = [], {}
    for f, opposite in faces.items():
        if opposite is None:
            continue
        a, b, c = (points[v] for v in f)
        n = cross(sub(b, a), sub(c, a))
        if dot(n, sub(points[opposite], a)) > 0:  # outward: away from the tet
            n = tuple(-x for x in n)
        length = norm(n)
        if length == 0:
            continue
        normals.append((tuple(x / length for x in n), f))
        for e in ((f[0], f[1]), (f[0], f[2]), (f[1], f[2])):
            by_edge.setdefault(e, []).append(len(normals) - 1)
    total, smooth, features, non_manifold = 0.0, 0, 0, 0
    for (u, v), ids in by_edge.items():
        if len(ids) != 2:
            non_manifold += 1
            continue
        (n1, f1), (n2, f2) = normals[ids[0]], normals[ids[1]]
        theta = math.atan2(norm(cross(n1, n2)), dot(n1, n2))  # exact 0 on flat parts, unlike acos
        if theta > math.radians(feature_angle_deg):
            features += 1
            continue
        w = next(x for x in f2 if x != u and x != v)  # convex: f2 bends away from n1
        if dot(n1, sub(points[w], points[u])) > 0:
            theta = -theta
        total += norm(sub(points[v], points[u])) * theta
        smooth += 1
    return {"integral_2H": total, "smooth_edges": smooth, "feature_edges": features,
            "non_manifold_edges": non_manifold}


def boundary_quad_edges(hexes):
    """The edges (vertex pairs) of the quads on the boundary of a hex mesh."""
    count = {}
    for h in hexes:
        for f in HEX_FACES:
            key = frozenset(h[i] for i in f)
            count[key] = count.get(key, 0) + 1
    edges = set()
    for h in hexes:
        for f in HEX_FACES:
            if count[frozenset(h[i] for i in f)] == 1:
                for i in range(4):
                    a, b = h[f[i]], h[f[(i + 1) % 4]]
                    edges.add((min(a, b), max(a, b)))
    return edges


def coverage_ceiling(l2, turning, tet_volume):
    """The coverage ceiling for boundary quads of mean squared edge l2 (see the top)."""
    if tet_volume <= 0:
        return None
    return max(0.0, 1 - l2 / 12 * turning["integral_2H"] / tet_volume)


def size_report(vols, hex_size, tet_volume=None):
    """The hexes' sizes against the edge L asked for (--hex-size): per hex
    the cube root of its volume over L (1: a hex of the volume asked for,
    whatever its shape; the edge families give the shape), and with the tet
    mesh's volume the hexes that hexes of edge L would need to fill it."""
    ratios = [math.copysign(abs(v) ** (1.0 / 3.0), v) / hex_size for v in vols]
    r = {"hex_size": hex_size, "edge_ratio": summary(ratios),
         "within_25_percent": sum(0.8 <= x <= 1.25 for x in ratios) / len(ratios)}
    if tet_volume is not None:
        r["expected_hexes"] = tet_volume / hex_size ** 3
        r["hexes_over_expected"] = len(vols) / r["expected_hexes"] if tet_volume > 0 else None
    return r


def evaluate(hex_path, tet_path=None, feature_angle_deg=40.0, hex_size=None):
    """The report as a dict, plus the hexes (VTK order) and their scaled Jacobians."""
    points, cells = read_ovm(hex_path)
    hexes, other = [], {}
    for loops in cells:
        h, why = cell_to_hex(loops)
        if h is None:
            other[why] = other.get(why, 0) + 1
        else:
            hexes.append(h)
    if not hexes:
        raise InputError("%s: no hexahedral cells (%d cells)" % (hex_path, len(cells)))
    sjs, corner_sjs, vols, fams = [], [], [], [[], [], []]
    ndegenerate, edges = 0, set()
    for h in hexes:
        P = [points[v] for v in h]
        sj, sjc, degenerate = scaled_jacobians(P)
        sjs.append(sj)
        corner_sjs.append(sjc)
        ndegenerate += degenerate
        vols.append(hex_volume(P))
        lengths = sorted(sum(norm(sub(P[b], P[a])) for a, b in fam) / 4 for fam in FAMILIES)
        for k in range(3):
            fams[k].append(lengths[k])
        edges.update((min(h[a], h[b]), max(h[a], h[b])) for fam in FAMILIES for a, b in fam)

    r = {"hex_file": hex_path, "vertices": len(points), "cells": len(cells),
         "hexahedra": len(hexes), "other_cells": len(cells) - len(hexes),
         "other_cells_by_reason": other}
    r["scaled_jacobian"] = dict(
        summary(sjs), definition="Verdict hex_scaled_jacobian: min over 8 corners and centre",
        count_le_0=sum(s <= 0 for s in sjs), count_lt_0_2=sum(s < 0.2 for s in sjs),
        count_lt_0_5=sum(s < 0.5 for s in sjs), degenerate=ndegenerate)
    r["scaled_jacobian_corners_only"] = dict(summary(corner_sjs, ("min", "median", "mean")),
                                             count_le_0=sum(s <= 0 for s in corner_sjs))
    r["hex_volume"] = {"total": sum(vols), "negative_hexes": sum(v < 0 for v in vols)}
    if tet_path:
        tp, tets = read_medit_tets(tet_path)
        dets = [det3(sub(tp[b], tp[a]), sub(tp[c], tp[a]), sub(tp[d], tp[a])) for a, b, c, d in tets]
        tv = sum(abs(x) for x in dets) / 6.0
        r["tets"] = {"file": tet_path, "tetrahedra": len(tets), "volume": tv,
                     "negative_tets": sum(x < 0 for x in dets)}
        r["coverage"] = r["hex_volume"]["total"] / tv if tv > 0 else None
        turning = boundary_turning(tp, tets, feature_angle_deg)
        quad_edges = boundary_quad_edges(hexes)
        l2 = (sum(norm(sub(points[b], points[a])) ** 2 for a, b in quad_edges) / len(quad_edges)
              if quad_edges else 0.0)
        r["coverage_ceiling"] = dict(
            turning, feature_angle_deg=feature_angle_deg, boundary_quad_edges=len(quad_edges),
            boundary_quad_edge_rms=math.sqrt(l2),
            estimate=coverage_ceiling(l2, turning, tv))
        if hex_size is not None:
            r["coverage_ceiling"]["at_hex_size"] = {
                "hex_size": hex_size, "estimate": coverage_ceiling(hex_size ** 2, turning, tv)}

    if hex_size is not None:
        r["size"] = size_report(vols, hex_size, r["tets"]["volume"] if tet_path else None)

    cos_max = math.cos(math.radians(AXIS_ANGLE_DEG))
    lengths, by_axis = [], [[], [], []]
    for a, b in edges:
        vec = sub(points[b], points[a])
        lengths.append(norm(vec))
        k = nearest_axis(vec, cos_max)
        if k is not None:
            by_axis[k].append(lengths[-1])
    r["edge_length"] = summary(lengths)
    r["edge_length_by_axis"] = {"max_angle_deg": AXIS_ANGLE_DEG,
                                "unaligned": len(lengths) - sum(map(len, by_axis))}
    for k, name in enumerate("xyz"):
        r["edge_length_by_axis"][name] = summary(by_axis[k], ("mean", "median"))
    r["edge_families"] = {name: summary(fams[k], ("mean", "median", "min", "max"))
                          for k, name in enumerate(("shortest", "middle", "longest"))}
    r["edge_families"]["longest_over_shortest"] = summary(
        [l / s for s, l in zip(fams[0], fams[2]) if s > 0], ("mean", "median", "max"))
    return r, hexes, points, sjs


def write_vtu(path, points, hexes, sjs):
    """VTK XML UnstructuredGrid, ASCII, hexes as VTK_HEXAHEDRON (VTK order)."""
    def array(name, typ, values, ncomp=1):
        comp = ' NumberOfComponents="%d"' % ncomp if ncomp > 1 else ""
        return ('<DataArray type="%s" Name="%s"%s format="ascii">\n%s\n</DataArray>\n'
                % (typ, name, comp, "\n".join(values)))
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" '
                'byte_order="LittleEndian">\n<UnstructuredGrid>\n'
                '<Piece NumberOfPoints="%d" NumberOfCells="%d">\n<Points>\n'
                % (len(points), len(hexes)))
        f.write(array("Points", "Float64", ("%.17g %.17g %.17g" % p for p in points), 3))
        f.write("</Points>\n<Cells>\n")
        f.write(array("connectivity", "Int64", (" ".join(map(str, h)) for h in hexes)))
        f.write(array("offsets", "Int64", (str(8 * (i + 1)) for i in range(len(hexes)))))
        f.write(array("types", "UInt8", (str(VTK_HEXAHEDRON) for _ in hexes)))
        f.write('</Cells>\n<CellData Scalars="scaled_jacobian">\n')
        f.write(array("scaled_jacobian", "Float64", ("%.9g" % s for s in sjs)))
        f.write("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")


# ------------------------------------------------------------------- output

def g(x):
    return "-" if x is None else "%.6g" % x


def print_text(r, out):
    w = out.write
    w("hex mesh %s: %d vertices, %d cells: %d hexahedra, %d other cells%s\n" % (
        r["hex_file"], r["vertices"], r["cells"], r["hexahedra"], r["other_cells"],
        "".join(" (%d: %s)" % (n, why) for why, n in sorted(r["other_cells_by_reason"].items()))))
    s, c = r["scaled_jacobian"], r["scaled_jacobian_corners_only"]
    w("scaled Jacobian (%s)\n" % s["definition"])
    w("  min %s  median %s  mean %s  max %s\n" % (g(s["min"]), g(s["median"]), g(s["mean"]), g(s["max"])))
    w("  hexes with SJ <= 0: %d   < 0.2: %d   < 0.5: %d   degenerate: %d\n" % (
        s["count_le_0"], s["count_lt_0_2"], s["count_lt_0_5"], s["degenerate"]))
    w("  corners only: min %s  median %s  mean %s  <= 0: %d\n" % (
        g(c["min"]), g(c["median"]), g(c["mean"]), c["count_le_0"]))
    w("hex volume %s  (hexes with negative volume: %d)\n" % (
        g(r["hex_volume"]["total"]), r["hex_volume"]["negative_hexes"]))
    if "tets" in r:
        t = r["tets"]
        w("tet mesh %s: %d tetrahedra, volume %s  (negatively oriented: %d)\n" % (
            t["file"], t["tetrahedra"], g(t["volume"]), t["negative_tets"]))
        w("coverage (hex volume / tet volume) %s\n" % g(r["coverage"]))
        c = r["coverage_ceiling"]
        w("coverage ceiling from the boundary's curvature %s  (boundary quad edges: %d, rms length %s;\n"
          "  tet boundary: integral of 2H %s over %d edges, %d edges over %g deg left out, %d non-manifold)\n" % (
              g(c["estimate"]), c["boundary_quad_edges"], g(c["boundary_quad_edge_rms"]), g(c["integral_2H"]),
              c["smooth_edges"], c["feature_edges"], c["feature_angle_deg"], c["non_manifold_edges"]))
        if "at_hex_size" in c:
            w("coverage ceiling for boundary quads of edge %s (--hex-size) %s\n" % (
                g(c["at_hex_size"]["hex_size"]), g(c["at_hex_size"]["estimate"])))
    if "size" in r:
        z = r["size"]
        w("size against --hex-size %s: cube root of hex volume / %s: min %s  median %s  mean %s  max %s;\n"
          "  %s of the hexes within 0.8-1.25%s\n" % (
              g(z["hex_size"]), g(z["hex_size"]), g(z["edge_ratio"]["min"]), g(z["edge_ratio"]["median"]),
              g(z["edge_ratio"]["mean"]), g(z["edge_ratio"]["max"]), g(z["within_25_percent"]),
              "; %d hexes for %s expected (tet volume / hex size^3): %s of them" % (
                  r["hexahedra"], g(z["expected_hexes"]), g(z["hexes_over_expected"]))
              if "expected_hexes" in z else ""))
    e, a = r["edge_length"], r["edge_length_by_axis"]
    w("edge length (%d edges): mean %s  median %s  min %s  max %s\n" % (
        e["count"], g(e["mean"]), g(e["median"]), g(e["min"]), g(e["max"])))
    for name in "xyz":
        d = a[name]
        w("  along %s (within %g deg): %5d edges  mean %s  median %s\n" % (
            name, a["max_angle_deg"], d["count"], g(d.get("mean")), g(d.get("median"))))
    w("  along no axis: %d edges\n" % a["unaligned"])
    w("per-hex edge families (mean length of a hex's 4 parallel edges):\n")
    for name in ("shortest", "middle", "longest"):
        d = r["edge_families"][name]
        w("  %-8s mean %s  median %s  min %s  max %s\n" % (
            name, g(d["mean"]), g(d["median"]), g(d["min"]), g(d["max"])))
    d = r["edge_families"]["longest_over_shortest"]
    w("  longest/shortest  mean %s  median %s  max %s\n" % (g(d["mean"]), g(d["median"]), g(d["max"])))


def main(argv=None):
    ap = argparse.ArgumentParser(description="Quality report for a HexEx hex mesh (OVM ASCII).")
    ap.add_argument("hexmesh", metavar="HEX.ovm", help="hex mesh in OpenVolumeMesh ASCII format")
    ap.add_argument("--tets", metavar="TET.mesh", help="input tet mesh (Medit) for the coverage")
    ap.add_argument("--feature-angle", metavar="DEG", type=float, default=40.0,
                    help="for the coverage ceiling: boundary edges turning by more than this are creases "
                         "that hexes follow (default 40, generate's)")
    ap.add_argument("--hex-size", metavar="L", type=float,
                    help="the hex edge asked for (a constant isotropic metric I / L^2): also give the hexes' "
                         "sizes against it and the coverage ceiling for boundary quads of edge L")
    ap.add_argument("--json", action="store_true", help="print a JSON object instead of text")
    ap.add_argument("--vtu", metavar="OUT.vtu", help="also write the hexes as VTK XML with scaled_jacobian")
    args = ap.parse_args(argv)
    try:
        if not 0 <= args.feature_angle <= 180:
            raise InputError("--feature-angle %g: not in [0, 180]" % args.feature_angle)
        if args.hex_size is not None and not (args.hex_size > 0 and math.isfinite(args.hex_size)):
            raise InputError("--hex-size %g: not a positive length" % args.hex_size)
        r, hexes, points, sjs = evaluate(args.hexmesh, args.tets, args.feature_angle, args.hex_size)
        if args.vtu:
            write_vtu(args.vtu, points, hexes, sjs)
    except InputError as err:
        sys.stderr.write("hex_mesh_quality: error: %s\n" % err)
        return 1
    except OSError as err:
        sys.stderr.write("hex_mesh_quality: error: %s: %s\n" % (err.filename, err.strerror))
        return 1
    if r["other_cells"]:
        sys.stderr.write("hex_mesh_quality: warning: %s: %d cells are not hexahedra (not evaluated)\n"
                         % (args.hexmesh, r["other_cells"]))
    if args.json:
        json.dump(r, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        print_text(r, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
