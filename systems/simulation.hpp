#pragma once
// A run of a scene: the engine's loop (engine/run_loop.hpp) over the world the composition root builds
// (systems/world_builder.hpp). What the CLI, the tests and the benchmarks construct.
#include "engine/run_loop.hpp"
#include "systems/world_builder.hpp"

namespace rift {

class Simulation : public RunLoop {
 public:
  Simulation(Scene scene, RunOptions options) : RunLoop(std::move(scene), std::move(options), build_world) {}
};

}  // namespace rift
