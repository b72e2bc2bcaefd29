// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
// Output files: VTU (ParaView) tetrahedra and segments, read back with our own
// strict reader (test/vtu_test_reader.h), in binary and ASCII; CubeCover .fra
// frame fields, written and read back bit for bit; CubeCover .perm face
// matchings; and every kind of bad input.
#include <CGAL_ext/IO/Fra_file.h>
#include <CGAL_ext/IO/Perm_file.h>
#include <CGAL_ext/IO/Vtu_file.h>
#include <CGAL_ext/Input_error.h>

#include "input_error_checks.h"
#include "vtu_test_reader.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using CGAL_ext::IO::read_fra;
using CGAL_ext::IO::Vtu_array;
using CGAL_ext::IO::Vtu_options;
using CGAL_ext::IO::write_fra;
using CGAL_ext::IO::write_vtu_segments;
using CGAL_ext::IO::write_vtu_tetrahedra;
using CGAL_ext::testing::Data_array;
using CGAL_ext::testing::read_vtu;
using Points = std::vector<std::array<double, 3>>;
using Frames = std::vector<std::array<double, 9>>;

const double not_a_number = std::numeric_limits<double>::quiet_NaN();
const double infinity = std::numeric_limits<double>::infinity();

// The scratch directory of this test process: CTest runs test cases as
// parallel processes, each gets its own directory (named after its pid),
// removed at exit.
struct Scratch {
  fs::path path = fs::temp_directory_path() / ("cgal_ext_test_output_files_" + std::to_string(::getpid()));
  Scratch() {
    std::error_code ec;
    fs::remove_all(path, ec);
    fs::create_directories(path);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};
std::string scratch(const std::string& name) {
  static const Scratch s;
  return (s.path / name).string();
}

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string put_file(const std::string& name, const std::string& text) {
  const std::string p = scratch(name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// Files that the atomic writer's temporary files would have left behind.
std::size_t temporary_files_left() {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(fs::path(scratch("x")).parent_path()))
    if (e.path().filename().string().rfind(".mf-tmp-", 0) == 0) ++n;
  return n;
}

// Equality bit for bit (so NaN == NaN and 0.0 != -0.0).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

std::vector<double> flatten(const Points& p) {
  std::vector<double> r;
  for (const auto& x : p) r.insert(r.end(), x.begin(), x.end());
  return r;
}

template <std::size_t N>
std::vector<double> flatten(const std::vector<std::array<std::size_t, N>>& cells) {
  std::vector<double> r;
  for (const auto& c : cells)
    for (std::size_t v : c) r.push_back(static_cast<double>(v));
  return r;
}

// Checks a decoded array against what was written.
void check_array(const std::map<std::string, Data_array>& arrays, const Vtu_array& expected, const std::string& format) {
  INFO("array " << expected.name);
  const auto it = arrays.find(expected.name);
  REQUIRE(it != arrays.end());
  const Data_array& got = it->second;
  CHECK(got.type == (expected.integer ? "Int32" : "Float64"));
  CHECK(got.format == format);
  CHECK(got.components == expected.components);
  CHECK(same_bits(got.values, expected.values));
}

// Checks the geometry and cells of a decoded file.
template <std::size_t N>
void check_grid(const CGAL_ext::testing::Vtu_content& v, const Points& points,
                const std::vector<std::array<std::size_t, N>>& cells, double vtk_type, const std::string& format) {
  CHECK(v.root_attributes.at("type") == "UnstructuredGrid");
  CHECK(v.root_attributes.at("byte_order") == "LittleEndian");
  CHECK(v.root_attributes.at("header_type") == "UInt64");
  CHECK(v.root_attributes.at("version") == "1.0");
  CHECK(v.number_of_points == points.size());
  CHECK(v.number_of_cells == cells.size());
  CHECK(v.points.type == "Float64");
  CHECK(v.points.format == format);
  CHECK(same_bits(v.points.values, flatten(points)));
  CHECK(v.connectivity.type == "Int64");
  CHECK(v.connectivity.values == flatten(cells));
  CHECK(v.offsets.type == "Int64");
  CHECK(v.types.type == "UInt8");
  std::vector<double> offsets, types;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    offsets.push_back(static_cast<double>(N * (i + 1)));
    types.push_back(vtk_type);
  }
  CHECK(v.offsets.values == offsets);
  CHECK(v.types.values == types);
}

// Two tetrahedra sharing a face, with coordinates that need all 17 digits
// (and a subnormal and a huge one), and one array of each kind.
struct Two_tets {
  Points points{{0.1, 1.0 / 3, -2.5},
                {1, 0, 0},
                {0, 1, 4.9406564584124654e-324},
                {0, 0, 1},
                {1.7976931348623157e308, -0.0, 2.0 / 3}};
  std::vector<std::array<std::size_t, 4>> tets{{0, 1, 2, 3}, {1, 2, 3, 4}};
  std::vector<Vtu_array> cell_data{
      {"quality", 1, {0.5, 1.0 / 7}, false},
      {"direction", 3, {1, 0, 0, 0.6, -0.8, 1e-17}, false},
      {"frame", 9, {1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9}, false},
      {"label <&\"'>", 1, {7, -2147483648.0}, true}};
  std::vector<Vtu_array> point_data{{"size", 1, {1, 2, 3, 4, 5.5}, false},
                                    {"singular", 1, {0, 1, 0, 2147483647.0, -1}, true},
                                    {"normal", 3, {0, 0, 1, 0, 1, 0, 1, 0, 0, 0.5, 0.5, 0.5, -1, -1, -1}, false}};
};

// Runs `write`, which must throw std::invalid_argument naming `path` and
// containing `words`, and checks that the file that was at `path` is intact
// and that no temporary file is left.
void expect_invalid(const std::string& path, const std::function<void()>& write, const std::string& words) {
  const std::string before = "previous content, must survive\n";
  std::ofstream(path, std::ios::binary) << before;
  try {
    write();
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find(path) != std::string::npos);
    CHECK(what.find(words) != std::string::npos);
  }
  CHECK(slurp(path) == before);
  CHECK(temporary_files_left() == 0);
}

