// Once a run is in steady state a step allocates nothing on the C++ heap: systems size their scratch
// at set-up. Counted through a replaced global operator new (oneTBB's own task pool is outside it, as
// is the output path, which this test switches off).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"
#include "tests/unit/test_allocation_counter.hpp"

TEST(SteadyState, StepsAllocateNothing) {
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  rift::RunOptions o;
  o.write_output = false;
  o.progress = false;
  for (int threads : {1, 2}) {
    o.threads = threads;
    rift::Simulation sim(rift::load_scene(path), o);
    for (int i = 0; i < 20; ++i) sim.step_once();  // warm-up
    const long before = allocations.load();
    for (int i = 0; i < 200; ++i) sim.step_once();
    EXPECT_EQ(allocations.load() - before, 0) << threads << " thread(s)";
  }
}
