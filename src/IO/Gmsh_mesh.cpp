// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
#include <CGAL_ext/IO/Gmsh_mesh.h>

#include "input_file.h"
#include "text_binary_cursor.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace CGAL_ext {
namespace IO {

namespace {

// Node count, dimension and name of Gmsh's element types (MSH_* in Gmsh's GmshDefines.h).
struct Element_type {
  int nodes, dim;
  const char* name;
};

std::optional<Element_type> element_type(std::int64_t type) {
  static const std::unordered_map<std::int64_t, Element_type> types = {
      {1, {2, 1, "line"}}, {2, {3, 2, "triangle"}}, {3, {4, 2, "quadrangle"}}, {4, {4, 3, "tetrahedron"}},
      {5, {8, 3, "hexahedron"}}, {6, {6, 3, "prism"}}, {7, {5, 3, "pyramid"}}, {8, {3, 1, "second-order line"}},
      {9, {6, 2, "second-order triangle"}}, {10, {9, 2, "second-order quadrangle"}},
      {11, {10, 3, "second-order tetrahedron"}}, {12, {27, 3, "second-order hexahedron"}},
      {13, {18, 3, "second-order prism"}}, {14, {14, 3, "second-order pyramid"}}, {15, {1, 0, "point"}},
      {16, {8, 2, "8-node quadrangle"}}, {17, {20, 3, "20-node hexahedron"}}, {18, {15, 3, "15-node prism"}},
      {19, {13, 3, "13-node pyramid"}}, {20, {9, 2, "9-node triangle"}}, {21, {10, 2, "third-order triangle"}},
      {22, {12, 2, "12-node triangle"}}, {23, {15, 2, "fourth-order triangle"}}, {24, {15, 2, "15-node triangle"}},
      {25, {21, 2, "fifth-order triangle"}}, {26, {4, 1, "third-order line"}}, {27, {5, 1, "fourth-order line"}},
      {28, {6, 1, "fifth-order line"}}, {29, {20, 3, "third-order tetrahedron"}},
      {30, {35, 3, "fourth-order tetrahedron"}}, {31, {56, 3, "fifth-order tetrahedron"}},
      {92, {64, 3, "third-order hexahedron"}}, {93, {125, 3, "fourth-order hexahedron"}}};
  const auto it = types.find(type);
  if (it == types.end()) return std::nullopt;
  return it->second;
}


// Tags hashed through splitmix64's finalizer: std::hash of an integer is the
// integer, so tags that are multiples of the bucket count would all share a
// bucket and make a crafted file's lookups quadratic.
struct Scrambled_tag_hash {
  std::size_t operator()(std::int64_t tag) const {
    std::uint64_t z = std::uint64_t(tag) + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return std::size_t(z ^ (z >> 31));
  }
};

struct Reader {
  internal::Text_binary_cursor cursor;
  int major = 0;
  bool binary = false;
  Medit_mesh mesh;
  std::unordered_map<std::int64_t, std::size_t, Scrambled_tag_hash> node_index; // tag -> 0-based vertex
  // MSH 4.1: (dimension, entity tag) -> the entity's first physical tag.
  std::unordered_map<std::int64_t, int, Scrambled_tag_hash> entity_physical[4];
  std::size_t element_line = 0; // the line of the element being read (ASCII)

  explicit Reader(const std::string& path) : cursor(path) {}

  // A count that the rest of the file can hold, each record taking at least `bytes` bytes.
  std::size_t count(std::int64_t n, std::size_t bytes, const char* what) {
    if (n < 0 || std::uint64_t(n) > cursor.remaining() / bytes)
      cursor.fail("", std::string("the count of ") + what + " " + std::to_string(n) +
                          " is more than the rest of the file can hold: wrong count or truncated file");
    return std::size_t(n);
  }
  std::size_t ascii_or_binary_count(const char* what, std::size_t bytes) {
    return count(binary ? std::int64_t(std::min<std::uint64_t>(cursor.size(what), INT64_MAX)) : cursor.integer(what),
                 bytes, what);
  }

  void read_format() {
    cursor.expect("$MeshFormat");
    const std::string_view version = cursor.token("the format version");
    const std::int64_t file_type = cursor.integer("the file type (0 ASCII, 1 binary)");
    const std::int64_t data_size = cursor.integer("the data size");
    if (version == "4.1")
      major = 4;
    else if (version == "2" || version == "2.0" || version == "2.1" || version == "2.2")
      major = 2;
    else
      cursor.fail("", "MSH version " + Input_error::quote(version) +
                          " is not read: save the mesh as MSH 4.1 or 2.2 (Gmsh: -format msh41 or msh22)");
    if (file_type != 0 && file_type != 1) cursor.fail("", "file type " + std::to_string(file_type) + " is not 0 or 1");
    if (data_size != 8) cursor.fail("", "data size " + std::to_string(data_size) + " is not 8");
    binary = file_type == 1;
    if (binary) {
      cursor.skip_line_end();
      cursor.start_binary();
      const std::int64_t one = cursor.int32("the endianness check");
      if (one != 1) cursor.fail("", "binary data is not little-endian (the check value reads " + std::to_string(one) + ")");
    }
    cursor.expect("$EndMeshFormat");
  }