// Expects read_perm(path) to throw an Input_error (see expect_input_error).
void expect_perm_error(const std::string& path, std::size_t line, const std::string& element, const std::string& words) {
  CGAL_ext::testing::expect_input_error([&] { CGAL_ext::IO::read_perm(path); }, path, line, element, words);
}

// Expects read_fra(path) to throw an Input_error (see expect_input_error).
void expect_fra_error(const std::string& path, std::size_t line, const std::string& element, const std::string& words) {
  CGAL_ext::testing::expect_input_error([&] { read_fra(path); }, path, line, element, words);
}

} // namespace

// --- The test reader itself ---------------------------------------------

TEST_CASE("the test reader's base64 decoder follows RFC 4648", "[vtu][reader]") {
  auto text = [](const std::string& s) {
    const auto b = CGAL_ext::testing::base64_decode(s);
    return std::string(b.begin(), b.end());
  };
  // RFC 4648 section 10 test vectors.
  CHECK(text("") == "");
  CHECK(text("Zg==") == "f");
  CHECK(text("Zm8=") == "fo");
  CHECK(text("Zm9v") == "foo");
  CHECK(text("Zm9vYg==") == "foob");
  CHECK(text("Zm9vYmE=") == "fooba");
  CHECK(text("Zm9vYmFy") == "foobar");
  CHECK_THROWS(text("Zm9"));      // length
  CHECK_THROWS(text("Zm=v"));     // data after padding
  CHECK_THROWS(text("Zm9v Zg=")); // white space inside
}

