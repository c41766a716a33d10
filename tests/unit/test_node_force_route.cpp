// The one route of forces onto the solid's nodes (systems/node_force_route.hpp): the node pass reads the
// force columns of exactly the sources a scene has, in the route's order, and books their work.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/scene/load_scene.hpp"
#include "systems/node_force_route.hpp"
#include "systems/world_builder.hpp"

using namespace rift;

namespace {

// The force columns the node pass declares it reads, in its declaration's order.
std::vector<std::string> force_reads(const std::string& file, std::vector<std::string> overrides = {}) {
  auto world = build_world(load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/" + file, overrides));
  for (System* s : world->systems())
    if (s->name() == "node_integration") {
      std::vector<std::string> out;
      for (const std::string& read : s->access().reads)
        for (const NodeForceRouteEntry& e : kNodeForceRoute)
          if (read == solid::col(e.table, e.column)) out.push_back(read);
      return out;
    }
  ADD_FAILURE() << file << ": no node_integration system";
  return {};
}

std::string column_of(NodeForceSource s) {
  return solid::col(route_entry(s).table, route_entry(s).column);
}

const std::vector<std::string> kCoarseWedge = {"mesh.generate.size_min=0.008", "mesh.generate.size_max=0.012",
                                               "fluid.mesh.generate.size_min=0.008",
                                               "fluid.mesh.generate.size_max=0.012"};

TEST(NodeForceRoute, ASolidWithoutJointsGathersItsTetsAndLoadedFaces) {
  EXPECT_EQ(
      force_reads("examples/elastic_bar.yaml"),
      (std::vector<std::string>{column_of(NodeForceSource::tets), column_of(NodeForceSource::loaded_faces)}));
}

TEST(NodeForceRoute, TheDryWedgeAddsJointsCrackPressureAndContact) {
  EXPECT_EQ(
      force_reads("examples/guo2015_wedge_dry.yaml",
                  {"mesh.generate.size_min=0.008", "mesh.generate.size_max=0.012"}),
      (std::vector<std::string>{column_of(NodeForceSource::tets), column_of(NodeForceSource::joints),
                                column_of(NodeForceSource::loaded_faces), column_of(NodeForceSource::crack),
                                column_of(NodeForceSource::contact)}));
}

TEST(NodeForceRoute, TheCoupledWedgeGathersEverySourceInRouteOrder) {
  std::vector<std::string> all;
  for (const NodeForceRouteEntry& e : kNodeForceRoute) all.push_back(solid::col(e.table, e.column));
  EXPECT_EQ(force_reads("examples/guo2015_wedge.yaml", kCoarseWedge), all);
}

}  // namespace
