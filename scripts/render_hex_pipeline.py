#!/usr/bin/env python3
"""Render pictures of the hex-meshing pipeline for the user manual (VTK).

Usage:
  python3 scripts/render_hex_pipeline.py OUTDIR_OF_GENERATE HEX.vtu IMAGE_PREFIX

OUTDIR_OF_GENERATE is the output folder of `metric-frames generate`; it must
hold frames.vtu (tets with cell data hex_edge_1..3) and singularities.vtu
(VTK_LINE cells with cell data `type`, `meshable`; point data `node`).
HEX.vtu is the hex mesh with cell data `scaled_jacobian`, as written by
  python3 scripts/hex_mesh_quality.py HEX.ovm --vtu HEX.vtu
Writes three 1200x900 PNGs:
  IMAGE_PREFIX_frames.png         the three hex edge vectors of each tet cut by
                                  the horizontal mid plane, in the translucent domain
  IMAGE_PREFIX_singularities.png  the singular curves as tubes coloured by type
                                  (valence 3, valence 5, non-meshable)
  IMAGE_PREFIX_hexes.png          the hex mesh with its front part cut away by a
                                  plane, coloured by scaled Jacobian

Requirements (Debian bookworm):
  apt-get install python3-vtk9 xvfb xauth libgl1-mesa-dri
python3-vtk9 is VTK 9.1 for Debian's /usr/bin/python3.  Debian builds VTK with
X11/GLX rendering only (no OSMesa or EGL), so even off-screen rendering needs
an X server: without DISPLAY the script re-runs itself under `xvfb-run`
(package xvfb; xauth for xvfb-run, Mesa's software OpenGL from libgl1-mesa-dri).
If `import vtk` fails (e.g. a pyenv or venv python3), it re-runs itself with
/usr/bin/python3.
"""

import math
import os
import shutil
import statistics
import sys

SIZE = (1200, 900)  # of the PNGs
SS = 2              # rendered SS times larger, then shrunk: anti-aliasing (MSAA
                    # breaks depth peeling, FXAA breaks thin lines); pixel sizes * SS
LATTICE = 2.0       # frames image: one cross every LATTICE hex edges ...
GLYPH_SCALE = 1.3   # ... its bars GLYPH_SCALE times the hex edge vectors
_GUARD = "RENDER_HEX_PIPELINE_REEXEC"


def _prepare_environment():
    """Re-run once under /usr/bin/python3 (if this python has no VTK) and/or
    xvfb-run (if there is no X display); exit with a hint if that cannot help."""
    import importlib.util
    has_vtk = importlib.util.find_spec("vtkmodules") is not None
    if not os.environ.get(_GUARD):
        cmd = [sys.executable]
        if not has_vtk and os.path.exists("/usr/bin/python3") \
                and os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
            cmd = ["/usr/bin/python3"]
        if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
            cmd = ["xvfb-run", "-a", "-s", "-screen 0 2560x2048x24"] + cmd
        if cmd != [sys.executable]:
            os.environ[_GUARD] = "1"
            os.execvp(cmd[0], cmd + [os.path.abspath(__file__)] + sys.argv[1:])
    if not has_vtk:
        sys.exit("render_hex_pipeline: error: no VTK Python module "
                 "(apt-get install python3-vtk9; it serves /usr/bin/python3)")
    if not os.environ.get("DISPLAY"):
        sys.exit("render_hex_pipeline: error: no X display and no xvfb-run "
                 "(apt-get install xvfb xauth)")


if __name__ == "__main__":
    _prepare_environment()
import vtk  # noqa: E402  (Debian: python3-vtk9)

TEXT = (0.1, 0.1, 0.1)
EDGE_COLOURS = ((0.84, 0.19, 0.15), (0.17, 0.63, 0.17), (0.16, 0.35, 0.80))  # hex_edge_1..3
SINGULAR_KINDS = (("valence 3  (index +1/4)", (0.13, 0.40, 0.85)),
                  ("valence 5  (index -1/4)", (0.90, 0.33, 0.05)),
                  ("not meshable", (0.55, 0.10, 0.60)))


