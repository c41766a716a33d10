#pragma once
// A 20 x 10 x 10 mm limestone block, clamped at x = 0 and pulled at x = 20 mm by `traction` [Pa] (4e7 breaks
// joints within a few hundred steps, 1e6 keeps them whole); the fracture zone is the block beyond
// x = zone_from. With zone_from inside the block, tets with nodes of their own (which the node pass computes
// when `fused`) and tets sharing nodes lie side by side. And a simulation of such a scene with no output.
#include <memory>
#include <stdexcept>
#include <string>

#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"

namespace rift::test {

inline std::string pulled_block(bool fused, double zone_from, double traction) {
  return "scene: {name: pulled-block}\n"
         "time: {end: 1.0, safety: 0.5}\n"
         "mesh:\n  generate: {box: [0.02, 0.01, 0.01], size_min: 0.002, size_max: 0.002}\n"
         "solid:\n"
         "  fused_tet_pass: " +
         std::string(fused ? "true" : "false") +
         "\n"
         "  materials: [{name: rock, density: 2650, young: 4.0e10, poisson: 0.25, damping: 0.05,\n"
         "               fracture: {tensile_strength: 5.0e6, cohesion: 1.5e7, friction_angle: 35, G_I: 30,\n"
         "                          G_II: 300}}]\n"
         "  boundaries:\n"
         "    - {surface: xmin, type: fixed}\n"
         "    - {surface: xmax, type: traction, direction: [1, 0, 0], value: " +
         std::to_string(traction) +
         "}\n"
         "  fracture: {box_min: [" +
         std::to_string(zone_from) + ", -1, -1], box_max: [1, 1, 1]}\n";
}

inline std::unique_ptr<Simulation> quiet_simulation(const std::string& yaml, int threads) {
  auto result = read_scene_text(yaml, "pulled_block_scene", ".");
  if (!result.scene) throw std::runtime_error(result.errors.front().format());
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  o.threads = threads;
  return std::make_unique<Simulation>(std::move(*result.scene), o);
}

}  // namespace rift::test
