// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#ifndef CGAL_EXT_TETRAHEDRALIZE_H
#define CGAL_EXT_TETRAHEDRALIZE_H

/// \file tetrahedralize.h
/// Tetrahedral meshing of the inside of a closed surface, or of a built-in
/// shape, with CGAL Mesh_3. The header is free of CGAL: the meshing code is
/// compiled once, in the library.

#include <CGAL_ext/IO/Medit_mesh.h>
#include <CGAL_ext/Input_error.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace CGAL_ext {

/// \ingroup PkgCGALExtMesh
/// The parameters of `tetrahedralize_surface()` and `tetrahedralize_builtin()`.
///
/// Mesh_3's criteria are derived from `size` and `facet_distance`:
/// `cell_size = facet_size = edge_size = size`, `facet_angle = 25` degrees,
/// `cell_radius_edge_ratio = 3`. Mesh_3's sizes bound the radii of the
/// circumscribing balls of the cells and of the surface Delaunay balls of the
/// boundary facets, not edge lengths: the mean edge length comes out at about
/// 1.2 to 1.35 times `size` (shorter near protected sharp edges), and a fine
/// mesh has about `4.5 * volume / size^3` tetrahedra (doc/meshing.md).
struct Tetrahedralize_options {
  /// The target size (Mesh_3's `cell_size`, `facet_size` and, on sharp
  /// edges, `edge_size`); 0 means automatic: the diagonal of the bounding
  /// box of the domain divided by 20, capped by `max_automatic_size`. Must
  /// be finite and not negative.
  double size = 0;
  /// Caps the automatic `size` (used when `size` is 0): the diagonal / 20
  /// or this, the smaller; 0 means no cap. Must be finite and not negative.
  /// `metric-frames generate` sets it to the smallest hex edge that
  /// `--hex-size` asks for (h, or h / sqrt of the largest eigenvalue of a
  /// constant metric), so that the tetrahedra are about as large as the
  /// hexahedra, or smaller.
  double max_automatic_size = 0;
  /// The bound on the distance between the boundary facets and the input
  /// surface (Mesh_3's `facet_distance`); 0 means automatic: `size / 10`.
  /// Must be finite and not negative.
  double facet_distance = 0;
  /// For polyhedral domains (input surfaces and the built-in `box_with_hole`
  /// and `cube`): detect the edges of the surface whose dihedral angle
  /// differs from flat by more than `sharp_angle_deg` (the angle between
  /// the normals of their two facets), and protect them so that the mesh
  /// keeps them sharp. Ignored by smooth (implicit) built-in shapes.
  bool sharp_features = true;
  /// The angle of `sharp_features`, in degrees, in (0, 180]. At the default
  /// 60, a 45-degree chamfer is not protected (its edges come out rounded);
  /// the frame field's own feature angle (`Frame_field_options`) is 40.
  double sharp_angle_deg = 60;
  /// The seed of the random numbers of CGAL used while meshing; the caller's
  /// `CGAL::get_default_random()` is restored afterwards.
  unsigned seed = 0;
  /// Run the cheap optimizers, sliver perturbation and sliver exudation,
  /// after the refinement, both aiming at a smallest dihedral angle of 15
  /// degrees, without a time limit (a time limit would break determinism).
  /// They remove the flat tetrahedra and cost about a third of the
  /// refinement time. The slow global optimizers (Lloyd, ODT) are never run.
  bool optimize = true;
  /// The memory, in bytes, that the meshing and what follows may use: a size
  /// whose estimated mesh would need more is refused before Mesh_3 starts,
  /// with the estimate, and Mesh_3 stops with an error when its mesh
  /// reaches the vertices this allows (`memory_limit / bytes_per_tetrahedron
  /// / 6`: the limit holds where the estimate is wrong). 0 means the physical memory of this machine; a
  /// negative value means no limit. The estimate is
  /// `tetrahedra_per_unit_volume` tetrahedra per `size^3` of the domain's
  /// volume, and `bytes_per_tetrahedron` each (the peak of `metric-frames
  /// generate`, Mesh_3 included, measured on 10^4 to 1.3 10^6 tetrahedra).
  double memory_limit = 0;
  /// Mesh_3 runs in rounds of this many vertices (Mesh_3's vertex cap,
  /// then a resumed refinement), with a `progress` call after each. 0 means
  /// automatic: one call for meshes expected to have fewer than 1.5 10^5
  /// vertices (about 9 10^5 tetrahedra, seconds of meshing), rounds of an
  /// quarter of the expected vertices beyond. Rounds change the mesh slightly
  /// (each one rescans for bad elements) but not its determinism.
  std::size_t round_vertices = 0;
  /// Called after each round (see `round_vertices`): the vertices so far,
  /// the vertices expected (the tetrahedra estimate over 6), and the seconds
  /// since the call began.
  std::function<void(std::size_t vertices, std::size_t expected_vertices, double seconds)> progress;
};

/// \ingroup PkgCGALExtMesh
/// About how many tetrahedra Mesh_3 makes per `size^3` of volume (4.4 to 4.8
/// measured on fine meshes of the built-in shapes and of CGAL's fandisk and
/// elephant, up to 10 on coarse meshes dominated by sharp edges).
constexpr double tetrahedra_per_unit_volume = 5.0;
/// \ingroup PkgCGALExtMesh
/// Peak memory per tetrahedron of a whole `generate` run, Mesh_3 included
/// (1.50 GB for 1.0 10^6 tetrahedra, 1.85 GB for 1.27 10^6; doc/benchmarks.md),
/// rounded up.
constexpr double bytes_per_tetrahedron = 1600;