# -------------------------------------------------------------------- input

def read_vtu(path, cell_arrays=(), point_arrays=(), allow_empty=False):
    """The unstructured grid in path; exits with a message if it is missing,
    has no cells (unless allow_empty) or lacks one of the named arrays."""
    def fail(msg):
        sys.exit("render_hex_pipeline: error: %s: %s" % (path, msg))
    if not os.path.isfile(path):
        fail("no such file")
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    grid = r.GetOutput()
    if r.GetErrorCode() or grid is None:
        fail("cannot read it as a VTK XML unstructured grid")
    if grid.GetNumberOfCells() == 0:
        if allow_empty:
            return grid
        fail("no cells")
    for data, names in ((grid.GetCellData(), cell_arrays), (grid.GetPointData(), point_arrays)):
        for n in names:
            if data.GetArray(n) is None:
                fail("no array '%s'" % n)
    return grid


def values(array):
    return [array.GetTuple1(i) for i in range(array.GetNumberOfTuples())]


# ------------------------------------------------------------ scene helpers

def new_scene():
    ren = vtk.vtkRenderer()
    ren.SetBackground(1, 1, 1)
    ren.SetUseDepthPeeling(1)  # correct order for the translucent surfaces
    ren.SetMaximumNumberOfPeels(20)
    ren.SetOcclusionRatio(0.0)
    vtk.vtkLightKit().AddLightsToRenderer(ren)
    return ren


def actor(source, colour, opacity=1.0):
    m = vtk.vtkPolyDataMapper()
    m.SetInputConnection(source.GetOutputPort())
    m.ScalarVisibilityOff()
    a = vtk.vtkActor()
    a.SetMapper(m)
    a.GetProperty().SetColor(colour)
    a.GetProperty().SetOpacity(opacity)
    return a


def domain_actors(tets, opacity):
    """The tet mesh's boundary surface (translucent) and its sharp edges."""
    surf = vtk.vtkDataSetSurfaceFilter()
    surf.SetInputData(tets)
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputConnection(surf.GetOutputPort())
    normals.SetFeatureAngle(30)
    skin = actor(normals, (0.72, 0.78, 0.86), opacity)
    skin.GetProperty().SetSpecular(0.2)
    edges = vtk.vtkFeatureEdges()
    edges.SetInputConnection(surf.GetOutputPort())
    edges.SetFeatureAngle(30)
    edges.BoundaryEdgesOff()
    edges.NonManifoldEdgesOff()
    edges.ManifoldEdgesOff()
    outline = actor(edges, (0.35, 0.38, 0.45))
    outline.GetProperty().SetLineWidth(2 * SS)
    outline.GetProperty().LightingOff()
    return [skin, outline]


def caption(ren, text, size=22):
    t = vtk.vtkTextActor()
    t.SetInput(text)
    p = t.GetTextProperty()
    p.SetFontSize(size * SS)
    p.SetColor(TEXT)
    p.SetFontFamilyToArial()
    t.SetDisplayPosition(24 * SS, (SIZE[1] - 24 - int(1.3 * size * (text.count("\n") + 1))) * SS)
    ren.AddActor2D(t)


def legend(ren, entries, box=(0.70, 0.04, 0.28, 0.16)):
    """entries: (label, colour); a coloured bar symbol each."""
    symbol = vtk.vtkCubeSource()
    symbol.SetXLength(2.0)
    symbol.SetYLength(0.5)
    symbol.Update()
    leg = vtk.vtkLegendBoxActor()
    leg.SetNumberOfEntries(len(entries))
    for i, (label, colour) in enumerate(entries):
        leg.SetEntry(i, symbol.GetOutput(), label, colour)
    leg.GetEntryTextProperty().SetFontSize(20 * SS)
    leg.GetEntryTextProperty().SetColor(TEXT)
    leg.BorderOff()
    leg.SetPosition(box[0], box[1])
    leg.SetPosition2(box[2], box[3])
    ren.AddActor2D(leg)


