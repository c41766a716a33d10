#pragma once
// The two halves of the fluid-solid exchange as systems (kernels/fluid_solid_exchange.hpp has the
// formulas). The run's step is the solid's; a window of `substeps` solid steps makes one fluid step, and
// on the last step of each window (loose, sequential coupling, fluid.md 1.7):
//   1. SolidToFluidSystem: the solid at the window's end -> volume fraction, solid velocity and absorption
//      on the fluid tets (into the solver and the store);
//   2. the fluid steps (FluidStepSystem) to the window's end;
//   3. FluidToSolidSystem: the fluid's force on every solid node, held over the next window.
// Both share the window's candidate pairs and overlap volumes (ExchangePairs).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/volume_fraction.hpp"
#include "systems/fluid/fluid_solver.hpp"

namespace rift {

struct ExchangeSettings {
  int64_t substeps = 1;                // solid steps per fluid step
  double beta = 1.0;                   // absorption weight
  double rho = 0.0;                    // fluid density [kg/m^3]
  double dt = 0.0;                     // fluid step [s]
  std::array<double, 3> body_force{};  // fluid body force [N/m^3]
  double added_mass = 0.0;             // c_a (FluidSolidSpec::added_mass)
  bool dilatation = false;             // FluidSolidSpec::dilatation: the continuity source s_K
  bool fluid_continuity = false;       // FluidSolidSpec::Continuity::fluid: continuity weighted by 1 - alpha
  std::optional<std::array<double, 3>> network_inlet;  // FluidSolidSpec::network_inlet
  std::array<double, 3> network_inlet_extent{};        // FluidSolidSpec::network_inlet_extent
  bool volume_force = true;  // FluidSolidSpec::Force::volume; else only the wetted faces' pressure
  std::array<double, 3> solid_gravity{};  // solid.gravity: the virtual mass must not weigh anything
  int oscillation_lag = 1;  // fluid steps between a solid state and the force answering it (2: concurrent)
};

// Scratch of one exchange, sized once and reused (grown only when the pair count grows).
struct ExchangePairs {
  kernels::CouplingBroadPhaseWorkspace broad;
  std::vector<int32_t> fluid_ids, solid_ids;  // 0, 1, 2, ... (the box kernel takes id lists)
  std::vector<double> fluid_lo, fluid_hi, solid_lo, solid_hi;
  std::vector<double> volume, penalty, force;  // 1, 3, 3 per pair
  std::vector<int64_t> first;                  // per fluid tet + 1
  std::vector<double> pair_weight;             // per fluid tet (kernels::SolidToFluidArgs::pair_weight)
  std::vector<double> solid_velocity;          // mean velocity per solid tet
  std::vector<double> solid_dilatation;        // (dV/dt) / V per solid tet
  std::vector<double> fluid_velocity;          // mean velocity per fluid tet after the step
  // Wetted faces (solid boundaries of type fluid_pressure): rows of solid_load_face, their centroids (also
  // their zero-size boxes), the candidate fluid tets of each centroid, the sampled pressures.
  std::vector<int32_t> wet_faces;
  std::vector<double> wet_points, wet_pressure;
  kernels::CouplingBroadPhaseWorkspace wet_broad;
  size_t wet_outside = 0;  // centroids outside the fluid mesh at the last exchange (they get 0)
  // The network inlet (FluidSolidSpec::network_inlet): its fluid tets, each one's share of the fluid
  // there (summing to 1), and the pressure at the last exchange.
  kernels::CouplingBroadPhaseWorkspace inlet_broad;
  std::vector<int32_t> inlet_cells;
  std::vector<double> inlet_shares;
  double inlet_pressure = 0.0;
};

class SolidToFluidSystem : public System {
 public:
  SolidToFluidSystem(Store& store, fluid::FluidSolver& solver, ExchangeSettings settings,
                     ExchangePairs& pairs);
  std::string name() const override { return "solid_to_fluid"; }
  Access access() const override;
  void run(const StepContext& ctx) override;  // exchange(), at the end of each window
  void exchange();                            // also the initial exchange at t = 0, outside the step
  // The fluid's mesh was remade (fluid.adapt): its tet boxes and the per-tet scratch again.
  void fluid_mesh_changed();
  // Points the solver at the stored absorption, solid velocity and dilatation (it reads them in place) and
  // derives its continuity weights: after each exchange, a remesh and a restart.
  void bind_solver_inputs();
  // fluid_solid.network_inlet: the solid tets on the network's well (the notch). At every exchange they
  // mark, with the tets of the broken joints, the fluid cells the network owns (fluid_tet.network_cell):
  // those whose centre lies in the solid's box at t = 0 (the rock's envelope: its notch and cracks
  // included) or that share volume with one of those tets, but the inlet's. The notch and the cracks
  // hold the network's fluid, so there the surrounding fluid's continuity does not hold (its weight is
  // 0, as inside the solid): as the notch's walls part, the network fills the gap, not the Navier-Stokes
  // fluid of its cells (docs/coupling.md, "The fluid feeds the cracks").
  void set_network_wall(std::span<const int32_t> wall_tets);
  // After a restart of the concurrent coupling: the last exchange's pairs, from the solid's node
  // positions then (the cells' values are restored with the store).
  void rebuild_pairs(std::span<const double> x_at_exchange);

 private:
  void find_pairs(std::span<const double> x, std::span<const double> v);
  void network_sink();
  void mark_network_cells();

  Store& store_;
  fluid::FluidSolver& solver_;
  ExchangeSettings settings_;
  ExchangePairs& pairs_;
  std::vector<uint8_t> wall_tet_, network_tet_;  // per solid tet: on the well's wall; in the network
  std::array<double, 6> rock_box_{};             // the solid's box at t = 0: lo (3), hi (3)
  std::vector<uint8_t> in_rock_box_;             // per fluid tet: its centre lies in rock_box_
};

class FluidToSolidSystem : public System {
 public:
  // fluid_volume: |K| per fluid tet (the solver's), for the fluid's side of the force balance.
  FluidToSolidSystem(Store& store, ExchangeSettings settings, ExchangePairs& pairs,
                     std::span<const double> fluid_volume)
      : store_(store), settings_(settings), pairs_(pairs), fluid_volume_(fluid_volume) {}
  void set_fluid_volume(std::span<const double> fluid_volume) { fluid_volume_ = fluid_volume; }
  std::string name() const override { return "fluid_to_solid"; }
  Access access() const override;
  void run(const StepContext& ctx) override;  // exchange(), at the end of each window
  // initial: the exchange at t = 0, before the fluid has felt the solid: only the body-force part
  // (buoyancy). The absorption's reaction is not known until the fluid has stepped with it.
  void exchange(bool initial = false);
  // The virtual added mass per solid node from the current pairs, c_a rho_f (share of V_KS): into
  // solid_node.fluid_added_mass, which it creates, with solid_node.window_velocity = v.
  void set_added_mass();
  // The faces whose fluid pressure is sampled at each exchange (solid_load_face rows); creates
  // solid_load_face.fluid_pressure.
  void set_wetted_faces(std::vector<int32_t> faces);

 private:
  void sample_wetted_faces();
  void sample_network_inlet();
  void wetted_face_total(double force[3]) const;
  void add_virtual_mass_force();
  void watch_oscillation(const double force[3]);

  Store& store_;
  ExchangeSettings settings_;
  ExchangePairs& pairs_;
  std::span<const double> fluid_volume_;
};

}  // namespace rift
