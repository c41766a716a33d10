#pragma once
// The composition root: which models a scene needs, and the step they take (the script of stages in
// systems/step_script.cpp). A scene gets one model
// per physics section it has (model only what the scene requires): the solid; the fracture-flow network
// right after it (its step follows the node pass); the continuous meshes when the adaptive fluid mesh or
// an output consumes them; the fluid, on its own mesh around a solid with the coupling after it. The
// engine (engine/run_loop.hpp) runs what this builds and knows none of the models.
#include <memory>

#include "engine/scene/scene.hpp"
#include "engine/world.hpp"

namespace rift {

// Reads or generates the mesh and builds the models (a WorldBuilder). Throws rift::Error with a complete
// message.
std::unique_ptr<World> build_world(const Scene& scene);

}  // namespace rift
