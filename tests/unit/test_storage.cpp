// SoA tables: aligned columns, typed spans, swap-remove, and stable handles with generations.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "engine/core/aligned_buffer.hpp"
#include "engine/core/handle_map.hpp"
#include "engine/core/state_hash.hpp"
#include "engine/core/table.hpp"

using namespace rift;

TEST(Table, ColumnsAreAlignedTypedAndZeroFilled) {
  Store store;
  Table& t = store.add_table("solid_node");
  t.add<double>("x", 3);
  t.add<int32_t>("held");
  t.resize(1000);
  for (const auto& c : t.columns()) {
    EXPECT_EQ(reinterpret_cast<uintptr_t>(c->data()) % 64, 0u) << c->key();
    EXPECT_EQ(c->rows(), 1000u);
  }
  auto x = t.span<double>("x");
  EXPECT_EQ(x.size(), 3000u);
  for (double v : x) EXPECT_EQ(v, 0.0);
  EXPECT_THROW(t.span<float>("x"), Error);
  EXPECT_THROW(t.column("nope"), Error);
  EXPECT_EQ(&store.column("solid_node.x"), &t.column("x"));
  EXPECT_THROW(store.column("solid_node"), Error);
  EXPECT_THROW(t.add<double>("x"), Error);
}

TEST(Table, GrowingKeepsValues) {
  Table t("tet");
  t.add<double>("v", 2);
  t.resize(3);
  auto v = t.span<double>("v");
  for (size_t i = 0; i < v.size(); ++i) v[i] = double(i);
  t.resize(100000);
  auto w = t.span<double>("v");
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(w[i], double(i));
  EXPECT_EQ(w[6], 0.0);
}

// swap_values exchanges the values of two columns of the same shape (how a solver's step becomes the
// store's without a copy) and refuses any other shape.
TEST(Column, SwapValuesExchangesOnlyColumnsOfTheSameShape) {
  Table t("fluid_node");
  t.add<double>("velocity", 3);
  t.add<double>("pressure", 1);
  t.resize(4);
  Column spare("solver", "next_velocity", ElementType::f64, 3);
  spare.resize(4);
  for (size_t i = 0; i < 12; ++i) spare.values<double>()[i] = double(i) + 0.5;
  const double* was = spare.values<double>().data();
  t.column("velocity").swap_values(spare);
  EXPECT_EQ(t.span<double>("velocity").data(), was);  // the buffer moved, nothing was copied
  EXPECT_EQ(t.span<double>("velocity")[11], 11.5);
  for (double v : spare.values<double>()) EXPECT_EQ(v, 0.0);
  EXPECT_EQ(t.column("velocity").key(), "fluid_node.velocity");  // names stay
  EXPECT_THROW(t.column("pressure").swap_values(spare), Error);  // width
  Column rows("solver", "r", ElementType::f64, 3);
  rows.resize(5);
  EXPECT_THROW(t.column("velocity").swap_values(rows), Error);  // rows
  Column type("solver", "t", ElementType::f32, 3);
  type.resize(4);
  EXPECT_THROW(t.column("velocity").swap_values(type), Error);  // element type
}

// Blocks of 1 MiB or more take whole 2 MiB pages (aligned_buffer.cpp asks for huge pages on them): they
// are 2 MiB aligned, and growing past that size keeps the contents and zero-fills the rest, as below it.
TEST(AlignedBuffer, LargeBlocksAreHugePageAlignedAndKeepTheirContents) {
  constexpr size_t MiB = size_t{1} << 20;
  AlignedBuffer b;
  b.resize(1000);
  std::memset(b.data(), 7, 1000);
  b.resize(3 * MiB);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(b.data()) % (2 * MiB), 0u);
  EXPECT_EQ(b.capacity() % (2 * MiB), 0u);
  EXPECT_EQ(static_cast<int>(b.data()[999]), 7);
  EXPECT_EQ(static_cast<int>(b.data()[1000]), 0);
  EXPECT_EQ(static_cast<int>(b.data()[3 * MiB - 1]), 0);
  AlignedBuffer small;
  small.resize(MiB / 2);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(small.data()) % 64, 0u);
  EXPECT_LT(small.capacity(), MiB);  // small blocks are not rounded to a huge page
}

TEST(HandleMap, SwapRemoveKeepsHandlesAndDetectsStaleOnes) {
  Table t("contact");
  t.add<int32_t>("id");
  HandleMap map;
  std::vector<Handle> h;
  for (int i = 0; i < 5; ++i) {
    t.resize(i + 1);
    t.span<int32_t>("id")[i] = 100 + i;
    h.push_back(map.insert(i));
  }
  // Remove the entity of handle 1: the last row (id 104) moves into row 1.
  const uint32_t row = *map.row(h[1]);
  const size_t last = t.swap_remove(row);
  map.swap_remove(row, static_cast<uint32_t>(last));
  EXPECT_FALSE(map.row(h[1]).has_value());
  for (int i : {0, 2, 3, 4}) EXPECT_EQ(t.span<int32_t>("id")[*map.row(h[i])], 100 + i);
  // The freed slot is reused with a new generation: the old handle stays dead.
  t.resize(5);
  Handle fresh = map.insert(4);
  EXPECT_EQ(fresh.slot, h[1].slot);
  EXPECT_NE(fresh.generation, h[1].generation);
  EXPECT_FALSE(map.row(h[1]).has_value());
  EXPECT_EQ(*map.row(fresh), 4u);
  EXPECT_EQ(map.handle_at(4), fresh);
}

TEST(StateHash, ChangesWithAnyBit) {
  Store s;
  auto& t = s.add_table("a");
  t.add<double>("x");
  t.resize(10);
  const uint64_t h0 = state_hash(s);
  t.span<double>("x")[7] = 1e-300;
  EXPECT_NE(state_hash(s), h0);
}