TEST_CASE("the test reader refuses XML that is not well formed", "[vtu][reader]") {
  using CGAL_ext::testing::parse_xml;
  const auto good = parse_xml("<?xml version=\"1.0\"?>\n<A x=\"1\" y='2'><B/><C z=\"&lt;&amp;\">t&gt;</C></A>\n");
  CHECK(good->name == "A");
  CHECK(good->attributes.at("y") == "2");
  REQUIRE(good->children.size() == 2);
  CHECK(good->children[1]->attributes.at("z") == "<&");
  CHECK(good->children[1]->text == "t>");
  CHECK_THROWS(parse_xml("<A><B></A></B>"));       // wrong nesting
  CHECK_THROWS(parse_xml("<A><B></B>"));           // not closed
  CHECK_THROWS(parse_xml("<A x=1></A>"));          // unquoted attribute
  CHECK_THROWS(parse_xml("<A x=\"1\" x=\"2\"/>")); // repeated attribute
  CHECK_THROWS(parse_xml("<A/><B/>"));             // two roots
  CHECK_THROWS(parse_xml("<A>a < b</A>"));         // stray '<'
  CHECK_THROWS(parse_xml("<A>a & b</A>"));         // stray '&'
  CHECK_THROWS(parse_xml("<A x=\"1\"y=\"2\"/>"));  // no space between attributes
  CHECK_THROWS(parse_xml(" <?xml version=\"1.0\"?><A/>"));
  CHECK_THROWS(CGAL_ext::testing::parse_vtu("<VTKFile type=\"UnstructuredGrid\"/>"));
}

// --- VTU ---------------------------------------------------------------------

TEST_CASE("VTU tetrahedra: points, cells and every array read back exactly", "[vtu]") {
  const bool binary = GENERATE(true, false);
  const std::string format = binary ? "binary" : "ascii";
  INFO(format);
  const Two_tets m;
  const std::string p = scratch("two_tets_" + format + ".vtu");
  write_vtu_tetrahedra(p, m.points, m.tets, m.cell_data, m.point_data, Vtu_options{binary});
  const auto v = read_vtu(p);
  check_grid(v, m.points, m.tets, 10, format);
  CHECK(v.cell_data.size() == m.cell_data.size());
  CHECK(v.point_data.size() == m.point_data.size());
  for (const Vtu_array& a : m.cell_data) check_array(v.cell_data, a, format);
  for (const Vtu_array& a : m.point_data) check_array(v.point_data, a, format);
  CHECK(temporary_files_left() == 0);
  // The name with XML special characters is escaped in the file.
  CHECK(slurp(p).find("Name=\"label &lt;&amp;&quot;&apos;&gt;\"") != std::string::npos);
}

TEST_CASE("VTU segments: lines (type 3) with their arrays read back exactly", "[vtu]") {
  const bool binary = GENERATE(true, false);
  const std::string format = binary ? "binary" : "ascii";
  INFO(format);
  const Points points{{0, 0, 0}, {0.5, 0.25, 0.125}, {1, 1, 1}, {-3e-5, 7, 1e10}};
  const std::vector<std::array<std::size_t, 2>> segments{{0, 1}, {1, 2}, {3, 0}};
  const std::vector<Vtu_array> cell_data{{"index", 1, {1, -1, 1}, true},
                                         {"tangent", 3, {1, 0, 0, 0, 1, 0, 0.6, 0, 0.8}, false}};
  const std::vector<Vtu_array> point_data{{"t", 1, {0, 0.1, 0.2, 0.3}, false}};
  const std::string p = scratch("segments_" + format + ".vtu");
  write_vtu_segments(p, points, segments, cell_data, point_data, Vtu_options{binary});
  const auto v = read_vtu(p);
  check_grid(v, points, segments, 3, format);
  for (const Vtu_array& a : cell_data) check_array(v.cell_data, a, format);
  for (const Vtu_array& a : point_data) check_array(v.point_data, a, format);

  // Without data arrays.
  write_vtu_segments(p, points, segments, {}, {}, Vtu_options{binary});
  const auto bare = read_vtu(p);
  check_grid(bare, points, segments, 3, format);
  CHECK(bare.cell_data.empty());
  CHECK(bare.point_data.empty());
}