def oblique_camera(ren, bounds, azimuth=-35.0, elevation=30.0, region=(-0.92, 0.92, -0.92, 0.78)):
    """Look at the bounding box from the front (-y), turned and raised, z up;
    then pan and zoom so that its 8 corners just fill `region` (normalized
    device coordinates x0, x1, y0, y1), leaving room for caption and legend."""
    c = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
    cam = ren.GetActiveCamera()
    cam.SetFocalPoint(c)
    cam.SetPosition(c[0], c[1] - 1.0, c[2])
    cam.SetViewUp(0, 0, 1)
    cam.Azimuth(azimuth)
    cam.Elevation(elevation)
    cam.OrthogonalizeViewUp()
    ren.ResetCamera(bounds)
    corners = [(bounds[i], bounds[2 + j], bounds[4 + k]) for i in (0, 1) for j in (0, 1) for k in (0, 1)]
    for _ in range(4):  # perspective: pan and zoom are not linear, iterate
        m = cam.GetCompositeProjectionTransformMatrix(SIZE[0] / SIZE[1], -1, 1)
        ndc = [m.MultiplyPoint(p + (1.0,)) for p in corners]
        xs = [q[0] / q[3] for q in ndc]
        ys = [q[1] / q[3] for q in ndc]
        scale = min((region[1] - region[0]) / (max(xs) - min(xs)),
                    (region[3] - region[2]) / (max(ys) - min(ys)))
        dx = 0.5 * (region[0] + region[1]) - 0.5 * (min(xs) + max(xs)) * scale
        dy = 0.5 * (region[2] + region[3]) - 0.5 * (min(ys) + max(ys)) * scale
        cam.Zoom(scale)
        # pan: move the camera against the wanted shift, in view-plane units
        d = cam.GetDistance() * math.tan(math.radians(cam.GetViewAngle()) / 2)
        right = [0.0] * 3
        vtk.vtkMath.Cross(cam.GetDirectionOfProjection(), cam.GetViewUp(), right)
        up = cam.GetViewUp()
        shift = [-(dx * d * SIZE[0] / SIZE[1]) * right[i] - dy * d * up[i] for i in range(3)]
        cam.SetFocalPoint([cam.GetFocalPoint()[i] + shift[i] for i in range(3)])
        cam.SetPosition([cam.GetPosition()[i] + shift[i] for i in range(3)])
    ren.ResetCameraClippingRange()


def save(ren, path):
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetAlphaBitPlanes(1)
    win.SetMultiSamples(0)
    win.SetSize(SIZE[0] * SS, SIZE[1] * SS)
    win.AddRenderer(ren)
    win.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    shrink = vtk.vtkImageResize()  # windowed-sinc resampling
    shrink.SetInputConnection(grab.GetOutputPort())
    shrink.SetOutputDimensions(SIZE[0], SIZE[1], 1)
    png = vtk.vtkPNGWriter()
    png.SetCompressionLevel(9)
    png.SetFileName(path)
    png.SetInputConnection(shrink.GetOutputPort())
    png.Write()
    win.Finalize()
    print("wrote %s" % path)


def diagonal(bounds):
    return math.sqrt(sum((bounds[2 * i + 1] - bounds[2 * i]) ** 2 for i in range(3)))


# ------------------------------------------------------------------- images

def mean_length(grid, name):
    a = grid.GetCellData().GetArray(name)
    n = a.GetNumberOfTuples()
    return sum(math.sqrt(sum(c * c for c in a.GetTuple3(i))) for i in range(n)) / max(n, 1)


