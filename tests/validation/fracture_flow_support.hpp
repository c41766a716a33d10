#pragma once
// What the fracture-flow validation tests read from a running simulation: its fracture_flow model and a
// time-series metric of it by name.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "engine/simulation.hpp"
#include "systems/fracture_flow/fracture_flow_model.hpp"

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

}  // namespace rift::validation
