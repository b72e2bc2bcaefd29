// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_GROUPS_H
#define CGAL_EXT_GROUPS_H

/// \file groups.h
/// The Doxygen groups of the package (no code): one per component, in the
/// order of the pipeline (doc/architecture.md).

/// \defgroup PkgCGALExtIO Input and output files
/// Medit `.mesh` and `.sol`, VTU for ParaView, CubeCover `.fra` and `.perm`,
/// HexEx's `.hexex` maps and `.ovm` hex meshes, Medit hex meshes.

/// \defgroup PkgCGALExtMesh Tetrahedral meshes
/// The triangulation of a tet mesh, its statistics, and Mesh_3 meshing of surfaces.

/// \defgroup PkgCGALExtWalk Exact segment walk
/// Every vertex, edge, facet and cell a segment meets, decided with exact predicates.

/// \defgroup PkgCGALExtMetric Metric field and connection
/// `A = g^{1/2}` per vertex, linear per tet; its curl and the connection one-form `W`.

/// \defgroup PkgCGALExtTransport Transport
/// The rotation coefficient `T(a->b)` inside a cell and between arbitrary points.

/// \defgroup PkgCGALExtFrames Octahedral frame fields
/// SH band-4 frames, frame-field generation in a metric, singular edges.

/// \defgroup PkgCGALExtHex Integer-grid maps and hexahedra
/// The parametrization whose integer grid the hexahedra are: seamless,
/// aligned with the boundary, quantized; its solver and its files. Hex
/// meshes and their quality.

/// \defgroup PkgCGALExtPipeline The generate pipeline
/// Mesh, metric, frame field, singularities and output files, as the
/// `metric-frames generate` command chains them, callable from C++.

#endif // CGAL_EXT_GROUPS_H
