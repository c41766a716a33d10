#pragma once
// Contact between free faces of the solid (femdem.md 1c): broad phase by binning, Munjiza's potential
// between tet pairs, Coulomb friction with a tangential penalty, optional normal damping. The kernels are
// kernels/contact_broad_phase.hpp and kernels/contact_potential.hpp; this system decides who takes part,
// when to detect again, and where the forces go.
//
// Who takes part (the candidates): the two tets of every broken joint, from the step it broke (Y's rule:
// no step passes between cohesion and contact), and once the system is awake those of every damaged joint,
// from its first damage (a softening joint hinges, add_damaged_joints()); in a mesh of several bodies, every
// tet with a face on the outer boundary. In a scene of one intact body there are no candidates and the
// system does nothing but look at the fracture log's length: it wakes with the first break.
//
// Which pairs are excluded: two tets that are still tied at a point, i.e. some corner of one and some
// corner of the other are copies of one vertex of the continuous mesh (engine/mesh/mesh_conversion.hpp:
// copies tied through intact joints, or a node shared outside the fracture zone). The continuum carries
// their interaction; contact across a crack starts where the crack has separated the copies, so tets
// around a crack front (still tied around it) never push each other apart. Likewise two tets of one body
// outside the fracture zone (a node-sharing continuum does not touch itself at strains a tet survives).
// Never excluded: the two tets of a damaged or broken joint. Tied elsewhere (at the crack front), or by the
// joint itself while it softens, they would otherwise sink into each other with nothing to stop them.
//
// When to detect: at the first step with candidates, whenever candidates join, and when some candidate
// node has moved by more than buffer / 2 since the last detection (the criterion in
// contact_broad_phase.hpp): the pair list is then exact in between. Each detection carries the friction
// history of the pairs that stay over to the new list.
//
// Forces: each pair writes its own 24 corner forces (parallel over pairs, any split), then one sequential
// gather adds them to solid_node.contact_force in pair order: bitwise the same on any thread count. The
// node pass adds contact_force to the internal forces.
//
// Per-pair constants from the mesh's mean tet (volume V, face area A, edge L, density rho): normal stiffness
// of a face-to-face contact k_n = 8 p A^2 / (3 V) (both ways: p A delta / (H / 4) each, H = 3 V / A),
// tangential k_t = tangential_penalty x p L, damping eta_n = 2 xi sqrt(k_n m / 2) (critical for two tets of
// mass m = rho V on the spring k_n); each pair's eta_n is scaled by its own stiffness over k_n
// (kernels/contact_potential.hpp). The stable step estimate (stable_step below) uses each face's own V, A
// and the node masses, without the damping; damped_step() shortens a combined step for it.
#include <memory>
#include <span>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/mesh/mesh_conversion.hpp"
#include "engine/scene/scene.hpp"
#include "engine/schedule/system.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/contact_potential.hpp"

namespace rift {

struct ContactTotals {
  size_t candidates = 0, pairs = 0, touching = 0, sliding = 0;
  int64_t detections = 0;
};

// Contact penalties matched to the joints, one per tet: a tet pressed face to face into another feels
// 4 p_t / H per unit area from its side (H = 3 V / A over that face, header above), and its intact joint
// was p_j / h (h: the face's shortest edge). p_t = min over the tet's joint faces of p_j H / (8 h) gives
// each side half the joint's stiffness, so the pair is never stiffer than the joint it replaces: a joint
// that breaks under compression hands its load to a spring no stiffer than itself, and the contact does
// not shorten the step. Tets without a joint get the mean of the others. joint_penalty: p_j per joint
// material [Pa]. Needs the solid's node, tet and joint tables (with joints).
std::vector<double> matched_contact_penalties(const Store& store, std::span<const double> joint_penalty);

class ContactSystem : public System {
 public:
  // Needs the solid's tables; adds solid_node.contact_force and x_detect, solid_contact_pair,
  // solid_contact_state and the contact columns of solid_energy.
  // tet_density: 1 per tet [kg/m^3]. tet_penalty: 1 per tet [Pa] (matched_contact_penalties), used when
  // spec.penalty is absent; empty: spec.penalty must be set (the solid resolves its default).
  ContactSystem(Store& store, const ContactSpec& spec, size_t input_vertex_count,
                std::span<const double> tet_density, std::vector<double> tet_penalty = {});
  ~ContactSystem() override;
  std::string name() const override { return "contact"; }
  Access access() const override;
  void run(const StepContext& ctx) override;

