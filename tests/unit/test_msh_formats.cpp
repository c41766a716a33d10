// The MSH reader takes 4.1 and 2.2, each ASCII or binary: one mesh written in the four formats reads as
// the same TetMesh with the same stats, through every window size; and so do the files of an independent
// writer, meshio.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "engine/core/fnv1a.hpp"
#include "engine/core/spawn.hpp"
#include "engine/core/vec3.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_msh_support.hpp"

namespace rift {
namespace {

using test::cube_spec;
using test::msh_error;
using test::msh_formats;
using test::TempDir;
using test::write_bytes;

TEST(MshFormats, OneMeshInFourFormatsReadsAsTheSameMesh) {
  TempDir dir;
  for (const auto& format : msh_formats()) {
    SCOPED_TRACE(format.name);
    const std::string bytes = format.write(cube_spec(), format.binary);
    MshReadStats stats;
    const TetMesh mesh = read_msh(write_bytes(dir, "cube.msh", bytes), 2.0, &stats);

    // Node 70 (a point element's only) is dropped; the rest keep file order, scaled by 2, to the bit.
    ASSERT_EQ(mesh.nodes.size(), 6u);
    EXPECT_EQ(mesh.nodes[0], (Vec3{0, 0, 0}));
    EXPECT_EQ(mesh.nodes[2], (Vec3{0, 2 * (0.1 + 0.2), 0}));
    EXPECT_EQ(mesh.nodes[4], (Vec3{2, 2, 2.0 / 3.0}));
    EXPECT_EQ(mesh.nodes[5], (Vec3{0, 0, -2e-3}));
    // 105 as is; 106 and 107 flipped (2nd and 3rd node swapped).
    EXPECT_EQ(mesh.tets, (std::vector<std::array<int32_t, 4>>{{0, 1, 2, 3}, {1, 2, 3, 4}, {0, 2, 1, 5}}));
    // Entity 1 is in physical volumes 7 and 8: its tet goes to the first; 8 is an empty region. In 2.2 the
    // tet is written once per group and kept once.
    EXPECT_EQ(mesh.region_names, (std::vector<std::string>{"rock", "volume_8", "volume_9", "domain"}));
    EXPECT_EQ(mesh.tet_region, (std::vector<int32_t>{0, 2, 3}));
    // Triangle 102 is in two physical surfaces: listed twice; 104 is in none: dropped.
    EXPECT_EQ(mesh.surface_names, (std::vector<std::string>{"base", "surface_5"}));
    EXPECT_EQ(mesh.triangles, (std::vector<std::array<int32_t, 3>>{{0, 1, 3}, {0, 1, 3}, {1, 4, 2}}));
    EXPECT_EQ(mesh.triangle_surface, (std::vector<int32_t>{0, 1, 0}));

    EXPECT_EQ(stats.nodes_in_file, 7u);
    EXPECT_EQ(stats.unused_nodes_dropped, 1u);
    EXPECT_EQ(stats.tets, 3u);
    EXPECT_EQ(stats.flipped_tets, 2u);
    EXPECT_EQ(stats.triangles_without_surface, 1u);
    EXPECT_EQ(stats.skipped_elements, (std::vector<std::pair<int, size_t>>{{1, 1}, {11, 1}, {15, 1}}));
    EXPECT_EQ(stats.content_fnv1a64, fnv1a64(bytes.data(), bytes.size()));
  }
}

TEST(MshFormats, EveryWindowGivesTheSameMeshHashAndErrors) {
  // A window of w bytes first ends at byte w: windows from the smallest that holds the longest token to the
  // file's size put a window boundary at every byte offset from there on, so that every token, binary
  // value and record is read across a boundary at every point of it. The smallest window is one byte more
  // than the longest token: 20 in ASCII (a coordinate of 19 bytes), 18 in binary files ($EndPhysicalNames;
  // the binary int 1 at bytes 20 - 23 is crossed too). Damaged copies must give the same message through
  // every window.
  TempDir dir;
  for (const auto& format : msh_formats()) {
    SCOPED_TRACE(format.name);
    test::MshSpec undefined = cube_spec();
    undefined.element_blocks[6].elements[0][4] = 51;  // tet 106 on an undefined node
    const std::string bytes = format.write(cube_spec(), format.binary);
    const std::string path = write_bytes(dir, "whole.msh", bytes);
    MshReadStats whole_stats;
    const TetMesh whole = read_msh(path, 1.0, &whole_stats);
    const std::vector<std::string> damaged = {
        bytes.substr(0, bytes.find("$EndNodes") - 9),          // cut in the last node
        bytes.substr(0, bytes.find("$EndElements") - 5),       // cut in the last element
        bytes.substr(0, bytes.find("$EndPhysicalNames") + 6),  // cut in a marker
        std::string(bytes).replace(bytes.find("$EndElements"), 12, "$EndElementz"),
        format.write(undefined, format.binary),
    };
    std::vector<std::string> paths, errors;
    for (size_t i = 0; i < damaged.size(); ++i) {
      paths.push_back(write_bytes(dir, "damaged_" + std::to_string(i) + ".msh", damaged[i]));
      errors.push_back(msh_error(paths.back()));
      EXPECT_NE(errors.back(), "no error") << i;
    }
    for (size_t window = format.binary ? 18 : 20; window <= bytes.size(); ++window) {
      MshReadStats stats;
      const TetMesh mesh =
          read_msh(path, 1.0, &stats, {msh_default_max_bytes, "mesh.max_file_bytes"}, window);
      test::expect_same_mesh(mesh, whole);
      EXPECT_EQ(stats.content_fnv1a64, whole_stats.content_fnv1a64) << window;
      EXPECT_EQ(stats.skipped_elements, whole_stats.skipped_elements) << window;
      EXPECT_EQ(stats.flipped_tets, whole_stats.flipped_tets) << window;
      for (size_t i = 0; i < damaged.size(); ++i)
        EXPECT_EQ(msh_error(paths[i], window), errors[i]) << window << " " << i;
    }
  }
}

// meshio writes one mesh with physical groups in MSH 2.2 and 4.1, ASCII and binary (4.1's entities come
// from gmsh:dim_tags, without which meshio writes none).
constexpr const char* kMeshioWriter = R"py(
import sys
import meshio, numpy as np
points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [0.1, 0.7, -1.3]], dtype=float)
cells = [("tetra", np.array([[0, 1, 2, 3], [1, 2, 3, 4]])), ("tetra", np.array([[0, 1, 2, 5]])),
         ("triangle", np.array([[1, 2, 4], [0, 1, 3]]))]