TEST_CASE("VTU empty grids are valid files", "[vtu]") {
  const bool binary = GENERATE(true, false);
  const std::string format = binary ? "binary" : "ascii";
  INFO(format);
  const std::string p = scratch("empty_" + format + ".vtu");

  // No points, no cells, one empty array of each section.
  write_vtu_tetrahedra(p, {}, {}, {{"quality", 1, {}, false}}, {{"size", 3, {}, false}}, Vtu_options{binary});
  const auto v = read_vtu(p);
  check_grid(v, Points{}, std::vector<std::array<std::size_t, 4>>{}, 10, format);
  REQUIRE(v.cell_data.count("quality") == 1);
  CHECK(v.cell_data.at("quality").values.empty());
  REQUIRE(v.point_data.count("size") == 1);
  CHECK(v.point_data.at("size").components == 3);
  CHECK(v.point_data.at("size").values.empty());
  if (binary) // an empty binary array is the base64 of its 8-byte zero byte count
    CHECK(slurp(p).find(">\n          AAAAAAAAAAA=\n        </DataArray>") != std::string::npos);

  // Points but no segments.
  const Points points{{1, 2, 3}, {4, 5, 6}};
  write_vtu_segments(p, points, {}, {}, {{"id", 1, {0, 1}, true}}, Vtu_options{binary});
  const auto w = read_vtu(p);
  check_grid(w, points, std::vector<std::array<std::size_t, 2>>{}, 3, format);
  CHECK(w.point_data.at("id").values == std::vector<double>{0, 1});
}

TEST_CASE("VTU binary keeps NaN and infinities, ASCII refuses them", "[vtu]") {
  const Two_tets m;
  const std::vector<Vtu_array> cells{{"error", 1, {not_a_number, -infinity}, false}};
  const std::string p = scratch("nan.vtu");
  write_vtu_tetrahedra(p, m.points, m.tets, cells);
  const auto v = read_vtu(p);
  const auto& e = v.cell_data.at("error").values;
  REQUIRE(e.size() == 2);
  CHECK(std::isnan(e[0]));
  CHECK(e[1] == -infinity);
  CHECK(same_bits(e, cells[0].values));

  expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells, {}, Vtu_options{false}); },
                 "cell data array 'error': value 0 is NaN");
}

TEST_CASE("VTU bad input throws naming the path and leaves the existing file", "[vtu]") {
  const Two_tets m;
  const std::string p = scratch("bad input.vtu");

  SECTION("cell data size mismatch") {
    auto cells = m.cell_data;
    cells[2].values.pop_back();
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells, m.point_data); },
                   "cell data array 'frame' has 17 values, expected 2 tetrahedra x 9 components = 18");
  }
  SECTION("point data size mismatch") {
    auto points = m.point_data;
    points[0].values.push_back(1);
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, m.cell_data, points); },
                   "point data array 'size' has 6 values, expected 5 points x 1 components = 5");
  }
  SECTION("vertex index out of range") {
    auto tets = m.tets;
    tets[1][3] = 5;
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, tets, m.cell_data, m.point_data); },
                   "tetrahedron 1 (0-based): vertex index 5 is out of range (5 points)");
  }
  SECTION("segment index out of range") {
    expect_invalid(p, [&] { write_vtu_segments(p, m.points, {{0, 1}, {2, 3}, {99, 0}}, {}); },
                   "segment 2 (0-based): vertex index 99 is out of range (5 points)");
  }
  SECTION("non-finite point") {
    auto points = m.points;
    points[3][1] = not_a_number;
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, points, m.tets, {}); },
                   "point 3 (0-based) has a non-finite coordinate");
  }
  SECTION("integer array with a non-integer or out-of-range value") {
    auto cells = m.cell_data;
    cells[3].values[1] = 2.5;
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells); }, "is integer (Int32) but value 1 is 2.5");
    cells[3].values[1] = 2147483648.0;
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells); }, "but value 1 is 2147483648");
    cells[3].values[1] = not_a_number;
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells); }, "but value 1 is nan");
  }
  SECTION("names: empty, duplicate, control character; components") {
    auto cells = m.cell_data;
    cells[0].name = "";
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells); }, "a cell data array has an empty name");
    cells[0].name = "frame";
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells); }, "two cell data arrays are named 'frame'");
    cells[0].name = "a\nb";
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells); }, "the name has a control character");
    cells[0] = {"zero", 0, {}, false};
    expect_invalid(p, [&] { write_vtu_tetrahedra(p, m.points, m.tets, cells); }, "0 components (at least 1 needed)");
  }
  SECTION("a path that cannot be written") {
    const std::string q = scratch("no such directory/x.vtu");
    try {
      write_vtu_tetrahedra(q, m.points, m.tets, {});
      FAIL("no exception");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()).find(q) != std::string::npos);
    }
  }
}

