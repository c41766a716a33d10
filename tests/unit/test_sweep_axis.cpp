// --vary key.path=v1,v2,... as rift sweep reads it.
#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/sweep/reference_metrics.hpp"
#include "engine/sweep/sweep.hpp"

namespace rift {
namespace {

TEST(SweepAxis, SplitsValuesOnCommasOutsideBrackets) {
  const SweepAxis a = parse_sweep_axis("mesh.generate.size_max=4e-3,2e-3,1e-3");
  EXPECT_EQ(a.key, "mesh.generate.size_max");
  EXPECT_EQ(a.values, (std::vector<std::string>{"4e-3", "2e-3", "1e-3"}));
  const SweepAxis b = parse_sweep_axis("solid.boundaries[1].direction=[0,0,1],[0,1,0]");
  EXPECT_EQ(b.key, "solid.boundaries[1].direction");
  EXPECT_EQ(b.values, (std::vector<std::string>{"[0,0,1]", "[0,1,0]"}));
}

TEST(SweepAxis, RejectsMalformedText) {
  for (const char* bad : {"size_max", "=1,2", "size_max=", "size_max=1,,2"}) {
    try {
      parse_sweep_axis(bad);
      FAIL() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--vary"), std::string::npos) << e.what();
    }
  }
}

TEST(SweepAxis, RelativeError) {
  EXPECT_NEAR(relative_error(1.01, 1.0), 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(relative_error(-2.0, 0.0), 2.0);
}

}  // namespace
}  // namespace rift
