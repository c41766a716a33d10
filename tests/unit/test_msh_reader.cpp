// Gmsh MSH 4.1 ASCII reader and writer, on small files the test writes itself (MSH 2.2:
// test_msh22_reader.cpp; binary files: test_msh_binary.cpp; all four formats alike and meshio's
// files: test_msh_formats.cpp).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"
#include "engine/mesh/msh_reader.hpp"
#include "tests/unit/test_msh_support.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

fs::path temp_folder() {
  const fs::path dir = fs::temp_directory_path() / ("rift_test_msh_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path path = temp_folder() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

// 1-based number of the first line containing `marker` (how the tests know which line an error is on).
int line_of(const std::string& text, const std::string& marker) {
  const size_t pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

// Three tets on sparse node tags 10..60 plus an orphan node 70 that only a point element uses.
// Tet 105 is positive; 106 and 107 are negative in the file. Volume entity 1 is physical 7 "rock",
// entity 2 is physical 9 (no name), entity 3 is in no physical group. Surface entity 1 is in physicals
// 3 "base" and 5 (no name); entity 2 in "base"; entity 3 in none.
const std::string kCube = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Comments
anything at all, even $Nodes-like words
$EndComments
$PhysicalNames
3
3 7 "rock"
2 3 "base"
1 11 "an edge"
$EndPhysicalNames
$Entities
1 1 3 3
1 0 0 0 0
1 0 0 0 1 0 0 1 11 2 1 -1
1 0 0 0 1 1 1 2 3 5 0
2 0 0 0 1 1 1 1 3 0
3 0 0 0 1 1 1 0 0
1 0 0 0 1 1 1 1 7 0
2 0 0 0 1 1 1 1 9 0
3 0 0 -1 1 1 1 0 0
$EndEntities
$Nodes
2 7 10 70
0 1 0 1
70
5 5 5
3 1 0 6
10
20
30
40
50
60
0 0 0
1 0 0
0 1 0
0 0 1
1 1 1
0 0 -1
$EndNodes
$Elements
8 8 100 107
0 1 15 1
100 70
1 1 1 1
101 10 20
2 1 2 1
102 10 20 40
2 2 2 1
103 20 50 30
2 3 2 1
104 10 30 40
3 1 4 1
105 10 20 30 40
3 2 4 1
106 20 40 30 50
3 3 4 1
107 10 20 30 60
$EndElements
$NodeData
1
"displacement"
$EndNodeData
)";

TEST(MshReader, ReadsNamesTagsAndOrientation) {
  MshReadStats stats;
  const TetMesh mesh = read_msh(write_file("cube.msh", kCube), 2.0, &stats);

  // Node 70 is used by no tet: dropped; the rest keep file order, scaled by 2.
  ASSERT_EQ(mesh.nodes.size(), 6u);
  EXPECT_EQ(mesh.nodes[0], (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(mesh.nodes[4], (std::array<double, 3>{2, 2, 2}));
  EXPECT_EQ(mesh.nodes[5], (std::array<double, 3>{0, 0, -2}));

  // 105 as is; 106 (20 40 30 50) and 107 (10 20 30 60) flipped by swapping their 2nd and 3rd nodes.
  ASSERT_EQ(mesh.tets.size(), 3u);
  EXPECT_EQ(mesh.tets[0], (std::array<int32_t, 4>{0, 1, 2, 3}));
  EXPECT_EQ(mesh.tets[1], (std::array<int32_t, 4>{1, 2, 3, 4}));
  EXPECT_EQ(mesh.tets[2], (std::array<int32_t, 4>{0, 2, 1, 5}));

  // Regions by physical tag (7 "rock", 9 unnamed), then "domain" for the tet in no physical volume.
  EXPECT_EQ(mesh.region_names, (std::vector<std::string>{"rock", "volume_9", "domain"}));
  EXPECT_EQ(mesh.tet_region, (std::vector<int32_t>{0, 1, 2}));

  // Triangle 102 is in two physical surfaces: listed twice; 104 is in none: dropped.
  EXPECT_EQ(mesh.surface_names, (std::vector<std::string>{"base", "surface_5"}));
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.triangles[0], (std::array<int32_t, 3>{0, 1, 3}));
  EXPECT_EQ(mesh.triangles[1], (std::array<int32_t, 3>{0, 1, 3}));
  EXPECT_EQ(mesh.triangles[2], (std::array<int32_t, 3>{1, 4, 2}));
  EXPECT_EQ(mesh.triangle_surface, (std::vector<int32_t>{0, 1, 0}));

  EXPECT_EQ(stats.nodes_in_file, 7u);
  EXPECT_EQ(stats.unused_nodes_dropped, 1u);
  EXPECT_EQ(stats.tets, 3u);
  EXPECT_EQ(stats.flipped_tets, 2u);
  EXPECT_EQ(stats.triangles_without_surface, 1u);
  EXPECT_EQ(stats.skipped_elements, (std::vector<std::pair<int, size_t>>{{1, 1}, {15, 1}}));
}

TEST(MshReader, WithoutPhysicalGroupsEverythingIsDomain) {
  std::string text = kCube;
  const size_t from = text.find("$PhysicalNames"), to = text.find("$Nodes\n");
  text.erase(from, to - from);  // no names, no entities
  const TetMesh mesh = read_msh(write_file("bare.msh", text));
  EXPECT_EQ(mesh.region_names, (std::vector<std::string>{"domain"}));
  EXPECT_EQ(mesh.tet_region, (std::vector<int32_t>{0, 0, 0}));
  EXPECT_TRUE(mesh.surface_names.empty());
  EXPECT_TRUE(mesh.triangles.empty());
}

// Expects read_msh on `text` to throw an error on the line holding `marker`, mentioning `fragment`.
void expect_error(const std::string& name, const std::string& text, const std::string& marker,
                  const std::string& fragment) {
  const std::string path = write_file(name, text);
  const std::string where = path + ":" + std::to_string(line_of(text, marker)) + ": expected ";
  try {
    read_msh(path);
    ADD_FAILURE() << name << ": no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(where, 0), 0u) << message << "\n  should start with " << where;
    EXPECT_NE(message.find(fragment), std::string::npos) << message << "\n  should mention " << fragment;
  }
}

// The message of the rift::Error `call` throws, or "no error".
std::string test_error(auto&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const size_t pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

// MSH 4.1 and 2.2 are read (2.2 and binary files: test_msh_formats.cpp); 4.0, 3 and 1 differ in layout.
TEST(MshReader, RejectsOtherVersionsWithConversionHint) {
  for (const std::string version : {"4.0", "3.0", "2.1", "4"})
    expect_error("v" + version + ".msh", replace(kCube, "4.1 0 8", version + " 0 8"), version + " 0 8",
                 "MSH format version 4.1 or 2.2, found '" + version +
                     "'; convert it with `gmsh in.msh -save -format msh41");
  expect_error("file_type.msh", replace(kCube, "4.1 0 8", "4.1 2 8"), "4.1 2 8",
               "file type 0 (ASCII) or 1 (binary), found 2");
}

TEST(MshReader, RejectsTruncatedNodes) {
  // The block announces 6 nodes but the section ends after 5 coordinate lines.
  const std::string text = replace(kCube, "1 1 1\n0 0 -1\n$EndNodes", "1 1 1\n$EndNodes");
  expect_error("truncated.msh", text, "$EndNodes", "node coordinate");
}

TEST(MshReader, RejectsMissingNodeTag) {
  const std::string text = replace(kCube, "105 10 20 30 40", "105 10 20 30 41");
  expect_error("missing_node.msh", text, "105 10 20 30 41", "41 in element 105");
}

TEST(MshReader, RejectsCountMismatchAndMissingEnd) {
  expect_error("count.msh", replace(kCube, "2 7 10 70", "2 8 10 70"), "$EndNodes",
               "8 nodes as announced on line");
  expect_error("huge.msh", replace(kCube, "2 7 10 70", "2 7000000000 10 70"), "2 7000000000 10 70",
               "number of nodes that fits in the file's size");
  expect_error("noend.msh", replace(kCube, "$EndNodes", "$EndNode"), "$EndNode\n", "$EndNodes");
  expect_error("noend_elements.msh", replace(kCube, "$EndElements", "$Elements"), "$Elements\n$NodeData",
               "$EndElements");
}

// A second $Nodes would map its tags over the first's; Gmsh writes one of each.
TEST(MshReader, RejectsASecondNodesOrElementsSection) {
  for (const char* name : {"$Nodes", "$Elements"}) {
    const std::string section = std::string(name) + "\n";
    const std::string end = "$End" + std::string(name + 1) + "\n";
    const size_t from = kCube.find(section), to = kCube.find(end) + end.size();
    const std::string path = write_file("second.msh", kCube + kCube.substr(from, to - from));
    EXPECT_EQ(test_error([&] { read_msh(path); }),
              path + ":" + std::to_string(line_of(kCube, "$EndNodeData") + 1) + ": expected one " + name +
                  " section, found a second one");
  }
}

TEST(MshReader, RejectsNonNumericTokenAndDegenerateTet) {
  expect_error("token.msh", replace(kCube, "0 0 -1\n", "0 zero -1\n"), "0 zero -1", "'zero'");
  // Node 50 moved into the plane x + y + z = 1 of nodes 20, 30, 40: element 106 is flat.
  expect_error("flat.msh", replace(kCube, "1 1 1\n0 0 -1", "0.5 0.5 0\n0 0 -1"), "106 20 40 30 50",
               "element 106");
}

// A tet listed twice would count its volume twice; two node tags at one point leave the tets there
// unconnected. Both are refused where the second one is written, naming the first. Nodes that no tet uses
// (node 70, a point element's) may coincide with anything.
TEST(MshReader, RejectsDuplicateTetsAndCoincidentNodes) {
  const std::string twice = replace(replace(kCube, "8 8 100 107", "8 9 100 108"), "3 1 4 1\n105 10 20 30 40",
                                    "3 1 4 2\n105 10 20 30 40\n108 30 20 10 40");
  expect_error("duplicate_tet.msh", twice, "108 30 20 10 40", "the four nodes of element 105");
  expect_error("coincident.msh", replace(kCube, "1 1 1\n0 0 -1", "1 1 1\n1 1 1.0"), "1 1 1.0",
               "where node 50");
  EXPECT_NO_THROW(read_msh(write_file("point_node.msh", replace(kCube, "5 5 5", "0 0 0"))));
}

TEST(MshReader, RejectsUnterminatedUnknownSection) {
  const std::string text = replace(kCube, "$EndNodeData\n", "");
  expect_error("unterminated.msh", text, "$NodeData", "$EndNodeData");
}

TEST(MshReader, AFileThatIsNoMeshIsRefusedWithoutQuotingIt) {
  // mesh.file may name any file (a typo, /etc/passwd): the message must not carry its content.
  for (const std::string& text :
       {std::string("root:x:0:0:first-word second-word\nsecond-line:x:1:1\n"),
        std::string("alpha beta gamma\ndelta\n"), std::string("\x1b[2Jsecret\tword\n")}) {
    const std::string path = write_file("not_a_mesh.msh", text);
    std::string message;
    try {
      read_msh(path);
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_EQ(message, path +
                           ":1: expected a Gmsh MSH file, which starts with $MeshFormat, found a file that "
                           "does not (not a Gmsh mesh; its content is not shown)");
    for (const char* word :
         {"root", "first-word", "second-word", "second-line", "alpha", "beta", "delta", "secret", "\x1b"})
      EXPECT_EQ(message.find(word), std::string::npos) << message;
  }
}

TEST(MshReader, AFileAboveTheLimitIsRefusedBeforeItIsRead) {
  // A sparse 3 GiB file reads as 3 GiB of zeros: refused from its size alone (the message gives the size,
  // which the reader takes from the open descriptor before reading).
  const fs::path huge = temp_folder() / "huge.msh";
  { std::ofstream(huge, std::ios::binary) << "$MeshFormat\n"; }
  fs::resize_file(huge, uint64_t{3} << 30);
  std::string message;
  try {
    read_msh(huge.string());
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_EQ(message,
            huge.string() +
                ": the mesh file is 3221225472 bytes, above the limit of 2147483648 bytes (raise it with "
                "mesh.max_file_bytes)");
  fs::remove(huge);

  // The limit is the caller's; a file within it reads.
  const std::string cube = write_file("limit.msh", kCube);
  EXPECT_NE(test_error([&] {
              read_msh(cube, 1.0, nullptr, {100, "fluid.mesh.max_file_bytes"});
            }).find("bytes, above the limit of 100 bytes (raise it with fluid.mesh.max_file_bytes)"),
            std::string::npos);
  EXPECT_EQ(read_msh(cube, 1.0, nullptr, {kCube.size(), "mesh.max_file_bytes"}).tets.size(), 3u);

  // Not a regular file: refused without reading (a FIFO would block, /dev/zero never ends).
  const fs::path fifo = temp_folder() / "fifo.msh";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : {fifo.string(), std::string("/dev/zero"), temp_folder().string()})
    EXPECT_NE(test_error([&] { read_msh(path); }).find(path + ": the mesh file is not a regular file"),
              std::string::npos)
        << path;
  fs::remove(fifo);
}

TEST(MshReader, HundredThousandPhysicalSurfacesReadInLinearTime) {
  // One tet and 100,000 surface entities, each in its own named physical surface with one triangle:
  // naming surfaces by tag must not search a list per triangle (300,000 took 56 s that way).
  constexpr int n = 100000;
  std::string text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n" + std::to_string(n + 1) + "\n";
  text += "3 1 \"rock\"\n";
  for (int i = 1; i <= n; ++i) text += "2 " + std::to_string(i + 1) + " \"s" + std::to_string(i) + "\"\n";
  text += "$EndPhysicalNames\n$Entities\n0 0 " + std::to_string(n) + " 1\n";
  for (int i = 1; i <= n; ++i) text += std::to_string(i) + " 0 0 0 1 1 1 1 " + std::to_string(i + 1) + " 0\n";
  text += "1 0 0 0 1 1 1 1 1 0\n$EndEntities\n";
  text += "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n";
  text += "$Elements\n" + std::to_string(n + 1) + " " + std::to_string(n + 1) + " 1 " +
          std::to_string(n + 1) + "\n";
  text += "3 1 4 1\n1 1 2 3 4\n";
  for (int i = 1; i <= n; ++i)
    text += "2 " + std::to_string(i) + " 2 1\n" + std::to_string(i + 1) + " 1 3 2\n";
  text += "$EndElements\n";
  const TetMesh mesh = read_msh(write_file("many_surfaces.msh", text));
  ASSERT_EQ(mesh.surface_names.size(), static_cast<size_t>(n));
  ASSERT_EQ(mesh.triangles.size(), static_cast<size_t>(n));
  EXPECT_EQ(mesh.region_names, std::vector<std::string>{"rock"});
  for (const int i : {0, 1, n / 2, n - 1}) {
    EXPECT_EQ(mesh.surface_names[i], "s" + std::to_string(i + 1));
    EXPECT_EQ(mesh.triangle_surface[i], i);
  }
}

// The error message of read_msh(path) through a window of `window` bytes, or "no error" when it reads.
std::string error_through_window(const std::string& path, size_t window) {
  return test_error([&] {
    read_msh(path, 1.0, nullptr, {msh_default_max_bytes, "mesh.max_file_bytes"}, window);
  });
}

TEST(MshReader, StreamingThroughAnyWindowGivesTheSameMeshHashAndErrors) {
  // The file is streamed through a window; tokens, quoted names, skipped lines and sections cross its
  // boundary at every offset when the window runs from 24 to 160 bytes (the longest token, $EndPhysicalNames,
  // is 17). CRLF line ends and a comment line longer than any of these windows are mixed in.
  std::string text = kCube;
  text.insert(text.find("anything at all"), std::string(500, 'x') + " $EndComments-not\n");
  size_t crlf = text.find("$EndPhysicalNames");
  text.replace(crlf - 1, 1, "\r\n");
  const std::string path = write_file("windows.msh", text);
  MshReadStats whole_stats;
  const TetMesh whole = read_msh(path, 1.0, &whole_stats);
  EXPECT_EQ(whole_stats.content_fnv1a64, fnv1a64(text.data(), text.size()));
  // Damaged copies: each must give the same message (same line) through every window.
  const std::vector<std::string> damaged = {
      text.substr(0, text.find("0 0 -1\n$EndNodes")),                            // cut in the nodes
      std::string(text).replace(text.find("$EndElements"), 12, "$EndElementz"),  // wrong closing marker
      std::string(text).replace(text.find("\"rock\""), 6, "\"rock"),             // unclosed quote
      text.substr(0, text.find("$EndComments")),                                 // unterminated section
  };
  std::vector<std::string> damaged_paths, whole_errors;
  for (size_t i = 0; i < damaged.size(); ++i) {
    damaged_paths.push_back(write_file("damaged_" + std::to_string(i) + ".msh", damaged[i]));
    whole_errors.push_back(error_through_window(damaged_paths.back(), msh_window_bytes));
    EXPECT_NE(whole_errors.back(), "no error") << i;
  }
  for (size_t window = 24; window <= 160; ++window) {
    MshReadStats stats;
    const TetMesh mesh = read_msh(path, 1.0, &stats, {msh_default_max_bytes, "mesh.max_file_bytes"}, window);
    EXPECT_EQ(mesh.nodes, whole.nodes) << window;
    EXPECT_EQ(mesh.tets, whole.tets) << window;
    EXPECT_EQ(mesh.tet_region, whole.tet_region) << window;
    EXPECT_EQ(mesh.region_names, whole.region_names) << window;
    EXPECT_EQ(mesh.triangles, whole.triangles) << window;
    EXPECT_EQ(mesh.triangle_surface, whole.triangle_surface) << window;
    EXPECT_EQ(mesh.surface_names, whole.surface_names) << window;
    EXPECT_EQ(stats.content_fnv1a64, whole_stats.content_fnv1a64) << window;
    EXPECT_EQ(stats.skipped_elements, whole_stats.skipped_elements) << window;
    for (size_t i = 0; i < damaged.size(); ++i)
      EXPECT_EQ(error_through_window(damaged_paths[i], window), whole_errors[i]) << window << " " << i;
  }
}

TEST(MshReader, ATokenLongerThanTheWindowIsRefused) {
  // Memory is bounded by the window: a 100-digit coordinate through a 32-byte window is an error that
  // names the window, not a growing buffer.
  std::string text = kCube;
  text.replace(text.find("5 5 5"), 1, std::string(100, '5'));
  const std::string path = write_file("long_token.msh", text);
  EXPECT_NE(error_through_window(path, 32).find(":" + std::to_string(line_of(text, "555")) +
                                                ": expected a token or quoted string of at most 32 bytes, "
                                                "found a longer one"),
            std::string::npos)
      << error_through_window(path, 32);
  EXPECT_EQ(error_through_window(path, 128), "no error");
}

TEST(MshWriter, RoundTripGivesTheSameMesh) {
  TetMesh mesh = read_msh(write_file("cube_rt.msh", kCube), 1e-3);
  mesh.nodes[1][0] = 0.1 + 0.2;  // not exactly representable in few digits: must still round-trip
  const std::string path = (temp_folder() / "written.msh").string();
  write_msh(mesh, path);
  test::expect_same_mesh(read_msh(path), mesh);
}

TEST(MshWriter, RoundTripKeepsInterleavedGroupsInOrder) {
  TetMesh mesh;
  mesh.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  mesh.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}, {0, 3, 1, 4}};
  mesh.region_names = {"a", "b"};
  mesh.tet_region = {1, 0, 1};  // three runs: three element blocks
  mesh.surface_names = {"s"};
  mesh.triangles = {{0, 1, 2}};
  mesh.triangle_surface = {0};
  const std::string path = (temp_folder() / "interleaved.msh").string();
  write_msh(mesh, path);
  const TetMesh back = read_msh(path);
  EXPECT_EQ(back.tets, mesh.tets);
  EXPECT_EQ(back.tet_region, mesh.tet_region);
  EXPECT_EQ(back.region_names, mesh.region_names);
}

}  // namespace
}  // namespace rift