/// \ingroup PkgCGALExtMesh
/// The physical memory of this machine in bytes (0 if unknown).
/// \returns the size of the physical memory in bytes, or 0
double physical_memory_bytes();

/// \ingroup PkgCGALExtMesh
/// What `tetrahedralize_surface()` and `tetrahedralize_builtin()` made.
struct Tetrahedralize_report {
  std::size_t vertices = 0;           ///< vertices of the mesh
  std::size_t tets = 0;               ///< tetrahedra of the mesh
  std::size_t boundary_triangles = 0; ///< boundary triangles of the mesh
  double size = 0;                    ///< the size used (`Tetrahedralize_options::size`, or the automatic one)
  double seconds = 0;                 ///< wall-clock time of the whole call, reading included
  /// A one-line description of the domain and of the sizes used, e.g.
  /// ``surface 'part.off' (1200 vertices, 2396 triangles); size 0.17, facet
  /// distance 0.017; sharp edges protected (60 degrees)``. Every repair made
  /// to the input (orientation reversed, soup repaired, faces triangulated)
  /// is listed here after `repaired:`; nothing is ever repaired silently
  /// otherwise.
  std::string domain;
};

/// \ingroup PkgCGALExtMesh
/// Meshes the inside of the closed triangulated surface of a file with
/// tetrahedra (CGAL `Polyhedral_mesh_domain_with_features_3` and
/// `make_mesh_3`, sequential).
///
/// The surface may have several connected components (the inside is then
/// what they bound together, e.g. a hollow ball). Faces with more than three
/// vertices are triangulated. A surface whose faces all point inwards is
/// reversed, and a file whose faces do not form a surface at once (an STL
/// polygon soup, inconsistent orientations) is repaired with CGAL's polygon
/// soup repair and orientation; both are listed in `report->domain`.
///
/// The output is deterministic: for the same file and options, the same
/// mesh, bit for bit. Its vertices are numbered in Hilbert-curve order and its
/// tetrahedra sorted by their vertex indices.
///
/// \param path the file; `.off`, `.obj`, `.stl` or `.ply` (any case)
/// \param options the sizes and switches, see `Tetrahedralize_options`
/// \param report if not null, receives the counts, the time and a description
///   of the domain and of the repairs
/// \returns the mesh: `vertices`; `tetrahedra`, each positively oriented
///   (`CGAL::orientation(p0, p1, p2, p3) == CGAL::POSITIVE`), reference =
///   subdomain index (1); `triangles`, the boundary facets of the
///   tetrahedra, oriented with their normal pointing out of the domain,
///   reference = surface patch (1, 2... in the order of CGAL's patch ids);
///   `edges`, the protected sharp edges, reference = curve index;
///   `vertex_references`, the dimension of the feature the vertex lies on:
///   0 corner, 1 sharp edge, 2 surface, 3 inside. `vertex_lines` and
///   `tetrahedron_lines` are empty.
/// \throws Input_error naming the file for: a missing or unreadable file, an
///   unsupported extension, a file that cannot be parsed, a surface without
///   faces, a surface that is not a 2-manifold, a surface that is not closed
///   (with the number of border edges), a self-intersecting surface, a
///   surface that does not bound a volume even after reorientation, a
///   negative or non-finite `size` or `facet_distance`, a `size` so small
///   that the estimated mesh exceeds `memory_limit`, a mesh that reaches the
///   vertices `memory_limit` allows while meshing, and a meshing that
///   produced no tetrahedra.
IO::Medit_mesh tetrahedralize_surface(const std::string& path, const Tetrahedralize_options& options = {},
                                      Tetrahedralize_report* report = nullptr);

/// \ingroup PkgCGALExtMesh
/// Meshes one of the built-in shapes with tetrahedra, as
/// `tetrahedralize_surface()` does (same output conventions, same
/// determinism). The shapes are (`builtin_shape_names()`):
///
/// - `ball`: the unit ball (implicit domain, smooth);
/// - `torus`: the torus of radii R = 1 and r = 0.4 around the z axis
///   (implicit domain, smooth, genus 1);
/// - `box_with_hole`: the box [-1,1] x [-1,1] x [-0.5,0.5] minus the
///   cylinder of radius 0.4 around the z axis, the cylinder being a prism
///   over a regular 96-gon (polyhedral domain; the box's 12 edges and the
///   hole's 2 circles are protected when `sharp_features` is on);
/// - `cube`: the cube [-1,1]^3 (polyhedral domain, 12 sharp edges);
/// - `blobby`: a smooth union of four balls of different radii (implicit
///   domain, genus 0, no symmetry).
///
/// \param name the shape's name
/// \param options the sizes and switches, see `Tetrahedralize_options`
/// \param report if not null, receives the counts, the time and a description
/// \returns the mesh
/// \throws Input_error for an unknown name (the message lists the valid
///   names), a negative or non-finite `size` or `facet_distance`, a `size` so
///   small that the estimated mesh exceeds `memory_limit`, a mesh that
///   reaches the vertices `memory_limit` allows while meshing, and a meshing
///   that produced no tetrahedra.
IO::Medit_mesh tetrahedralize_builtin(const std::string& name, const Tetrahedralize_options& options = {},
                                      Tetrahedralize_report* report = nullptr);

/// \ingroup PkgCGALExtMesh
/// The names accepted by `tetrahedralize_builtin()`, in alphabetical order.
/// \returns `ball`, `blobby`, `box_with_hole`, `cube`, `torus`
std::vector<std::string> builtin_shape_names();

} // namespace CGAL_ext

#endif // CGAL_EXT_TETRAHEDRALIZE_H