TEST_CASE("VTU a larger mesh crosses the buffer and base64 chunk boundaries", "[vtu]") {
  const bool binary = GENERATE(true, false);
  INFO((binary ? "binary" : "ascii"));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Points points(20011);
  for (auto& x : points) x = {u(rng), u(rng) * 1e5, u(rng) * 1e-5};
  std::vector<std::array<std::size_t, 4>> tets(50021);
  std::uniform_int_distribution<std::size_t> vi(0, points.size() - 1);
  for (auto& t : tets) t = {vi(rng), vi(rng), vi(rng), vi(rng)};
  Vtu_array frame{"frame", 9, std::vector<double>(9 * tets.size()), false};
  for (double& x : frame.values) x = u(rng);
  Vtu_array label{"label", 1, std::vector<double>(tets.size()), true};
  for (std::size_t i = 0; i < tets.size(); ++i) label.values[i] = static_cast<double>(i % 1000) - 500;
  const std::string p = scratch(binary ? "large_binary.vtu" : "large_ascii.vtu");
  write_vtu_tetrahedra(p, points, tets, {frame, label}, {}, Vtu_options{binary});
  const auto v = read_vtu(p);
  check_grid(v, points, tets, 10, binary ? "binary" : "ascii");
  check_array(v.cell_data, frame, binary ? "binary" : "ascii");
  check_array(v.cell_data, label, binary ? "binary" : "ascii");
}

// Not run by default: `test_output_files "[.perf]"`, 10^6 tetrahedra.
TEST_CASE("VTU write time for a million tetrahedra", "[.perf]") {
  const std::size_t nt = 1000000, np = 170000;
  Points points(np);
  for (std::size_t i = 0; i < np; ++i) points[i] = {double(i % 97), double(i % 89) * 0.5, double(i) * 1e-3};
  std::vector<std::array<std::size_t, 4>> tets(nt);
  for (std::size_t t = 0; t < nt; ++t) tets[t] = {t % np, (t * 7 + 1) % np, (t * 13 + 2) % np, (t * 31 + 3) % np};
  Vtu_array frame{"frame", 9, std::vector<double>(9 * nt, 0.25), false};
  Vtu_array quality{"quality", 1, std::vector<double>(nt, 0.5), false};
  const std::string p = scratch("million.vtu");
  const auto t0 = std::chrono::steady_clock::now();
  write_vtu_tetrahedra(p, points, tets, {frame, quality});
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  WARN("10^6 tets + 9-component and scalar cell arrays, binary: " << s << " s, " << fs::file_size(p) / 1e6 << " MB");
  CHECK(fs::file_size(p) > 0);
}

// --- CubeCover .fra ----------------------------------------------------------