  // Largest step the contact penalty is stable with (femdem.md 1d's estimate for a joint, here for two
  // tets pressed face to face), minimum over tets [s]: over all faces that may touch, over the faces of
  // joints only (whose contact replaces the joint's spring once it breaks), and over the outer faces of a
  // mesh of several bodies only.
  double stable_step() const { return stable_step_; }
  double joint_face_stable_step() const { return joint_face_stable_step_; }
  double outer_face_stable_step() const { return outer_face_stable_step_; }
  // The central difference with the explicit (lagged) contact damping: a node's fastest mode, of frequency
  // omega = 2 / dt (dt the undamped step of everything acting on it), carries the contact's damping
  // eta_n / k_n per unit contact stiffness, whose omega_c^2 is at most (2 / stable_step())^2: its damping
  // ratio is xi = (eta_n / k_n) omega_c^2 / (2 omega) <= (eta_n / k_n) dt / stable_step()^2, and the step
  // is stable for dt (sqrt(1 + xi^2) - xi) (Belytschko, Liu & Moran, Nonlinear Finite Elements, 6.2.5).
  double damped_step(double dt) const;
  // eta_n / k_n [s]: the contact damping per unit pair stiffness (0 without damping).
  double damping_time() const {
    return law_.reference_stiffness > 0 ? law_.normal_damping / law_.reference_stiffness : 0.0;
  }
  // The contact springs' stiffness on each node's row, K_n [N/m] (estimate_stable_step): of the faces of
  // joints and of the outer faces; with the other side moving too, omega_n^2 <= 2 K_n / m_n. Sized to the
  // node count.
  void node_stiffness(std::vector<double>& joint_faces, std::vector<double>& outer_faces) const;
  // The stable steps again, from the node masses as they are now (after mass scaling).
  void update_stable_step() { estimate_stable_step(); }
  const kernels::ContactLaw& law() const { return law_; }
  double buffer() const { return buffer_; }
  size_t bodies() const { return bodies_; }
  ContactTotals totals() const;

 private:
  void wake();
  bool add_new_candidates();
  bool add_damaged_joints();
  void add_candidate(int32_t tet);
  void join_joint_pair(size_t joint);
  void merge_joined_pairs(size_t before);
  bool detection_needed();
  void detect();
  void compute_forces(const StepContext& ctx);
  void clear_gathered_nodes(std::span<const kernels::ContactPair> pairs);
  void derive_constants(const ContactSpec& spec, std::span<const double> tet_density);
  void find_bodies_and_boundary_tets();
  void estimate_stable_step();

  Store& store_;
  size_t input_vertex_count_;
  kernels::ContactLaw law_;
  std::vector<double> tet_penalty_;  // p per tet [Pa]; empty: law_.penalty for all
  double buffer_ = 0.0, stable_step_ = 0.0, joint_face_stable_step_ = 0.0, outer_face_stable_step_ = 0.0;
  size_t bodies_ = 0;
  std::vector<int32_t> boundary_tets_;  // tets with a face on the outer boundary (candidates if bodies_ > 1)
  std::vector<std::pair<int32_t, int>> boundary_faces_;
  std::vector<int32_t> tet_body_;  // per tet: its body (a root input vertex)
  std::vector<uint8_t> in_zone_;   // per tet: has a joint
  // Built at the first wake (a scene that never breaks never pays for it).
  std::unique_ptr<MeshConversion> grouping_;
  size_t events_seen_ = 0;
  int64_t onsets_seen_ = 0;  // solid_joint_state.damage_onsets at the last scan for damaged joints
  bool awake_ = false, must_detect_ = false;
  std::vector<uint8_t> is_candidate_;  // per tet
  std::vector<int32_t> candidates_;    // tet ids, in the order they joined (the broad phase ignores order)
  // The two tets of every damaged or broken joint (a < b), sorted: never excluded as tied (detect()).
  std::vector<kernels::ContactPair> joined_pairs_;
  // Scratch reused between steps and detections.
  std::vector<double> lo_, hi_;
  kernels::BroadPhaseWorkspace broad_;
  std::vector<kernels::ContactPair> old_pairs_;
  std::vector<double> old_history_, partial_max_;
  std::vector<kernels::ContactStatus> partial_status_;
  kernels::ContactStatus status_;
};

}  // namespace rift
