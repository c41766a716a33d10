// `rift partition`: a scene's split across processes as a table and as JSON, and the requests it refuses.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/unit/test_cli_support.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

TEST(CliPartition, TheBuiltInSceneSplitsIntoBalancedRanksWhoseOneRankCaseExchangesNothing) {
  test::TempDir dir;
  const fs::path json = dir / "split.json";
  const CliResult r = rift({"partition", "--ranks", "1,2,3", "--json", json.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("edge cut"), std::string::npos) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["domains"].size(), 1u);  // the quickstart has a solid only
  EXPECT_EQ(j["domains"][0]["domain"], "solid");
  const auto& partitions = j["domains"][0]["partitions"];
  ASSERT_EQ(partitions.size(), 3u);
  const auto& one = partitions[0];
  EXPECT_EQ(one["edge_cut"], 0);
  EXPECT_EQ(one["ghost_nodes_max"], 0);
  EXPECT_DOUBLE_EQ(one["efficiency"].get<double>(), 1.0);
  for (const auto& p : partitions) {
    EXPECT_EQ(p["work_total"], one["work_total"]);
    EXPECT_EQ(p["tets"], one["tets"]);
    // METIS's default tolerance is 1.03 on the weights; a part's ghost work comes on top of it.
    EXPECT_LE(p["weight_imbalance"].get<double>(), 1.05);
    EXPECT_GE(p["work_imbalance"].get<double>(), p["weight_imbalance"].get<double>() - 1e-12);
    EXPECT_GT(p["efficiency"].get<double>(), 0.0);
    EXPECT_LE(p["efficiency"].get<double>(), 1.0);
  }
  EXPECT_GT(partitions[1]["ghost_nodes_max"], 0);
}

TEST(CliPartition, AFluidSceneSplitsItsFluidMeshWithoutATimePrediction) {
  test::TempDir dir;
  const fs::path json = dir / "split.json";
  const CliResult r = rift({"partition", std::string(RIFT_SOURCE_DIR) + "/scenes/examples/cavity.yaml",
                            "--ranks", "2", "--json", json.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["domains"].size(), 1u);
  const auto& fluid = j["domains"][0];
  EXPECT_EQ(fluid["domain"], "fluid");
  EXPECT_EQ(fluid["timed"], false);
  EXPECT_EQ(fluid["node_bytes"], 8);
  const auto& two = fluid["partitions"][0];
  EXPECT_GT(two["edge_cut"], 0);
  EXPECT_LE(two["weight_imbalance"].get<double>(), 1.05);
  EXPECT_FALSE(two.contains("efficiency"));
}

TEST(CliPartition, RankCountsItCannotMeetAndANetworkWithoutBandwidthAreRefusedAndNothingIsWritten) {
  test::TempDir dir;
  const fs::path json = dir / "split.json";
  CliResult r = rift({"partition", "--ranks", "5000000", "--json", json.string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--ranks 5000000: give 1 to the solid mesh's"), std::string::npos) << r.output;
  r = rift({"partition", "--ranks", "0"});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = rift({"partition", "--ranks", "2", "--bandwidth", "0", "--json", json.string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--bandwidth above 0"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(json));
}

}  // namespace
}  // namespace rift