TEST_CASE(".fra: the layout CubeCover's readFrameField reads", "[fra]") {
  const Frames frames{{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0.5, -0.25, 2, 3, 4, 5, -6, 7e-20, 1e300}};
  const std::string p = scratch("layout.fra");
  write_fra(p, frames);
  CHECK(slurp(p) == "FRA 1\n"
                    "2 3 1\n"
                    "1 0 0\n"
                    "0 1 0\n"
                    "0 0 1\n"
                    "0.5 -0.25 2\n"
                    "3 4 5\n"
                    "-6 7.0000000000000001e-20 1.0000000000000001e+300\n");
  CHECK(temporary_files_left() == 0);

  write_fra(p, {});
  CHECK(slurp(p) == "FRA 1\n0 3 1\n");
  CHECK(read_fra(p).empty());
}

TEST_CASE(".fra: write then read is bit-exact", "[fra]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> e(-300, 300);
  Frames frames(1000);
  for (auto& F : frames)
    for (double& x : F) x = std::ldexp(u(rng), e(rng)); // magnitudes from 1e-90 to 1e90
  frames[0] = {-0.0, 4.9406564584124654e-324, 2.2250738585072014e-308, 1.7976931348623157e308, 0.1, 1.0 / 3, 2.0 / 3,
               -1e-300, 123456789.123456789};
  const std::string p = scratch("random.fra");
  write_fra(p, frames);
  const Frames back = read_fra(p);
  REQUIRE(back.size() == frames.size());
  CHECK(std::memcmp(back.data(), frames.data(), frames.size() * sizeof(frames[0])) == 0);
  CHECK(std::signbit(back[0][0]));
  // 2 header lines, then one line per vector.
  const std::string text = slurp(p);
  CHECK(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) == 2 + 3 * frames.size());
}

TEST_CASE(".fra: read_fra accepts what CubeCover accepts", "[fra]") {
  // Other writers' type (4, 0), fewer digits, any white space, CRLF.
  const std::string p = put_file("variants.fra", "FRA 1\r\n2 3 4\r\n"
                                                 "1.000000 0.000000 0.000000\r\n0 1 0\n0 0 1\n"
                                                 "  -0.5 0.25\t0.125 1 2 3\n\n4 5 6\n");
  const Frames f = read_fra(p);
  REQUIRE(f.size() == 2);
  CHECK(f[0] == std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1});
  CHECK(f[1] == std::array<double, 9>{-0.5, 0.25, 0.125, 1, 2, 3, 4, 5, 6});
  CHECK(read_fra(put_file("type0.fra", "FRA 1\n1 3 0\n1 2 3\n4 5 6\n7 8 9\n")).size() == 1);
}

TEST_CASE(".fra: read_fra errors name the file and the line", "[fra]") {
  const std::string good = "FRA 1\n2 3 1\n1 0 0\n0 1 0\n0 0 1\n1 0 0\n0 1 0\n0 0 1\n";
  SECTION("truncated file") {
    // The last vector cut after "0 0" on line 8, then after line 7.
    expect_fra_error(put_file("truncated.fra", good.substr(0, good.size() - 3)), 8, "frame 2",
                     "unexpected end of file: expected a frame coordinate");
    expect_fra_error(put_file("truncated_line.fra", good.substr(0, good.size() - 6)), 0, "frame 2",
                     "unexpected end of file");
  }
  SECTION("truncated in the header") {
    expect_fra_error(put_file("short_header.fra", "FRA 1\n2 3"), 2, "", "expected the frame type");
  }
  SECTION("bad first word") { expect_fra_error(put_file("bad_word.fra", "FRB 1\n0 3 1\n"), 1, "", "expected 'FRA', found 'FRB'"); }
  SECTION("a .mesh given as .fra") {
    expect_fra_error(put_file("mesh.fra", "MeshVersionFormatted 2\n"), 1, "", "not a CubeCover frame field");
  }
  SECTION("version") { expect_fra_error(put_file("v2.fra", "FRA\n2\n0 3 1\n"), 2, "", ".fra version 2"); }
  SECTION("vectors per frame") {
    expect_fra_error(put_file("vpt.fra", "FRA 1\n1 2 1\n1 0 0\n0 1 0\n"), 2, "", "2 vectors per frame");
  }
  SECTION("negative count") { expect_fra_error(put_file("neg.fra", "FRA 1\n-1 3 1\n"), 2, "", "negative number of frames"); }
  SECTION("absurd count") {
    expect_fra_error(put_file("huge.fra", "FRA 1\n1000000000000 3 1\n1 0 0\n"), 2, "", "more than the rest of the file");
  }
  SECTION("not a number") {
    const std::string t = "FRA 1\n2 3 1\n1 0 0\n0 1 0\n0 0 1\n1 0 0\nabc 1 0\n0 0 1\n"; // line 7: frame 2
    expect_fra_error(put_file("not_a_number.fra", t), 7, "frame 2", "expected a frame coordinate, found 'abc'");
  }
  SECTION("NaN") {
    expect_fra_error(put_file("nan.fra", "FRA 1\n1 3 1\n1 0 0\nnan 1 0\n0 0 1\n"), 4, "frame 1", "not finite");
  }
  SECTION("more values than the count") {
    expect_fra_error(put_file("extra.fra", good + "7\n"), 9, "", "after the last of the 2 frames");
  }
  SECTION("empty and missing files") {
    expect_fra_error(put_file("empty.fra", " \n"), 0, "", "empty");
    expect_fra_error(scratch("missing.fra"), 0, "", "cannot open");
  }
}