mesh = meshio.Mesh(points, cells,
    cell_data={"gmsh:physical": [np.array([1, 1]), np.array([2]), np.array([3, 3])],
               "gmsh:geometrical": [np.array([1, 1]), np.array([2]), np.array([1, 1])]},
    point_data={"gmsh:dim_tags": np.array([[3, 1], [3, 1], [2, 1], [3, 1], [3, 1], [3, 2]])},
    field_data={"rock": np.array([1, 3]), "clay": np.array([2, 3]), "top": np.array([3, 2])})
base = sys.argv[1]
for fmt, name in (("gmsh22", "22"), ("gmsh", "41")):
    for binary in (False, True):
        meshio.write(base + name + ("b" if binary else "a") + ".msh", mesh, file_format=fmt, binary=binary)
print("meshio", meshio.__version__)
)py";

TEST(MshFormats, MeshioFilesReadAsWritten) {
  const std::string py = python_with("meshio, numpy");
  if (py.empty())
    GTEST_SKIP()
        << "SKIP: no python3 with meshio (Debian: apt-get install python3-meshio); meshio's MSH files "
           "not read";
  TempDir dir;
  std::ofstream(dir / "write.py") << kMeshioWriter;
  ASSERT_EQ(run_program({py, (dir / "write.py").string(), (dir / "m").string()}, {}, dir / "log"), 0)
      << test::slurp(dir / "log");
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {0.1, 0.7, -1.3}};
  for (const std::string name : {"22a", "22b", "41a", "41b"}) {
    SCOPED_TRACE(name);
    MshReadStats stats;
    const TetMesh mesh = read_msh((dir / ("m" + name + ".msh")).string(), 1.0, &stats);
    // meshio's 4.1 writer orders the nodes by entity: map them back to the points put in, by coordinates.
    ASSERT_EQ(mesh.nodes.size(), points.size());
    std::vector<int32_t> input(mesh.nodes.size(), -1);
    for (size_t n = 0; n < mesh.nodes.size(); ++n) {
      const auto it = std::find(points.begin(), points.end(), mesh.nodes[n]);
      ASSERT_NE(it, points.end()) << n;
      input[n] = static_cast<int32_t>(it - points.begin());
    }
    std::vector<std::array<int32_t, 4>> tets = mesh.tets;
    for (auto& t : tets)
      for (int32_t& v : t) v = input[v];
    std::vector<std::array<int32_t, 3>> triangles = mesh.triangles;
    for (auto& t : triangles)
      for (int32_t& v : t) v = input[v];
    // The third tet is negative as written: flipped.
    EXPECT_EQ(tets, (std::vector<std::array<int32_t, 4>>{{0, 1, 2, 3}, {1, 2, 3, 4}, {0, 2, 1, 5}}));
    EXPECT_EQ(mesh.region_names, (std::vector<std::string>{"rock", "clay"}));
    EXPECT_EQ(mesh.tet_region, (std::vector<int32_t>{0, 0, 1}));
    EXPECT_EQ(mesh.surface_names, std::vector<std::string>{"top"});
    EXPECT_EQ(triangles, (std::vector<std::array<int32_t, 3>>{{1, 2, 4}, {0, 1, 3}}));
    EXPECT_EQ(mesh.triangle_surface, (std::vector<int32_t>{0, 0}));
    EXPECT_EQ(stats.flipped_tets, 1u);
    EXPECT_EQ(stats.unused_nodes_dropped, 0u);
  }
}

}  // namespace
}  // namespace rift
