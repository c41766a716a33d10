// MSH 2.2 ASCII (the binary file type: test_msh_binary.cpp): its group rules (the first tag is the
// physical group, the second the entity) and the damaged files of the 4.1 tests, written by the test.
#include <gtest/gtest.h>

#include <string>

#include "engine/mesh/msh_reader.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_msh_support.hpp"

namespace rift {
namespace {

using test::TempDir;
using test::write_bytes;

const std::string kCube22 = test::write_msh22(test::cube_spec(), false);

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const size_t pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return pos == std::string::npos ? text : text.replace(pos, from.size(), to);
}

// 1-based number of the first line containing `marker`.
int line_of(const std::string& text, const std::string& marker) {
  const size_t pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

class Msh22Test : public ::testing::Test {
 protected:
  // read_msh on `text` must fail on the line holding `marker` with a message holding `fragment`.
  void expect_error(const std::string& text, const std::string& marker, const std::string& fragment) {
    expect_error_on(text, line_of(text, marker), fragment);
  }
  // The same on line `line` (the end of a file is on the line after its last newline).
  void expect_error_on(const std::string& text, int line, const std::string& fragment) {
    const std::string path = write_bytes(dir_, "case.msh", text);
    const std::string message = test::msh_error(path);
    const std::string where = path + ":" + std::to_string(line) + ": expected ";
    EXPECT_EQ(message.rfind(where, 0), 0u) << message << "\n  should start with " << where;
    EXPECT_NE(message.find(fragment), std::string::npos) << message << "\n  should mention " << fragment;
  }
  TetMesh read(const std::string& text, MshReadStats* stats = nullptr) {
    return read_msh(write_bytes(dir_, "case.msh", text), 1.0, stats);
  }
  TempDir dir_;
};

TEST_F(Msh22Test, GroupsComeFromTheFirstTagAndNamesFromPhysicalNames) {
  // Tets with physical tags 4 (named), 6 (unnamed), 0 (none) and without tags; triangles with physical 2,
  // with 0, and one in two groups (written twice, as Gmsh does); a type the reader does not know (99),
  // skipped in ASCII like any other and counted.
  const std::string text = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
3 4 "granite"
2 2 "top"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
5 1 1 1
6 0 0 -1
$EndNodes
$Elements
9
1 4 2 4 1 1 2 3 4
2 4 2 6 2 2 3 4 5
3 4 2 0 3 1 3 2 6
4 4 0 5 1 6 2
5 2 2 2 1 1 2 4
6 2 2 0 1 2 3 4
7 2 2 2 2 2 3 5
8 2 2 9 2 2 3 5
9 99 3 1 2 3 1 2 3 4 5 6
$EndElements
)";
  MshReadStats stats;
  const TetMesh mesh = read(text, &stats);
  EXPECT_EQ(mesh.region_names, (std::vector<std::string>{"granite", "volume_6", "domain"}));
  EXPECT_EQ(mesh.tet_region, (std::vector<int32_t>{0, 1, 2, 2}));
  EXPECT_EQ(mesh.surface_names, (std::vector<std::string>{"top", "surface_9"}));
  EXPECT_EQ(mesh.triangles, (std::vector<std::array<int32_t, 3>>{{0, 1, 3}, {1, 2, 4}, {1, 2, 4}}));
  EXPECT_EQ(mesh.triangle_surface, (std::vector<int32_t>{0, 0, 1}));
  EXPECT_EQ(stats.triangles_without_surface, 1u);
  EXPECT_EQ(stats.skipped_elements, (std::vector<std::pair<int, size_t>>{{99, 1}}));
  EXPECT_EQ(stats.flipped_tets, 0u);
}

TEST_F(Msh22Test, ATetInTwoPhysicalVolumesIsKeptOnceInTheFirst) {
  // Gmsh writes the element once per group, in a row; cube_spec's entity 1 is in physicals 7 and 8.
  ASSERT_NE(kCube22.find("105 4 2 7 1 10 20 30 40\n1105 4 2 8 1 10 20 30 40\n"), std::string::npos);
  const TetMesh mesh = read(kCube22);
  EXPECT_EQ(mesh.tets.size(), 3u);
  EXPECT_EQ(mesh.region_names[mesh.tet_region[0]], "rock");
  // The same record twice in one group is a tet listed twice: refused.
  expect_error(replace(kCube22, "1105 4 2 8 1", "1105 4 2 7 1"), "1105 4 2 7 1",
               "the four nodes of element 105");
  // So is a repeat that is not the next tet record.
  expect_error(replace(replace(kCube22, "1105 4 2 8 1 10 20 30 40\n", ""), "108 11",
                       "1105 4 2 8 1 10 20 30 40\n108 11"),
               "1105 4 2 8 1", "the four nodes of element 105");
}

TEST_F(Msh22Test, ATruncatedFileIsRefusedWhereItEnds) {
  expect_error(kCube22.substr(0, kCube22.find("60 0 0 -0.001") + 7), "60 0 0",
               "node coordinate (a number), found end of file");
  expect_error(kCube22.substr(0, kCube22.find("107 4 2 0 3") + 15), "107 4 2 0 3",
               "node number (an integer), found end of file");
  expect_error_on(kCube22.substr(0, kCube22.find("$EndElements")), line_of(kCube22, "$EndElements"),
                  "$EndElements, found end of file");
}

TEST_F(Msh22Test, CountsThatLieAreRefused) {
  expect_error(replace(kCube22, "$Nodes\n7\n", "$Nodes\n8\n"), "$EndNodes",
               "node number (an integer), found '$EndNodes'");
  expect_error(replace(kCube22, "$Nodes\n7\n", "$Nodes\n6\n"), "60 0 0", "$EndNodes, found '60'");
  expect_error(replace(kCube22, "$Elements\n11\n", "$Elements\n12\n"), "$EndElements",
               "element number (an integer), found '$EndElements'");
  expect_error(replace(kCube22, "$Elements\n11\n", "$Elements\n10\n"), "108 11", "$EndElements, found '108'");
  // A record with more tags than it has reads a node as a tag and the next record's number as a node.
  expect_error(replace(kCube22, "107 4 2 0 3 10 20 30 60", "107 4 3 0 3 10 20 30 60"), "107 4 3",
               "a node tag defined in $Nodes, found 108 in element 107");
}

TEST_F(Msh22Test, AnUndefinedNodeTagIsRefused) {
  expect_error(replace(kCube22, "105 4 2 7 1 10 20 30 40", "105 4 2 7 1 10 20 30 41"), "105 4 2 7 1",
               "a node tag defined in $Nodes, found 41 in element 105");
}

TEST_F(Msh22Test, DegenerateAndDuplicateTetsAndCoincidentNodesAreRefused) {
  // Node 50 into the plane of 20, 40, 30: tet 106 is flat.
  expect_error(replace(kCube22, "50 1 1 0.33333333333333331", "50 0.5 0 0.5"), "106 4 2",
               "element 106 with 6V = 0");
  expect_error(replace(replace(kCube22, "$Elements\n11\n", "$Elements\n12\n"), "108 11",
                       "109 4 2 0 3 30 20 10 40\n108 11"),
               "109 4 2",
               "element 109 with the four nodes of element 105 (line " +
                   std::to_string(line_of(kCube22, "105 4 2 7")) + ")");
  expect_error(replace(kCube22, "60 0 0 -0.001", "60 1 1 0.33333333333333331"), "60 1 1",
               "node 60 at (1, 1, 0.333333333), where node 50 (line " +
                   std::to_string(line_of(kCube22, "50 1 1")) + ") is");
}

TEST_F(Msh22Test, MissingSectionsAndHugeCountsAreRefused) {
  const size_t nodes = kCube22.find("$Nodes"), elements = kCube22.find("$Elements");
  expect_error(kCube22.substr(0, nodes) + kCube22.substr(elements), "$Elements",
               "$Nodes before $Elements, found $Elements");
  expect_error_on(kCube22.substr(0, elements), line_of(kCube22, "$Elements"),
                  "an $Elements section, found end of file");
  expect_error(replace(kCube22, "$Nodes\n7\n", "$Nodes\n7000000000\n"), "7000000000",
               "number of nodes that fits in the file's size, found 7000000000");
  expect_error(replace(kCube22, "$Elements\n11\n", "$Elements\n7000000000\n"), "7000000000",
               "number of elements that fits in the file's size, found 7000000000");
  expect_error(replace(kCube22, "105 4 2 7", "105 4 2000000000 7"), "105 4 2000000000",
               "number of tags that fits in the file's size, found 2000000000");
  expect_error(replace(kCube22, "105 4 2 7", "105 4 -2 7"), "105 4 -2", "number of tags >= 0, found -2");
  expect_error(replace(kCube22, "105 4 2 7 1 10", "105 4 2 7 1 99999999999"), "105 4 2 7",
               "node number within the range of int, found 99999999999");
}

}  // namespace
}  // namespace rift
