#pragma once
// The coupled wedge's coarse preset (scenes/examples/guo2015_wedge.yaml: 4 / 8 mm tets, 4 mm fluid cells at
// the notch, mass scaling to a 1.5e-8 s step), with further overrides, for the tests of the paper's scene.
#include <string>
#include <vector>

#include "engine/scene/load_scene.hpp"

namespace rift::validation {

inline Scene coupled_wedge_coarse(const std::vector<std::string>& more) {
  std::vector<std::string> overrides{"mesh.generate.size_min=0.004", "mesh.generate.size_max=0.008",
                                     "fluid.mesh.generate.size_min=0.004", "solid.mass_scaling_step=1.5e-8"};
  overrides.insert(overrides.end(), more.begin(), more.end());
  return load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/examples/guo2015_wedge.yaml", overrides);
}

}  // namespace rift::validation
