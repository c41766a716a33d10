#pragma once
// The solid: builds its tables from a mesh and the scene's solid section, and owns the systems that
// advance it (surface loads, tet forces, joint forces, node integration). Inside the scene's fracture
// zone every tet has its own nodes and 6-node joints tie neighbours together; outside it tets share
// nodes and no joints exist. Without a fracture section the whole mesh is continuous.
//
// Member definitions are split by concern: solid_model.cpp (assembly, step limit, health, summary),
// solid_model_setup.cpp (nodes, tets, materials, boundaries, force slots, mass), solid_model_joints.cpp
// (joint table, joint materials, in-situ state, initial cracks, contact) and solid_model_output.cpp (fields,
// metrics, logs).
#include <functional>
#include <memory>

#include "engine/core/table.hpp"
#include "engine/mesh/discontinuous_mesh.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "engine/model.hpp"
#include "engine/scene/scene.hpp"
#include "kernels/stable_step.hpp"
#include "systems/contact_system.hpp"
#include "systems/joint_force_system.hpp"
#include "systems/node_integration_system.hpp"
#include "systems/surface_load_system.hpp"
#include "systems/tet_force_system.hpp"

namespace rift {

// Energies of the solid at one instant [J]; see docs/architecture.md "Energy balance".
struct SolidEnergies {
  double kinetic = 0, elastic = 0, joint_stored = 0, damping = 0, fracture = 0, external_work = 0;
  // What joints stored when they broke (the compression branch's 1/2 sigma_n o in mode II under
  // compression): it leaves their books with their forces, and is not fracture's; the contact that takes
  // the faces over starts its own books from the overlap (without contact the model drops it).
  double break_release = 0;
  // Contact: dissipated by friction and normal damping (from the contact kernel), and stored in the
  // overlaps and friction springs (the rest of what the contact forces took). A contact that puts energy
  // in (an unstable penalty) shows as a negative stored energy, which the energy guard checks.
  double contact_stored = 0, friction = 0, contact_damping = 0;
  double balance_error() const {
    return external_work - (kinetic + elastic + joint_stored + damping + fracture + break_release +
                            contact_stored + friction + contact_damping);
  }
};

struct SolidSplit;  // systems/solid_model_share.cpp
struct SolidSplitDelete {
  void operator()(SolidSplit* split) const;
};

class SolidModel : public Model {
 public:
  // Throws rift::Error naming the scene key when the scene and the mesh disagree (unknown surface or
  // region, tets without a material, an inverted tet in the input, a zone material without fracture
  // properties, an in-situ stress beyond a joint's strength).
  SolidModel(Store& store, const TetMesh& mesh, const SolidSpec& spec);

  std::string name() const override { return "solid"; }
  double stable_dt() const override { return stable_dt_; }
  std::optional<std::string> check_health(const StepContext& after) override;
  void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) override;
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;
  void partition_work(std::vector<PartitionWork>& domains) const override;
  void write_logs(const std::filesystem::path& dir) const override;

  SolidEnergies energies() const;
  // Its systems, which the step script places (systems/step_script.cpp): the element forces (joint
  // forces and contact null when the scene has no fracture or no contact) and the node pass that gathers
  // them and integrates.
  System* surface_loads() { return loads_.get(); }
  System* tet_forces() { return tet_forces_.get(); }
  System* joint_forces() { return joint_forces_.get(); }
  System* contact() { return contact_.get(); }
  System* node_integration() { return integration_.get(); }
  // The fluid's forces on the nodes (systems/coupling): adds solid_node.fluid_force (3, zero), which the
  // node pass gathers as an external force. Before the step graph is built.
  void accept_fluid_forces();
  // The fracture flow's forces on the crack faces' nodes (systems/fracture_flow): adds
  // solid_node.crack_force (3, zero), which the node pass gathers as an external force. Before the step
  // graph is built.
  void accept_crack_fluid_forces();
  const SolidSpec& spec() const { return spec_; }
  // The scene's boundary condition behind each load index of solid_load_face.load.
  const std::vector<SolidBoundarySpec>& load_conditions() const { return load_conditions_; }
  // Adds mass to the nodes (the coupling's virtual added mass, 1 per node [kg]); inv_mass and the kinetic
  // energy at t = 0 follow. Before the first step.
  void add_node_mass(std::span<const double> extra);
  size_t joint_count() const;
  size_t broken_joint_count() const;
  // From the next step on, the solid computes only a process's share of a split run (RankHalo of
  // engine/mesh/halo_plan.hpp, planned on partition_work's solid domain with its node units): the tets and
  // joints of the share and the sum units of its own nodes. The ghosts' positions and velocities must be
  // brought in after each node pass, and the energy books and the guards' counts added over the processes;
  // until a run does so, the energy guard is off in a share. Before the step graph is built. Throws Error
  // for a scene with contact (its pairs are not split yet).
  void compute_only(const RankHalo& share);
  // A split run (systems/solid_model_share.cpp): compute_only on the share, and after each graph the
  // ghosts' exchange and the books and counts added over the ranks, so that every rank books one process's
  // bits; rank 0 gathers the rows and the fracture log before it reads the store. Contact is refused.
  void take_share(const SplitJob& job, std::span<const SplitDomain> domains) override;
  void finish_share_step(const StepContext& ctx) override;
  void gather_to_root() override;

