// Typed column handles (engine/core/column_ref.hpp): a column declared once is created, looked up and
// named for access through the same ref; a lookup with the wrong width or in the wrong table throws.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "engine/core/column_ref.hpp"
#include "engine/core/error.hpp"

using namespace rift;

namespace {

constexpr ColumnRef<double, 3> kPosition{"points", "position"};
constexpr ColumnRef<double> kPositionAsScalar{"points", "position"};
constexpr ColumnRef<int32_t, 2> kPair{"points", "pair"};
constexpr ColumnRef<double, 3> kElsewhere{"others", "position"};

TEST(ColumnRef, CreatesLooksUpAndNamesTheSameColumn) {
  Store store;
  Table& points = store.add_table("points");
  kPosition.create(store);
  kPair.create(points);
  points.resize(4);
  EXPECT_EQ(kPosition.key(), "points.position");
  EXPECT_TRUE(kPosition.exists(store));
  EXPECT_FALSE(kElsewhere.exists(store));
  EXPECT_EQ(kPosition.in(store).size(), 12u);
  EXPECT_EQ(kPair.in(points).size(), 8u);
  kPosition.in(points)[5] = 2.5;
  EXPECT_EQ(points.span<double>("position")[5], 2.5);  // the same values as a lookup by name
  const Store& read_only = store;
  EXPECT_EQ(kPosition.in(read_only)[5], 2.5);
}

TEST(ColumnRef, AColumnHasOneCreator) {
  Store store;
  store.add_table("points");
  kPosition.create(store);
  EXPECT_THROW(kPosition.create(store), Error);
}

TEST(ColumnRef, TheWrongWidthOrTableIsReportedAtTheLookup) {
  Store store;
  Table& points = store.add_table("points");
  Table& others = store.add_table("others");
  kPosition.create(points);
  points.resize(2);
  try {
    kPositionAsScalar.in(points);
    FAIL() << "a 3-wide column looked up as 1 wide";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("points.position holds 3 values per row, looked up as 1"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(kPosition.in(others), Error);
  EXPECT_THROW(kElsewhere.create(points), Error);
}

}  // namespace