TEST_CASE(".fra: file names of 250 and 255 characters are written", "[fra]") {
  // The temporary file must have a name within NAME_MAX (255) whatever the target's.
  const Frames frames{{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0.5, -0.25, 2, 3, 4, 5, -6, 7e-20, 1e300}};
  for (std::size_t length : {250, 255}) {
    INFO(length);
    const std::string p = scratch(std::string(length - 4, 'f') + ".fra");
    write_fra(p, frames);
    CHECK(read_fra(p) == frames);
    write_fra(p, {}); // replaces it
    CHECK(read_fra(p).empty());
    CHECK(temporary_files_left() == 0);
  }
}

TEST_CASE(".fra: write_fra refuses non-finite frames and leaves the existing file", "[fra]") {
  const std::string p = scratch("bad.fra");
  Frames frames(3, std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1});
  frames[2][4] = infinity;
  expect_invalid(p, [&] { write_fra(p, frames); }, "the frame of tetrahedron 2 (0-based) is not finite");
}

TEST_CASE(".perm: the layout CubeCover's readFrameField reads, read back exactly", "[perm]") {
  using CGAL_ext::IO::Perm_face;
  CGAL_ext::IO::Perm_file f;
  f.tets = 5;
  f.faces = {Perm_face{0, 3, {{-2, 1, 3}}}, Perm_face{4, 1, {{3, -2, 1}}}};
  const std::string p = scratch("layout.perm");
  CGAL_ext::IO::write_perm(p, f);
  CHECK(slurp(p) == "PERM 1\n5 2 3\n0 3 -2 1 3\n4 1 3 -2 1\n");
  CHECK(temporary_files_left() == 0);
  const CGAL_ext::IO::Perm_file back = CGAL_ext::IO::read_perm(p);
  CHECK(back.tets == 5);
  REQUIRE(back.faces.size() == 2);
  for (int k = 0; k < 2; ++k) {
    CHECK(back.faces[k].tet1 == f.faces[k].tet1);
    CHECK(back.faces[k].tet2 == f.faces[k].tet2);
    CHECK(back.faces[k].p == f.faces[k].p);
  }
  // What CubeCover's own writer gives for a field without singular faces.
  CGAL_ext::IO::write_perm(p, {3, {}});
  CHECK(slurp(p) == "PERM 1\n3 0 3\n");
  CHECK(CGAL_ext::IO::read_perm(p).faces.empty());
  // Any white space, CRLF.
  const auto v = CGAL_ext::IO::read_perm(put_file("variants.perm", "PERM 1\r\n4 1\n3\r\n  2 1\t-1 -2 3\r\n"));
  REQUIRE(v.faces.size() == 1);
  CHECK(v.faces[0].p == std::array<int, 3>{-1, -2, 3});
}

