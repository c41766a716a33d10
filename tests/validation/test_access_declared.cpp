// Every system changes only what its access() declares (engine/schedule/access_check.hpp): the scenes
// below, small and short, each cover a configuration of models (dry and jointed solids with fracture,
// contact, crack pressure, the fracture-flow network with its well and vents, the fluid alone, the coupled
// fluid with and without an adaptive mesh and a network inlet), run with RunOptions::check_access.
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/simulation.hpp"

namespace rift {
namespace {

struct Case {
  std::string scene;  // under scenes/
  std::vector<std::string> overrides;
  int steps;
  // What the run must have exercised: this table has at least one row at the end ("" for nothing).
  std::string grown_table = "";
};

void run_checked(const Case& c) {
  SCOPED_TRACE(c.scene);
  spdlog::set_level(spdlog::level::warn);
  RunOptions o;
  o.write_output = false;
  o.progress = false;
  o.check_access = true;
  Simulation sim(load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/" + c.scene, c.overrides), o);
  try {
    for (int i = 0; i < c.steps && sim.step() < sim.total_steps(); ++i) sim.step_once();
  } catch (const Error& e) {
    FAIL() << e.what();
  }
  if (!c.grown_table.empty()) {
    EXPECT_GT(sim.world().store.table(c.grown_table).size(), 0u) << c.grown_table;
  }
}

TEST(AccessDeclared, SolidScenes) {
  for (const Case& c : std::vector<Case>{
           {"validation/single_joint_mode_I.yaml", {}, 30000, "solid_fracture_event"},  // it breaks
           {"validation/contact_collision.yaml", {}, 200, "solid_contact_pair"},
           {"validation/sneddon_plane_strain.yaml", {}, 50},
           {"examples/brazilian_disc.yaml", {"mesh.generate.size_max=0.008"}, 100},
           {"validation/contact_incline.yaml", {}, 200, "solid_contact_pair"},
           {"validation/contact_cut_column.yaml", {}, 100},
           {"validation/notch_pressure_ramp.yaml", {}, 100},
           {"validation/in_situ_block.yaml", {}, 50},
       })
    run_checked(c);
}

TEST(AccessDeclared, FractureFlowScenes) {
  for (const Case& c : std::vector<Case>{
           {"validation/sneddon_injection.yaml", {}, 100},
           {"validation/vent_slot.yaml", {}, 100},
           {"examples/hydraulic_fracture.yaml", {}, 200},
           {"validation/borehole_breakdown.yaml", {}, 100},
           {"validation/kgd_toughness.yaml", {}, 100},
       })
    run_checked(c);
}

TEST(AccessDeclared, FluidScenes) {
  for (const Case& c : std::vector<Case>{
           {"examples/cavity.yaml", {}, 5},
           {"validation/hydrostatic_box.yaml", {}, 5},
           {"validation/poiseuille.yaml", {}, 5},
           {"validation/immersed_block.yaml", {}, 60},
           {"validation/immersed_block_adaptive.yaml", {}, 60},
           // The paper's wedge, coupled, with the network's inlet and the adaptive fluid mesh: two windows.
           {"examples/guo2015_wedge.yaml",
            {"mesh.generate.size_min=0.008", "mesh.generate.size_max=0.016",
             "fluid.mesh.generate.size_min=0.008", "solid.mass_scaling_step=1.0e-7"},
            60},
       })
    run_checked(c);
}

}  // namespace
}  // namespace rift
