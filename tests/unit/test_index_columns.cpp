// Index columns: every int32 column of a built world says what it indexes, and a checkpoint whose
// indices point outside their targets is refused on restore, even when its checksums are right (a file
// written by something other than this run: checksums prove a file intact, not well-formed).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

std::unique_ptr<Simulation> start(const std::string& scene, const std::vector<std::string>& overrides = {}) {
  RunOptions o;
  o.progress = false;
  o.write_output = false;
  return std::make_unique<Simulation>(
      load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/" + scene, overrides), o);
}

TEST(IndexColumns, EveryInt32ColumnOfAWorldDeclaresWhatItIndexes) {
  // Scenes that between them build every table: the solid with joints, loads and held nodes, contact,
  // the fracture flow, the adaptive fluid.
  for (const char* scene : {"examples/quickstart.yaml", "validation/contact_incline.yaml",
                            "examples/hydraulic_fracture.yaml", "validation/immersed_block_adaptive.yaml"}) {
    const auto sim = start(scene);
    size_t declared = 0;
    for (const auto& table : sim->world().store.tables())
      for (const auto& column : table->columns()) {
        if (column->type() != ElementType::i32) continue;
        EXPECT_TRUE(column->index_target().has_value()) << scene << ": " << column->key();
        declared += column->index_target().has_value();
      }
    EXPECT_GT(declared, 3u) << scene;
  }
}

// A store with a node table and a tet table whose nodes index it, in the shape a world has.
void build(Store& store) {
  Table& nodes = store.add_table("node");
  nodes.add<double>("x", 3);
  nodes.add<int32_t>("held").indexes(IndexTarget::list_of(2).or_none());
  nodes.add<int32_t>("slots", 2).indexes(IndexTarget::rows_of("slot").or_end());
  Table& tets = store.add_table("tet");  // listed after "node" and indexing it
  tets.add<int32_t>("nodes", 4).indexes(IndexTarget::rows_of("node"));
  tets.add<int64_t>("material").indexes(IndexTarget::list_of(3));
  store.add_table("slot").add<int32_t>("slot");
  store.table("node").resize(5);
  store.table("tet").resize(2);
  store.table("slot").resize(7);
}

// The message of restoring a checkpoint written from `store` after `forge` changed it, or "restored".
std::string restore_after(void (*forge)(Store&)) {
  test::TempDir dir;
  Store written;
  build(written);
  auto nodes = written.table("tet").span<int32_t>("nodes");
  for (size_t i = 0; i < nodes.size(); ++i) nodes[i] = static_cast<int32_t>(i % 5);
  auto held = written.table("node").span<int32_t>("held");
  std::fill(held.begin(), held.end(), -1);
  held[3] = 1;
  auto slots = written.table("node").span<int32_t>("slots");
  for (size_t i = 0; i < slots.size(); ++i) slots[i] = static_cast<int32_t>(std::min<size_t>(i, 7));
  forge(written);
  write_checkpoint(dir / "c.h5", written, CheckpointMeta{});  // right checksums for the forged values
  Store restored;
  build(restored);
  try {
    read_checkpoint(dir / "c.h5", restored);
  } catch (const Error& e) {
    return e.what();
  }
  return "restored";
}

TEST(IndexColumns, ACheckpointWithAnIndexOutOfItsTargetIsRefused) {
  EXPECT_EQ(restore_after([](Store&) {}), "restored");  // -1 where none is allowed, range ends at 7
  const std::string tail = " (the file passes its checksums, so it was written wrong, not damaged later)";
  const std::string tet = restore_after([](Store& s) { s.table("tet").span<int32_t>("nodes")[6] = 5; });
  EXPECT_NE(tet.find(": column 'tet.nodes' holds 5 at row 1, which is no index into 5 rows of node" + tail),
            std::string::npos)
      << tet;
  const std::string negative = restore_after([](Store& s) { s.table("tet").span<int32_t>("nodes")[0] = -1; });
  EXPECT_NE(negative.find("column 'tet.nodes' holds -1 at row 0"), std::string::npos) << negative;
  const std::string none = restore_after([](Store& s) { s.table("node").span<int32_t>("held")[4] = -2; });
  EXPECT_NE(none.find("column 'node.held' holds -2 at row 4, which is no index into a list of 2 entries, or "
                      "-1 for none"),
            std::string::npos)
      << none;
  const std::string range = restore_after([](Store& s) { s.table("node").span<int32_t>("slots")[9] = 8; });
  EXPECT_NE(range.find("column 'node.slots' holds 8 at row 4, which is no index into 7 rows of slot, or the "
                       "end of a range"),
            std::string::npos)
      << range;
  const std::string wide =
      restore_after([](Store& s) { s.table("tet").span<int64_t>("material")[1] = int64_t{1} << 40; });
  EXPECT_NE(wide.find("column 'tet.material' holds 1099511627776 at row 1"), std::string::npos) << wide;
}

TEST(IndexColumns, OnlyIntegerColumnsIndex) {
  Store store;
  EXPECT_THROW(store.add_table("t").add<double>("x").indexes(IndexTarget::list_of(1)), Error);
}

}  // namespace
}  // namespace rift