def render_frames(tets, path):
    b = tets.GetBounds()
    z = 0.5 * (b[4] + b[5]) + 1e-4 * diagonal(b)  # off the mid plane's mesh vertices
    plane = vtk.vtkPlane()
    plane.SetOrigin(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), z)
    plane.SetNormal(0, 0, 1)
    slab = vtk.vtkCutter()
    slab.SetInputData(tets)
    slab.SetCutFunction(plane)
    # One cross per cell of a square lattice two hex edges wide (a cross for
    # every cut tet would overlap its neighbours); each cross is the frame of
    # the tet containing its lattice point (probing copies cell data).
    lengths = [mean_length(tets, "hex_edge_%d" % k) for k in (1, 2, 3)]
    h = LATTICE * max(lengths)
    n = [max(1, round((b[2 * i + 1] - b[2 * i]) / h)) for i in (0, 1)]
    step = [(b[2 * i + 1] - b[2 * i]) / n[i] for i in (0, 1)]
    lattice = vtk.vtkPlaneSource()
    lattice.SetOrigin(b[0] + step[0] / 2, b[2] + step[1] / 2, z)
    lattice.SetPoint1(b[1] - step[0] / 2, b[2] + step[1] / 2, z)
    lattice.SetPoint2(b[0] + step[0] / 2, b[3] - step[1] / 2, z)
    lattice.SetResolution(max(1, n[0] - 1), max(1, n[1] - 1))
    probe = vtk.vtkProbeFilter()
    probe.SetInputConnection(lattice.GetOutputPort())
    probe.SetSourceData(tets)
    inside = vtk.vtkThresholdPoints()  # drop lattice points outside the domain
    inside.SetInputConnection(probe.GetOutputPort())
    inside.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "vtkValidPointMask")
    inside.ThresholdByUpper(0.5)
    inside.Update()
    ren = new_scene()
    a = actor(slab, (0.90, 0.90, 0.87), 0.85)
    a.GetProperty().LightingOff()
    ren.AddActor(a)
    for k, colour in enumerate(EDGE_COLOURS, 1):
        bar = vtk.vtkLineSource()  # a centred bar: the frame's +v and -v alike
        bar.SetPoint1(-0.5, 0, 0)
        bar.SetPoint2(0.5, 0, 0)
        glyphs = vtk.vtkGlyph3D()
        glyphs.SetInputConnection(inside.GetOutputPort())
        glyphs.SetSourceConnection(bar.GetOutputPort())
        glyphs.SetInputArrayToProcess(1, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "hex_edge_%d" % k)
        glyphs.SetVectorModeToUseVector()
        glyphs.SetScaleModeToScaleByVector()
        glyphs.OrientOn()
        glyphs.SetScaleFactor(GLYPH_SCALE)
        tubes = vtk.vtkTubeFilter()
        tubes.SetInputConnection(glyphs.GetOutputPort())
        tubes.SetRadius(0.04 * h)
        tubes.SetNumberOfSides(10)
        tubes.CappingOn()
        a = actor(tubes, colour)
        a.GetProperty().SetSpecular(0.3)
        ren.AddActor(a)
    for a in domain_actors(tets, 0.06):
        ren.AddActor(a)
    caption(ren, "Frame field on the mid plane z = %.2f: the three hex edge vectors\n"
                 "of the tet at each point (every %.2g), drawn at %g times their length"
            % (z, h, GLYPH_SCALE))
    legend(ren, [("hex_edge_%d  (mean length %.3g)" % (k, l), c)
                 for k, (l, c) in enumerate(zip(lengths, EDGE_COLOURS), 1)])
    oblique_camera(ren, b, azimuth=-25, elevation=55)
    save(ren, path)