TEST_CASE(".perm: read_perm errors name the file, the line and the face", "[perm]") {
  const std::string head = "PERM 1\n4 2 3\n";
  SECTION("bad first word") { expect_perm_error(put_file("word.perm", "FRA 1\n"), 1, "", "not a CubeCover face matching"); }
  SECTION("version") { expect_perm_error(put_file("v2.perm", "PERM 2\n4 0 3\n"), 1, "", ".perm version 2"); }
  SECTION("vectors per face") { expect_perm_error(put_file("vpf.perm", "PERM 1\n4 0 2\n"), 2, "", "2 vectors per face"); }
  SECTION("negative counts") {
    expect_perm_error(put_file("negt.perm", "PERM 1\n-4 0 3\n"), 2, "", "negative number of tetrahedra");
    expect_perm_error(put_file("negf.perm", "PERM 1\n4 -1 3\n"), 2, "", "negative number of faces");
  }
  SECTION("absurd count") {
    expect_perm_error(put_file("huge.perm", "PERM 1\n4 100000000000 3\n0 1 1 2 3\n"), 2, "", "more than the rest");
  }
  SECTION("tetrahedron out of range") {
    expect_perm_error(put_file("range.perm", head + "0 1 1 2 3\n2 4 1 2 3\n"), 4, "face 2", "tetrahedron index 4 is out of range");
  }
  SECTION("a face joining a tetrahedron to itself") {
    expect_perm_error(put_file("self.perm", head + "0 1 1 2 3\n2 2 1 2 3\n"), 4, "face 2", "both sides are tetrahedron 2");
  }
  SECTION("a face listed twice, in the other orientation") {
    expect_perm_error(put_file("twice.perm", head + "0 1 2 1 3\n1 0 2 1 3\n"), 4, "face 2", "listed twice");
  }
  SECTION("not a signed permutation") {
    expect_perm_error(put_file("zero.perm", head + "0 1 0 2 3\n"), 3, "face 1", "entry 0 is not one of");
    expect_perm_error(put_file("four.perm", head + "0 1 4 2 3\n"), 3, "face 1", "entry 4 is not one of");
    expect_perm_error(put_file("double.perm", head + "0 1 -2 2 3\n"), 3, "face 1", "vector 2 is the target of two");
  }
  SECTION("truncated, and more than the count") {
    expect_perm_error(put_file("cut.perm", head + "0 1 2 1 3\n1 2 2 1\n"), 0, "face 2", "unexpected end of file");
    expect_perm_error(put_file("extra.perm", head + "0 1 2 1 3\n1 2 2 1 3\n5\n"), 5, "", "after the last of the 2 faces");
  }
  SECTION("empty and missing files") {
    expect_perm_error(put_file("empty.perm", "\n"), 0, "", "empty");
    expect_perm_error(scratch("missing.perm"), 0, "", "cannot open");
  }
}

TEST_CASE(".perm: write_perm refuses bad faces and leaves the existing file", "[perm]") {
  const std::string p = scratch("bad.perm");
  using CGAL_ext::IO::Perm_face;
  expect_invalid(p, [&] { CGAL_ext::IO::write_perm(p, {3, {Perm_face{0, 3, {{1, 2, 3}}}}}); },
                 "face 0 (0-based): tetrahedron index out of range");
  expect_invalid(p, [&] { CGAL_ext::IO::write_perm(p, {3, {Perm_face{1, 1, {{1, 2, 3}}}}}); }, "both sides");
  expect_invalid(p, [&] { CGAL_ext::IO::write_perm(p, {3, {Perm_face{0, 1, {{1, 1, 3}}}}}); }, "target of two");
  expect_invalid(p, [&] { CGAL_ext::IO::write_perm(p, {3, {Perm_face{0, 1, {{2, 1, 3}}}, Perm_face{1, 0, {{2, 1, 3}}}}}); },
                 "face 1 (0-based): the face between tetrahedra 1 and 0 is listed twice");
}
