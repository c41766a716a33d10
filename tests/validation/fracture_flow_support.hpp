#pragma once
// What the fracture-flow validation tests read from a running simulation (its fracture_flow model, a
// time-series metric of it by name), and their check of determinism and restart.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/state_hash.hpp"
#include "systems/fracture_flow/fracture_flow_model.hpp"
#include "systems/simulation.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift::validation {

inline FractureFlowModel& flow_of(Simulation& sim) {
  for (auto& m : sim.world().models)
    if (auto* f = dynamic_cast<FractureFlowModel*>(m.get())) return *f;
  throw std::runtime_error("the scene has no fracture_flow");
}

inline double metric(const std::vector<std::pair<std::string, double>>& row, const std::string& name) {
  for (const auto& [n, v] : row)
    if (n == name) return v;
  ADD_FAILURE() << "no metric " << name;
  return 0.0;
}

// The same bits (state hash) on 1, 2 and 4 threads, and after a run stopped at step `stop` and resumed
// from its checkpoint.
inline void expect_same_bits_on_threads_and_restart(const Scene& scene, int64_t stop) {
  std::string reference;
  for (int threads : {1, 2, 4}) {
    test::TempDir dir;
    const RunResult r = test::run_scene(scene, dir.path(), threads);
    ASSERT_TRUE(r.completed) << threads;
    if (threads == 1) reference = hex64(r.state_hash);
    EXPECT_EQ(hex64(r.state_hash), reference) << threads << " threads";
  }
  test::TempDir dir;
  const auto resumed = test::stop_and_resume(scene, dir.path(), 2, stop);
  ASSERT_TRUE(resumed.rest.completed);
  EXPECT_EQ(hex64(resumed.rest.state_hash), reference);
}

}  // namespace rift::validation