def render_singularities(tets, sing, path):
    cd = sing.GetCellData()
    types = values(cd.GetArray("type")) if cd.GetArray("type") else []
    meshable = values(cd.GetArray("meshable")) if cd.GetArray("meshable") else []
    kind = vtk.vtkIntArray()
    kind.SetName("kind")
    counts = [0, 0, 0]
    for t, m in zip(types, meshable):
        k = 0 if (t == 1 and m) else 1 if (t == -1 and m) else 2
        kind.InsertNextValue(k)
        counts[k] += 1
    sing.GetCellData().AddArray(kind)
    ren = new_scene()
    radius = 0.008 * diagonal(tets.GetBounds())
    for k, (_, colour) in enumerate(SINGULAR_KINDS):
        if not counts[k]:
            continue
        sel = vtk.vtkThreshold()
        sel.SetInputData(sing)
        sel.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS, "kind")
        sel.SetLowerThreshold(k - 0.5)
        sel.SetUpperThreshold(k + 0.5)
        sel.SetThresholdFunction(vtk.vtkThreshold.THRESHOLD_BETWEEN)
        lines = vtk.vtkGeometryFilter()
        lines.SetInputConnection(sel.GetOutputPort())
        strip = vtk.vtkStripper()  # join the edges into polylines: smooth tube joints
        strip.SetInputConnection(lines.GetOutputPort())
        tubes = vtk.vtkTubeFilter()
        tubes.SetInputConnection(strip.GetOutputPort())
        tubes.SetRadius(radius)
        tubes.SetNumberOfSides(16)
        tubes.CappingOn()
        a = actor(tubes, colour)
        a.GetProperty().SetSpecular(0.4)
        a.GetProperty().SetSpecularPower(30)
        ren.AddActor(a)
    # curve ends and junctions (point data `node`) as small dark balls
    node = sing.GetPointData().GetArray("node")
    pts = vtk.vtkPoints()
    for i in range(sing.GetNumberOfPoints() if node else 0):
        if node.GetTuple1(i):
            pts.InsertNextPoint(sing.GetPoint(i))
    nodes = vtk.vtkPolyData()
    nodes.SetPoints(pts)
    ball = vtk.vtkSphereSource()
    ball.SetRadius(1.8 * radius)
    ball.SetThetaResolution(20)
    ball.SetPhiResolution(20)
    balls = vtk.vtkGlyph3D()
    balls.SetInputData(nodes)
    balls.SetSourceConnection(ball.GetOutputPort())
    balls.ScalingOff()
    ren.AddActor(actor(balls, (0.25, 0.25, 0.25)))
    for a in domain_actors(tets, 0.18):
        ren.AddActor(a)
    curves = len(set(values(cd.GetArray("curve")))) if cd.GetArray("curve") else 0
    caption(ren, "Singular curves: %d edges in %d curves, %d end points / junctions"
            % (sing.GetNumberOfCells(), curves, pts.GetNumberOfPoints()))
    legend(ren, [("%s: %d edges" % (label, n), c) for (label, c), n in zip(SINGULAR_KINDS, counts)])
    oblique_camera(ren, tets.GetBounds(), azimuth=-35, elevation=28)
    save(ren, path)


def sj_lookup_table(lo):
    """Red (bad) - yellow - blue (good), as in ColorBrewer's RdYlBu."""
    ctf = vtk.vtkColorTransferFunction()
    ctf.SetColorSpaceToLab()
    for x, rgb in ((0.0, (0.65, 0.0, 0.15)), (0.3, (0.96, 0.43, 0.26)), (0.6, (1.0, 0.88, 0.56)),
                   (0.85, (0.67, 0.85, 0.91)), (1.0, (0.19, 0.21, 0.58))):
        ctf.AddRGBPoint(lo + x * (1.0 - lo), *rgb)
    lut = vtk.vtkLookupTable()
    lut.SetNumberOfTableValues(256)
    lut.SetRange(lo, 1.0)
    for i in range(256):
        lut.SetTableValue(i, *ctf.GetColor(lo + (1.0 - lo) * i / 255.0), 1.0)
    lut.Build()
    return lut


