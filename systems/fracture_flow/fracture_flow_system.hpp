#pragma once
// The fluid in the cracks, one step (docs/hydraulic-fracture.md). Runs after the node pass:
//   1. the network takes in the joints broken since the last step (the fracture log's new rows);
//   2. from the predicted positions: each wet triangle's mid-surface, opening and area, the vertices'
//      volumes, the corner nodes' pressure area vectors and the closure's compliance;
//   3. the flow step (every `interval` steps; in between each vertex keeps its mass and takes the pressure
//      of its own volume), with the well's source or pressure and the vents;
//   4. the closure moves the wet corner nodes for the pressure change, and writes each such node's force
//      p a into solid_node.crack_force, which the next step's node pass gathers as an external force.
// The per-triangle geometry and the per-entry closure run in fixed blocks in parallel; every sum over
// vertices or blocks is serial, in a fixed order, so the step does not depend on the thread count.
#include <cstdint>
#include <vector>

#include "engine/core/groups.hpp"
#include "engine/core/table.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/crack_pressure_closure.hpp"
#include "kernels/fracture_flow.hpp"
#include "systems/fracture_flow/network_flow.hpp"

namespace rift {

// A borehole's wall as the well (fracture_flow.injection.surfaces): one lumped network vertex that holds
// the hole's fluid, loads the wall with its pressure and feeds every crack that reaches the wall.
struct WellWall {
  std::vector<int32_t> face_nodes;  // 3 per wall face: solid nodes, the face's normal out of the rock
  std::vector<uint8_t> on_wall;     // 1 per mesh vertex: on the wall; empty: the well is a crack vertex
};

class FractureFlowSystem : public System {
 public:
  // mass_damping: the solid's (its factor enters the closure). Throws rift::Error (naming the scene key)
  // when the well's point is not at a crack vertex.
  FractureFlowSystem(Store& store, const FractureFlowSpec& spec, TimeFunction mass_damping,
                     std::vector<uint8_t> vent_vertex, WellWall wall = {});
  std::string name() const override { return "fracture_flow"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  // After a checkpoint was read: the network is rebuilt from the fracture log.
  void restored();
  // The diagnosis of the last step ("" when it went well): a failed solve or broken mass books.
  const std::string& problem() const { return problem_; }

  struct Measures {
    double well_pressure = 0, crack_volume = 0, fluid_volume = 0, wet_area = 0, crack_area = 0;
    double crack_extent = 0, front_extent = 0;  // largest distance from the well of a network vertex / of one
                                                // that holds fluid (wet or filling)
    double compression_energy = 0;              // the work that compressed the fluid from rho0
    size_t triangles = 0, wet_vertices = 0;
  };
  Measures measure() const;
  // The network's mid-surface for output: points (3 per network vertex, the mean of its triangles'
  // mid-surface corners), triangles on them, per point its table row and its mean hydraulic aperture
  // (the area-weighted mean of its corners').
  void network_geometry(std::vector<double>& points, std::vector<int32_t>& triangles,
                        std::vector<int32_t>& rows, std::vector<double>& aperture) const;
  size_t well_row() const { return well_row_; }
  const WellWall& well_wall() const { return wall_; }
  double total_mass() const;
  double specific_compression_energy(double p) const;  // [J/kg]

 private:
  void sync_network();
  void join(size_t joint);
  void add_triangle(size_t joint);
  void network_changed();
  void add_well_wall();
  bool well_is_wall() const { return !wall_.on_wall.empty(); }
  void geometry();
  void initial_fill();
  void locate_well();
  void fill_initial_cracks();
  void wall_geometry(std::span<const double> x);
  void closure_compliance(const kernels::CrackClosureNodes& closure,
                          const kernels::CrackClosureNodes& open_closure, double scale);

  // Blocks of the parallel loops: fixed sizes, so every sum is the same on any thread count.
  static constexpr size_t kTriangleGrain = 1024, kEntryGrain = 2048, kVertexGrain = 1024;
  // How many triangles or entries ahead their nodes' rows are prefetched: the wet nodes are scattered
  // over the solid's node arrays, which the hardware prefetcher does not follow.
  static constexpr size_t kPrefetchAhead = 16;

  Store& store_;
  FractureFlowSpec spec_;
  TimeFunction mass_damping_;
  WellWall wall_;
  std::vector<uint8_t> vent_row_;         // 1 per vertex row: on a vent surface
  std::vector<int32_t> wall_entry_;       // 3 per wall face: its corners' entries (the first entries)
  size_t wall_entries_ = 0;               // the wall's nodes: entries [0, wall_entries_)
  std::vector<double> wall_x0_;           // 3 per wall entry: its node's reference position
  std::vector<double> wall_area_vector_;  // 3 per wall entry, this step
  double hole_change_ = 0.0;              // the hole's volume change from the reference positions [m^3]
  NetworkFlow flow_;
  std::vector<int32_t> row_of_mesh_vertex_;  // -1 where no joint touches the vertex
  size_t well_row_ = 0;
  // The network: triangles (joints, in the order they joined) on local vertex ids.
  size_t events_seen_ = 0;
  std::vector<int32_t> joints_;        // 1 per triangle
  std::vector<int32_t> local_of_row_;  // -1 outside the network
  std::vector<int32_t> row_of_local_;
  std::vector<int32_t> triangles_;  // 3 per triangle, local ids
  // 6 per triangle: its joint's solid nodes, copied in network order so that the per-step geometry reads
  // them in a stream (the joint table's rows are scattered) and can prefetch their positions.
  std::vector<int32_t> triangle_nodes_;
  std::vector<int32_t> node_;           // the wet corner nodes (entries), each once
  std::vector<int32_t> node_vertex_;    // local vertex of each entry
  std::vector<int32_t> corner_entry_;   // 6 per triangle
  std::vector<int32_t> entry_of_node_;  // -1 for a node on no wet triangle
  // Per entry, its node's inverse mass and free components (fixed once the solid is set up), kept beside
  // the entries so the closure does not reach into the node arrays for them.
  std::vector<double> entry_inv_mass_;
  std::vector<uint8_t> entry_free_;
  // The scatters of the geometry as gathers (engine/core/groups.hpp): per vertex its triangles' corners
  // (3 t + c), per entry its faces' corners (6 t + k), per vertex its entries.
  Groups vertex_corners_, entry_corners_, vertex_entries_;
  std::vector<double> felt_;  // per entry: the pressure its node felt in the node pass
  // Per step, sized with the network.
  std::vector<double> tri_x_, aperture_, normal_, area_, volume_, compliance_, applied_, source_, fixed_;
  std::vector<double> area_vector_, open_area_vector_, opening_, now_, joining_;
  std::vector<double> floor_volume_, compliance_open_, previous_pressure_;
  std::vector<double> vertex_area_, vertex_x_;      // per local vertex: area share, position
  std::vector<double> entry_weight_, work_blocks_;  // per entry: closure weights; per block: work
  std::vector<double> pressure_, mass_, wetting_, exchanged_;
  std::vector<uint8_t> role_;
  std::string problem_;
};

}  // namespace rift
