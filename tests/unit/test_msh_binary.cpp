// Binary MSH files (4.1 and 2.2, file type 1), damaged in every way the ASCII tests damage theirs, plus
// what only binary files can get wrong: the endianness integer, the data size, an element type whose
// records cannot be skipped. Errors in binary data name the byte offset of the value (a line means nothing
// there); the tests find the offsets from the bytes the test wrote.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

#include "engine/mesh/msh_reader.hpp"
#include "tests/unit/test_allocation_counter.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_msh_support.hpp"

namespace rift {
namespace {

using test::cube_spec;
using test::msh_error;
using test::MshSpec;
using test::offset_of;
using test::TempDir;
using test::write_bytes;

template <class T>
std::string le(T value) {  // the test machine is little-endian, as the files are
  return std::string(reinterpret_cast<const char*>(&value), sizeof value);
}
template <class T>
std::string patched(std::string bytes, size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof value);
  return bytes;
}

// 1-based line of byte `at`, counting the newline bytes in binary data too (as an editor does).
int line_at(const std::string& bytes, size_t at) {
  return 1 + static_cast<int>(std::count(bytes.begin(), bytes.begin() + static_cast<long>(at), '\n'));
}

// The two binary formats: the writer and, for a tet's record, the bytes that start it (its tag and what
// follows it: 4.1 the first node tag, 2.2 the physical tag).
struct Binary {
  std::string name;
  std::string (*write)(const MshSpec&, bool);
  std::string record(int64_t tag, int64_t next) const {
    return name == "4.1" ? le<uint64_t>(tag) + le<uint64_t>(next)
                         : le<int>(static_cast<int>(tag)) + le<int>(static_cast<int>(next));
  }
};
const Binary kBinaries[] = {{"4.1", test::write_msh41}, {"2.2", test::write_msh22}};

class MshBinaryTest : public ::testing::Test {
 protected:
  // Writes `bytes`, reads them; the message must be exactly `expected` after the path.
  void expect_error(const std::string& bytes, const std::string& expected) {
    const std::string path = write_bytes(dir_, "case.msh", bytes);
    EXPECT_EQ(msh_error(path), path + expected);
  }
  // The same, for a message that starts with `start` after the path.
  void expect_error_start(const std::string& bytes, const std::string& start) {
    const std::string path = write_bytes(dir_, "case.msh", bytes);
    const std::string message = msh_error(path);
    EXPECT_EQ(message.rfind(path + start, 0), 0u) << message << "\n  should start with " << path + start;
  }
  TempDir dir_;
};

TEST_F(MshBinaryTest, ABigEndianFileOrAnotherEndiannessIntegerIsRefused) {
  for (const Binary& b : kBinaries) {
    SCOPED_TRACE(b.name);
    MshSpec spec = cube_spec();
    spec.one = 1 << 24;  // 1 as a big-endian machine writes it
    // "$MeshFormat\n4.1 1 8\n" is 20 bytes.
    expect_error_start(
        b.write(spec, true),
        ": byte offset 20: expected a little-endian file (the binary integer 1 reads 1), found a "
        "big-endian file (it reads 16777216); convert it with `gmsh in.msh -save -format msh41");
    spec.one = 7;
    expect_error(b.write(spec, true),
                 ": byte offset 20: expected the binary integer 1 (the endianness check), found 7");
    expect_error(b.write(cube_spec(), true).substr(0, 22),
                 ": byte offset 20: expected the binary integer 1 (the endianness check), found end of file");
  }
}

TEST_F(MshBinaryTest, ADataSizeOtherThan8IsRefused) {
  MshSpec spec = cube_spec();
  spec.data_size = 4;
  expect_error_start(
      test::write_msh41(spec, true),
      ":2: expected data size 8 (the size of a size_t in a binary MSH 4.1 file), found 4; convert it");
  expect_error_start(
      test::write_msh22(spec, true),
      ":2: expected data size 8 (the size of a double in a binary MSH 2.2 file), found 4; convert it");
}

TEST_F(MshBinaryTest, ATruncatedFileIsRefusedWhereItEnds) {
  for (const Binary& b : kBinaries) {
    SCOPED_TRACE(b.name);
    const std::string bytes = b.write(cube_spec(), true);
    // Node 60 is the last, at (0, 0, -1e-3): cut 4 bytes into its coordinates.
    const size_t x60 = offset_of(bytes, le(-1e-3)) - 16;
    expect_error(bytes.substr(0, x60 + 4),
                 ": byte offset " + std::to_string(x60) + ": expected node coordinate, found end of file");
    // Cut 12 bytes into tet 107's record.
    const size_t r107 = offset_of(bytes, b.record(107, b.name == "4.1" ? 10 : 0));
    expect_error(bytes.substr(0, r107 + 12),
                 b.name == "4.1"
                     ? ": byte offset " + std::to_string(r107 + 8) + ": expected node tag, found end of file"
                     : ": byte offset " + std::to_string(r107) +
                           ": expected an element record (number, tags, node numbers), found end of file");
    // Cut before the section's end marker.
    const size_t end = offset_of(bytes, "$EndNodes");
    expect_error(bytes.substr(0, end),
                 ":" + std::to_string(line_at(bytes, end)) + ": expected $EndNodes, found end of file");
  }
}

TEST_F(MshBinaryTest, CountsThatLieAreRefused) {
  // 4.1: the totals in the section headers are checked against the blocks.
  MshSpec more_nodes = cube_spec(), more_elements = cube_spec();
  more_nodes.announced_nodes = 8;
  more_elements.announced_elements = 10;
  std::string bytes = test::write_msh41(more_nodes, true);
  const size_t nodes_header = offset_of(bytes, "$Nodes\n") + 7;
  expect_error(bytes, ":" + std::to_string(line_at(bytes, offset_of(bytes, "$EndNodes"))) +
                          ": expected 8 nodes as announced at byte offset " +
                          std::to_string(nodes_header + 8) + ", found 7 nodes in the blocks");
  bytes = test::write_msh41(more_elements, true);
  const size_t elements_header = offset_of(bytes, "$Elements\n") + 10;
  expect_error(bytes, ":" + std::to_string(line_at(bytes, offset_of(bytes, "$EndElements"))) +
                          ": expected 10 elements as announced at byte offset " +
                          std::to_string(elements_header + 8) + ", found 9 elements in the blocks");
  // A block that announces one node fewer leaves binary data where $EndNodes must be.
  bytes = test::write_msh41(cube_spec(), true);
  const std::string block = le<int>(3) + le<int>(1) + le<int>(0) + le<uint64_t>(6);
  expect_error_start(patched(bytes, offset_of(bytes, block) + 12, uint64_t{5}), ":");
  EXPECT_NE(
      msh_error(write_bytes(dir_, "case.msh", patched(bytes, offset_of(bytes, block) + 12, uint64_t{5})))
          .find(": expected $EndNodes, found '"),
      std::string::npos);

  // 2.2: the totals are the only counts of nodes; element blocks must fit in the total.
  MshSpec fewer_nodes = cube_spec();
  fewer_nodes.announced_nodes = 6;
  bytes = test::write_msh22(fewer_nodes, true);
  EXPECT_NE(msh_error(write_bytes(dir_, "case.msh", bytes)).find(": expected $EndNodes, found '"),
            std::string::npos);
  MshSpec fewer_elements = cube_spec();
  fewer_elements.announced_elements = 5;  // a point, a line, then a block of 4 triangles
  bytes = test::write_msh22(fewer_elements, true);
  const int count_line = line_at(bytes, offset_of(bytes, "$Elements\n")) + 1;
  expect_error(bytes, ": byte offset " +
                          std::to_string(offset_of(bytes, le<int>(2) + le<int>(4) + le<int>(2))) +
                          ": expected a block of at most 3 elements (5 as announced on line " +
                          std::to_string(count_line) + ", 2 read), found a block of 4");
  MshSpec more = cube_spec();
  more.announced_elements = 12;  // one more than the 11 records: the $EndElements text is read as a header
  bytes = test::write_msh22(more, true);
  expect_error_start(bytes, ": byte offset " + std::to_string(offset_of(bytes, "\n$EndElements")) +
                                ": expected a block of at most 1 elements (12 as announced on line ");
}

TEST_F(MshBinaryTest, AnUndefinedNodeTagIsRefusedAtItsElement) {
  for (const Binary& b : kBinaries) {
    SCOPED_TRACE(b.name);
    MshSpec spec = cube_spec();
    spec.element_blocks[5].elements[0][4] = 41;  // tet 105: 10 20 30 41
    const std::string bytes = b.write(spec, true);
    expect_error(bytes, ": byte offset " +
                            std::to_string(offset_of(bytes, b.record(105, b.name == "4.1" ? 10 : 7))) +
                            ": expected a node tag defined in $Nodes, found 41 in element 105");
  }
}

TEST_F(MshBinaryTest, DegenerateAndDuplicateTetsAndCoincidentNodesAreRefused) {
  for (const Binary& b : kBinaries) {
    SCOPED_TRACE(b.name);
    const int64_t after106 = b.name == "4.1" ? 20 : 9;  // 4.1: first node; 2.2: physical group
    // Node 50 moved into the plane of 20, 40, 30: tet 106 is flat.
    MshSpec flat = cube_spec();
    flat.node_blocks[1].nodes[4].x = {0.5, 0, 0.5};
    std::string bytes = b.write(flat, true);
    expect_error_start(bytes,
                       ": byte offset " + std::to_string(offset_of(bytes, b.record(106, after106))) +
                           ": expected a tetrahedron with non-zero volume, found element 106 with 6V = 0");
    // Tet 109 has the nodes of 105 in another order.
    MshSpec twice = cube_spec();
    twice.element_blocks[7].elements.push_back({109, 30, 20, 10, 40});
    bytes = b.write(twice, true);
    expect_error(
        bytes, ": byte offset " + std::to_string(offset_of(bytes, b.record(109, b.name == "4.1" ? 30 : 0))) +
                   ": expected each tetrahedron once, found element 109 with the four nodes of element 105 "
                   "(byte offset " +
                   std::to_string(offset_of(bytes, b.record(105, b.name == "4.1" ? 10 : 7))) +
                   "); remove one of them");
    // Node 60 where node 50 is.
    MshSpec coincident = cube_spec();
    coincident.node_blocks[1].nodes[5].x = coincident.node_blocks[1].nodes[4].x;
    bytes = b.write(coincident, true);
    const std::string at = le(1.0) + le(1.0) + le(1.0 / 3.0);
    const size_t x50 = offset_of(bytes, at), x60 = bytes.find(at, x50 + 1);
    expect_error(bytes,
                 ": byte offset " + std::to_string(x60) +
                     ": expected each point once in the tets' nodes, found node 60 at (1, 1, 0.333333333), "
                     "where node 50 (byte offset " +
                     std::to_string(x50) +
                     ") is; merge them (Gmsh: Coherence) or, for a crack, use solid.fracture.initial_cracks");
  }
}

TEST_F(MshBinaryTest, MissingSectionsAreRefused) {
  for (const Binary& b : kBinaries) {
    SCOPED_TRACE(b.name);
    const std::string bytes = b.write(cube_spec(), true);
    std::string no_nodes = bytes;
    const size_t from = offset_of(no_nodes, "$Nodes\n"), to = offset_of(no_nodes, "$EndNodes\n") + 10;
    no_nodes.erase(from, to - from);
    expect_error(no_nodes, ":" + std::to_string(line_at(no_nodes, offset_of(no_nodes, "$Elements"))) +
                               ": expected $Nodes before $Elements, found $Elements");
    const std::string no_elements = bytes.substr(0, offset_of(bytes, "$Elements\n"));
    expect_error(no_elements, ":" + std::to_string(line_at(no_elements, no_elements.size())) +
                                  ": expected an $Elements section, found end of file");
  }
}

TEST_F(MshBinaryTest, AnUnknownElementTypeIsRefusedNamingIt) {
  // A binary record holds no node count: a type not in the table cannot be skipped (in ASCII it can).
  MshSpec spec = cube_spec();
  spec.element_blocks.push_back({3, 3, 99, {{110, 10, 20, 30}}});
  std::string bytes = test::write_msh41(spec, true);
  const std::string expected =
      ": expected an element type of known node count (binary records of another type cannot be skipped), "
      "found "
      "element type 99";
  expect_error(bytes, ": byte offset " +
                          std::to_string(offset_of(bytes, le<int>(3) + le<int>(3) + le<int>(99)) + 8) +
                          expected);
  bytes = test::write_msh22(spec, true);
  expect_error(bytes, ": byte offset " +
                          std::to_string(offset_of(bytes, le<int>(99) + le<int>(1) + le<int>(2))) + expected);
  // Known types of any size are skipped and counted: the 10-node tet (type 11) of cube_spec.
  for (const Binary& b : kBinaries) {
    MshReadStats stats;
    read_msh(write_bytes(dir_, "case.msh", b.write(cube_spec(), true)), 1.0, &stats);
    EXPECT_EQ(stats.skipped_elements, (std::vector<std::pair<int, size_t>>{{1, 1}, {11, 1}, {15, 1}}))
        << b.name;
  }
}

TEST_F(MshBinaryTest, HugeCountsAreRefusedBeforeTheyAllocate) {
  // Each count is far beyond what the file can hold; the largest allocation while reading stays the window's.
  const std::string b41 = test::write_msh41(cube_spec(), true), b22 = test::write_msh22(cube_spec(), true);
  const size_t nodes41 = offset_of(b41, "$Nodes\n") + 7 + 8;
  const size_t block41 = offset_of(b41, le<int>(3) + le<int>(1) + le<int>(0) + le<uint64_t>(6)) + 12;
  const size_t block22 = offset_of(b22, le<int>(4) + le<int>(4) + le<int>(2));
  MshSpec huge = cube_spec();
  huge.announced_nodes = int64_t{1} << 40;
  const std::string text_count = test::write_msh22(huge, true);
  const struct {
    std::string bytes, expected;
  } cases[] = {
      {patched(b41, nodes41, uint64_t{1} << 40),
       ": byte offset " + std::to_string(nodes41) +
           ": expected number of nodes that fits in the file's size, found 1099511627776"},
      {patched(b41, nodes41, ~uint64_t{0}),
       ": byte offset " + std::to_string(nodes41) +
           ": expected number of nodes (a size_t below 2^63), found 18446744073709551615"},
      {patched(b41, block41, uint64_t{1} << 40),
       ": byte offset " + std::to_string(block41) +
           ": expected number of nodes in block that fits in the file's size, found 1099511627776"},
      {text_count, ":" + std::to_string(line_at(text_count, offset_of(text_count, "$Nodes")) + 1) +
                       ": expected number of nodes that fits in the file's size, found 1099511627776"},
      {patched(b22, block22 + 4, 1 << 30),
       ": byte offset " + std::to_string(block22) +
           ": expected a block of at most 5 elements (11 as announced on line " +
           std::to_string(line_at(b22, offset_of(b22, "$Elements")) + 1) +
           ", 6 read), found a block of 1073741824"},
      {patched(b22, block22 + 8, 1 << 30),
       ": byte offset " + std::to_string(block22) +
           ": expected number of tags that fits in the file's size, found 1073741824"},
  };
  for (const auto& c : cases) {
    const std::string path = write_bytes(dir_, "case.msh", c.bytes);
    largest_allocation = 0;
    const std::string message = msh_error(path);
    EXPECT_LE(largest_allocation.load(), msh_window_bytes) << message;
    EXPECT_GE(largest_allocation.load(), msh_window_bytes) << "the window's allocation was not seen";
    EXPECT_EQ(message, path + c.expected);
  }
}

}  // namespace
}  // namespace rift