  void add_node(std::int64_t tag, const std::array<double, 3>& x) {
    if (!node_index.emplace(tag, mesh.vertices.size()).second)
      cursor.fail("node " + std::to_string(tag), "node tag given twice");
    mesh.vertices.push_back(x);
    mesh.vertex_references.push_back(0);
    if (!binary) mesh.vertex_lines.push_back(cursor.line());
  }

  // MSH 2.2 lists an element once per physical group it is in, with the
  // same elementary tag: (type, elementary tag, sorted nodes) of each
  // element kept, to keep the first listing only.
  std::unordered_map<std::string, int> listed;
  std::int64_t elementary = 0; // the elementary tag of the MSH 2.2 element being read
  bool listed_before(std::int64_t type, std::vector<std::size_t> v, int reference);

  void add_element(std::int64_t tag, std::int64_t type, const std::vector<std::int64_t>& nodes, int reference);

  // Runs `read`, naming `element` in an Input_error that names none (a
  // token that is not a number, a truncated record).
  template <class Read>
  void named(const std::string& element, Read&& read) {
    try {
      read();
    } catch (const Input_error& e) {
      if (!e.element().empty()) throw;
      throw Input_error(e.file(), e.line(), element, e.problem());
    }
  }
  void read_nodes_v2();
  void read_elements_v2();
  void read_entities_v4();
  void read_nodes_v4();
  void read_elements_v4();
  Medit_mesh read();
};

void Reader::add_element(std::int64_t tag, std::int64_t type, const std::vector<std::int64_t>& nodes, int reference) {
  const std::string element = "element " + std::to_string(tag);
  const Element_type t = *element_type(type);
  if (t.dim == 3 && type != 4)
    cursor.fail_at(element_line, element, std::string("a ") + t.name + " (element type " + std::to_string(type) +
                             "): only linear tetrahedra are read; leaving it out would change the domain");
  if (type != 4 && type != 2 && type != 1) return; // points, quadrangles, higher-order surface elements
  std::vector<std::size_t> v;
  for (std::int64_t n : nodes) {
    const auto it = node_index.find(n);
    if (it == node_index.end())
      cursor.fail_at(element_line, element, "node tag " + std::to_string(n) + " is not a node of the file");
    v.push_back(it->second);
  }
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      if (v[i] == v[j]) cursor.fail_at(element_line, element, "node tag " + std::to_string(nodes[i]) + " appears twice");
  if (major == 2 && listed_before(type, v, reference)) return;
  if (type == 4) {
    mesh.tetrahedra.push_back({v[0], v[1], v[2], v[3]});
    mesh.tetrahedron_references.push_back(reference);
    if (!binary) mesh.tetrahedron_lines.push_back(element_line);
  } else if (type == 2) {
    mesh.triangles.push_back({v[0], v[1], v[2]});
    mesh.triangle_references.push_back(reference);
  } else {
    mesh.edges.push_back({v[0], v[1]});
    mesh.edge_references.push_back(reference);
  }
}

bool Reader::listed_before(std::int64_t type, std::vector<std::size_t> v, int reference) {
  std::sort(v.begin(), v.end());
  std::string key(2 * sizeof(std::int64_t) + sizeof(std::size_t) * v.size(), '\0');
  std::memcpy(&key[0], &type, sizeof type);
  std::memcpy(&key[sizeof type], &elementary, sizeof elementary);
  std::memcpy(&key[2 * sizeof type], v.data(), sizeof(std::size_t) * v.size());
  const auto [it, inserted] = listed.emplace(std::move(key), reference);
  // The same element with the same reference is a duplicate the user should
  // hear of (the triangulation refuses it): it is kept.
  return !inserted && it->second != reference;
}

std::optional<Element_type> checked_type(internal::Text_binary_cursor& cursor, std::int64_t type, const std::string& element) {
  const auto t = element_type(type);
  if (!t) cursor.fail(element, "unknown element type " + std::to_string(type));
  return t;
}

int checked_reference(internal::Text_binary_cursor& cursor, std::int64_t tag, const std::string& element) {
  if (tag < INT32_MIN || tag > INT32_MAX) cursor.fail(element, "physical tag " + std::to_string(tag) + " is not a 32-bit integer");
  return int(tag);
}

void Reader::read_nodes_v2() {
  const std::size_t n = count(cursor.integer("the number of nodes"), binary ? 28 : 8, "nodes");
  if (binary) cursor.skip_line_end();
  for (std::size_t i = 0; i < n; ++i)
    named("node record " + std::to_string(i + 1), [&] {
      const std::int64_t tag = binary ? cursor.int32("a node tag") : cursor.integer("a node tag");
      if (tag <= 0) cursor.fail("node " + std::to_string(tag), "a node tag must be positive");
      std::array<double, 3> x;
      for (double& c : x) c = binary ? cursor.real("a coordinate") : cursor.number("a coordinate");
      add_node(tag, x);
    });
  cursor.expect("$EndNodes");
}

void Reader::read_elements_v2() {
  const std::size_t n = count(cursor.integer("the number of elements"), 8, "elements");
  if (binary) cursor.skip_line_end();
  std::vector<std::int64_t> nodes;
  for (std::size_t done = 0; done < n;) {
    // ASCII: one header per element; binary: one per block of elements of a type.
    const std::int64_t first = binary ? cursor.int32("an element type") : cursor.integer("an element tag");
    element_line = cursor.line();
    const std::int64_t type = binary ? first : cursor.integer("an element type");
    const std::size_t block = binary ? count(cursor.int32("an element count"), 8, "elements of a block") : 1;
    const std::int64_t ntags = binary ? cursor.int32("a tag count") : cursor.integer("a tag count");
    if (block > n - done) cursor.fail("", "more elements in the blocks than the section's count");
    const std::string where = binary ? "element block of type " + std::to_string(type) : "element " + std::to_string(first);
    const auto t = checked_type(cursor, type, where);
    if (ntags < 0 || ntags > 64) cursor.fail(where, "tag count " + std::to_string(ntags) + " is not in [0, 64]");
    for (std::size_t k = 0; k < block; ++k, ++done) named("element record " + std::to_string(done + 1), [&] {
      const std::int64_t tag = binary ? cursor.int32("an element tag") : first;
      std::int64_t physical = 0;
      elementary = 0;
      for (std::int64_t j = 0; j < ntags; ++j) {
        const std::int64_t v = binary ? cursor.int32("a tag") : cursor.integer("a tag");
        if (j == 0) physical = v;
        if (j == 1) elementary = v;
      }
      nodes.resize(std::size_t(t->nodes));
      for (std::int64_t& v : nodes) v = binary ? cursor.int32("a node tag") : cursor.integer("a node tag");
      add_element(tag, type, nodes, checked_reference(cursor, physical, "element " + std::to_string(tag)));
    });
  }
  cursor.expect("$EndElements");
}

void Reader::read_entities_v4() {
  std::size_t counts[4];
  for (std::size_t& c : counts) c = ascii_or_binary_count("the number of entities", binary ? 36 : 10);
  for (int dim = 0; dim < 4; ++dim)
    for (std::size_t i = 0; i < counts[dim]; ++i) {
      const std::int64_t tag = binary ? cursor.int32("an entity tag") : cursor.integer("an entity tag");
      const std::string element = "entity " + std::to_string(tag) + " of dimension " + std::to_string(dim);
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) binary ? cursor.real("a bounding box coordinate") : cursor.number("a bounding box coordinate");
      const std::size_t physicals = ascii_or_binary_count("the number of physical tags", binary ? 4 : 2);
      for (std::size_t j = 0; j < physicals; ++j) {
        const std::int64_t p = binary ? cursor.int32("a physical tag") : cursor.integer("a physical tag");
        if (j == 0) entity_physical[dim][tag] = checked_reference(cursor, p, element);
      }
      if (dim == 0) continue;
      const std::size_t bounding = ascii_or_binary_count("the number of bounding entities", binary ? 4 : 2);
      for (std::size_t j = 0; j < bounding; ++j) binary ? cursor.int32("a bounding entity") : cursor.integer("a bounding entity");
    }
  cursor.expect("$EndEntities");
}

void Reader::read_nodes_v4() {
  const std::size_t blocks = ascii_or_binary_count("the number of node blocks", binary ? 20 : 8);
  ascii_or_binary_count("the number of nodes", 1);
  for (int k = 0; k < 2; ++k) binary ? std::int64_t(cursor.size("a node tag bound")) : cursor.integer("a node tag bound");
  for (std::size_t b = 0; b < blocks; ++b) named("node block " + std::to_string(b + 1), [&] {
    const std::int64_t dim = binary ? cursor.int32("an entity dimension") : cursor.integer("an entity dimension");
    binary ? cursor.int32("an entity tag") : cursor.integer("an entity tag");
    const std::int64_t parametric = binary ? cursor.int32("the parametric flag") : cursor.integer("the parametric flag");
    if (dim < 0 || dim > 3 || (parametric != 0 && parametric != 1))
      cursor.fail("node block " + std::to_string(b + 1), "entity dimension " + std::to_string(dim) +
                                                              " or parametric flag " + std::to_string(parametric) + " is wrong");
    const std::size_t extra = parametric ? std::size_t(dim) : 0; // the parametric coordinates, not used
    const std::size_t n = ascii_or_binary_count("the number of nodes in a block", binary ? 32 : 8);
    std::vector<std::int64_t> tags(n);
    for (std::int64_t& t : tags) {
      t = binary ? std::int64_t(std::min<std::uint64_t>(cursor.size("a node tag"), INT64_MAX)) : cursor.integer("a node tag");
      if (t <= 0) cursor.fail("node " + std::to_string(t), "a node tag must be positive");
    }
    for (std::int64_t t : tags) {
      std::array<double, 3> x;
      for (double& c : x) c = binary ? cursor.real("a coordinate") : cursor.number("a coordinate");
      for (std::size_t j = 0; j < extra; ++j) binary ? cursor.real("a parametric coordinate") : cursor.number("a parametric coordinate");
      add_node(t, x);
    }
  });
  cursor.expect("$EndNodes");
}

void Reader::read_elements_v4() {
  const std::size_t blocks = ascii_or_binary_count("the number of element blocks", binary ? 20 : 8);
  ascii_or_binary_count("the number of elements", 1);
  for (int k = 0; k < 2; ++k) binary ? std::int64_t(cursor.size("an element tag bound")) : cursor.integer("an element tag bound");
  std::vector<std::int64_t> nodes;
  for (std::size_t b = 0; b < blocks; ++b) named("element block " + std::to_string(b + 1), [&] {
    const std::int64_t dim = binary ? cursor.int32("an entity dimension") : cursor.integer("an entity dimension");
    const std::int64_t entity = binary ? cursor.int32("an entity tag") : cursor.integer("an entity tag");
    const std::int64_t type = binary ? cursor.int32("an element type") : cursor.integer("an element type");
    const std::string where = "element block " + std::to_string(b + 1);
    const auto t = checked_type(cursor, type, where);
    if (dim != t->dim) cursor.fail(where, "entity dimension " + std::to_string(dim) + " is not that of a " + t->name);
    const auto physical = entity_physical[dim].find(entity);
    const int reference = physical == entity_physical[dim].end() ? 0 : physical->second;
    const std::size_t n = ascii_or_binary_count("the number of elements in a block", binary ? 8 * (1 + t->nodes) : 4);
    nodes.resize(std::size_t(t->nodes));
    for (std::size_t e = 0; e < n; ++e) {
      const std::int64_t tag = binary ? std::int64_t(std::min<std::uint64_t>(cursor.size("an element tag"), INT64_MAX))
                                      : cursor.integer("an element tag");
      element_line = cursor.line();
      for (std::int64_t& v : nodes)
        v = binary ? std::int64_t(std::min<std::uint64_t>(cursor.size("a node tag"), INT64_MAX)) : cursor.integer("a node tag");
      add_element(tag, type, nodes, reference);
    }
  });
  cursor.expect("$EndElements");
}

Medit_mesh Reader::read() {
  read_format();
  bool entities = false, nodes = false, elements = false;
  std::string_view section;
  while (cursor.next(section)) {
    const bool known = section == "$Nodes" || section == "$Elements" || (section == "$Entities" && major == 4);
    if (known) {
      if (binary && major == 4) cursor.skip_line_end();
      if (section == "$Entities") {
        // The elements' references come from the entities: they must come first, once.
        if (entities || nodes) cursor.fail("", entities ? "a second $Entities section" : "$Entities after $Nodes");
        read_entities_v4();
        entities = true;
      } else if (section == "$Nodes") {
        if (nodes) cursor.fail("", "a second $Nodes section");
        major == 4 ? read_nodes_v4() : read_nodes_v2();
        nodes = true;
      } else if (section == "$Elements") {
        if (!nodes) cursor.fail("", "$Elements before $Nodes");
        if (elements) cursor.fail("", "a second $Elements section");
        major == 4 ? read_elements_v4() : read_elements_v2();
        elements = true;
      }
    } else if (section == "$PartitionedEntities") {
      cursor.fail("", "partitioned meshes are not read: save the mesh unpartitioned");
    } else if (section.size() > 1 && section[0] == '$' && section.substr(0, 4) != "$End") {
      cursor.skip_section(section);
    } else {
      cursor.fail("", "expected a section ($Nodes, $Elements...), found " + Input_error::quote(section));
    }
  }
  if (mesh.tetrahedra.empty())
    throw Input_error(cursor.path(), 0, "", "no tetrahedra (element type 4): not a 3D tetrahedral mesh");
  return std::move(mesh);
}

} // namespace

Medit_mesh read_gmsh_mesh(const std::string& path) {
  Reader reader(path);
  return reader.read();
}

} // namespace IO
} // namespace CGAL_ext