 private:
  void build_nodes_and_tets(const DiscontinuousMesh& dm, const TetMesh& mesh);
  void assign_materials(const TetMesh& mesh);
  std::vector<uint8_t> fracture_zone(const TetMesh& mesh) const;
  void apply_initial_velocity(const TetMesh& mesh);  // before boundaries: held components override it
  void apply_boundaries(const DiscontinuousMesh& dm, const TetMesh& mesh);
  size_t hold_nodes_in_box(const SolidBoundarySpec& bc, int32_t index);  // nodes held
  void build_joints(const DiscontinuousMesh& dm);
  void set_joint_initial_state();
  void build_force_slots();
  void compute_mass_and_stable_dt();
  void check_step_outlier() const;  // refuses a mesh with a tet whose step is < 1e-4 of the median
  void create_bookkeeping_tables();
  void apply_initial_cracks(const std::vector<uint8_t>& zone);  // zone: 1 per tet, in the fracture zone
  void add_crack_faces();  // two loaded faces per joint, pressed once the joint is broken
  void build_contact(const TetMesh& mesh);
  void scale_masses();  // solid.mass_scaling_step: heavier nodes where the step is short, the per-node step
  std::optional<std::string> check_energy(const StepContext& after);
  // The order-free sum of term(r) over rows [0, rows) of a table (kernels/reproducible_sum.hpp); in a
  // split run over the rows this rank counts, added over the ranks: the same bits.
  enum class Rows { nodes, tets, joints, events };
  double total_over(Rows kind, size_t rows, const std::function<double(size_t)>& term) const;

  Store& store_;
  SolidSpec spec_;
  std::array<double, 6> initial_stress_{};
  std::vector<kernels::TetMaterial> tet_materials_;
  std::vector<kernels::JointMaterial> joint_materials_;
  std::vector<SolidBoundarySpec> velocity_conditions_, load_conditions_;
  size_t crack_face_begin_ = 0;  // loaded faces from here on are joint faces (2 per joint, in joint order)
  double stable_dt_ = 0.0, tet_stable_dt_ = 0.0, joint_stable_dt_ = 0.0;
  int64_t critical_tet_ = -1;
  kernels::MassScaling mass_scaling_;  // what solid.mass_scaling_step added (nothing when off)
  double mass0_ = 0.0;                 // the solid's mass before scaling [kg]
  size_t zone_tets_ = 0;
  size_t fused_tets_ = 0;          // tets whose forces the node pass computes (solid.fused_tet_pass)
  std::vector<uint8_t> zone_;      // 1 per tet: in the fracture zone, i.e. with nodes of its own
  std::vector<double> tet_steps_;  // 1 per tet: its stable step (exact in the zone, else h / c_p) [s]
  bool share_ = false;             // compute_only: one process's share of the solid
  std::unique_ptr<SolidSplit, SolidSplitDelete> split_;  // take_share: the job's exchange, sums and gathers
  double largest_energy_ = 0.0,
         energy_floor_ = 0.0;  // largest energy scale seen so far, for the energy guard
  std::unique_ptr<SurfaceLoadSystem> loads_;
  std::unique_ptr<TetForceSystem> tet_forces_;
  std::unique_ptr<JointForceSystem> joint_forces_;
  std::unique_ptr<ContactSystem> contact_;  // with solid.contact only
  std::unique_ptr<NodeIntegrationSystem> integration_;
  // Output scratch, reused between outputs.
  std::vector<double> displacement_, principal_, reaction_;
  std::vector<double> stress_tensor6_;  // the stress in XDMF's Tensor6 order, for output
};

}  // namespace rift