def render_hexes(hexes, tets, path):
    sj = values(hexes.GetCellData().GetArray("scaled_jacobian"))
    b = hexes.GetBounds()
    c = [(b[2 * i] + b[2 * i + 1]) / 2 for i in range(3)]
    # keep the whole hexes behind an oblique plane through the centre (no
    # cell is cut in pieces), so the cut shows the interior hex layers
    plane = vtk.vtkPlane()
    plane.SetOrigin(c)
    plane.SetNormal(-0.45, -1.0, 0.55)
    keep = vtk.vtkExtractGeometry()
    keep.SetInputData(hexes)
    keep.SetImplicitFunction(plane)
    keep.ExtractInsideOn()
    keep.ExtractBoundaryCellsOff()
    surf = vtk.vtkDataSetSurfaceFilter()
    surf.SetInputConnection(keep.GetOutputPort())
    lo = min(0.0, math.floor(min(sj) * 10) / 10)
    lut = sj_lookup_table(lo)
    normals = vtk.vtkPolyDataNormals()  # smooth over the slightly non-planar quads
    normals.SetInputConnection(surf.GetOutputPort())
    normals.SetFeatureAngle(30)
    m = vtk.vtkPolyDataMapper()
    m.SetInputConnection(normals.GetOutputPort())
    m.SetScalarModeToUseCellFieldData()
    m.SelectColorArray("scaled_jacobian")
    m.SetLookupTable(lut)
    m.UseLookupTableScalarRangeOn()
    m.ScalarVisibilityOn()
    mesh = vtk.vtkActor()
    mesh.SetMapper(m)
    p = mesh.GetProperty()
    p.EdgeVisibilityOn()
    p.SetEdgeColor(0.15, 0.15, 0.2)
    p.SetLineWidth(1.2 * SS)
    p.SetAmbient(0.15)
    p.SetDiffuse(0.85)
    ren = new_scene()
    ren.AddActor(mesh)
    # the part cut away, as a faint ghost of the domain
    for a in domain_actors(tets, 0.06)[1:]:
        a.GetProperty().SetOpacity(0.3)
        ren.AddActor(a)
    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetTitle("scaled Jacobian")
    bar.SetNumberOfLabels(6 if lo == 0 else 5)
    bar.SetLabelFormat("%.1f")
    bar.UnconstrainedFontSizeOn()
    bar.SetBarRatio(0.25)
    for tp, size in ((bar.GetTitleTextProperty(), 22), (bar.GetLabelTextProperty(), 20)):
        tp.SetColor(TEXT)
        tp.SetFontSize(size * SS)
        tp.SetFontFamilyToArial()
        tp.ShadowOff()
        tp.ItalicOff()
    bar.SetPosition(0.83, 0.12)
    bar.SetPosition2(0.14, 0.62)
    ren.AddActor2D(bar)
    caption(ren, "Hex mesh: %d hexahedra, front part cut away\n"
                 "scaled Jacobian: min %.2f, median %.3f, %d below 0.5"
            % (len(sj), min(sj), statistics.median(sj), sum(s < 0.5 for s in sj)))
    oblique_camera(ren, b, azimuth=-35, elevation=30, region=(-0.92, 0.62, -0.92, 0.78))
    save(ren, path)


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: python3 scripts/render_hex_pipeline.py OUTDIR_OF_GENERATE HEX.vtu IMAGE_PREFIX")
    outdir, hex_vtu, prefix = argv
    tets = read_vtu(os.path.join(outdir, "frames.vtu"), ["hex_edge_1", "hex_edge_2", "hex_edge_3"])
    sing = read_vtu(os.path.join(outdir, "singularities.vtu"), ["type", "meshable"], ["node"], True)
    hexes = read_vtu(hex_vtu, ["scaled_jacobian"])
    if os.path.dirname(prefix):
        os.makedirs(os.path.dirname(prefix), exist_ok=True)
    render_frames(tets, prefix + "_frames.png")
    render_singularities(tets, sing, prefix + "_singularities.png")
    render_hexes(hexes, tets, prefix + "_hexes.png")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
