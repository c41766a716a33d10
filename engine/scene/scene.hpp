#pragma once
// The typed scene: what a scene file means once it has been read, checked and completed with
// defaults. Every run, test and benchmark builds its world from one of these. SI units throughout.
// The YAML layout, units, defaults and ranges are documented in docs/scene-format.md.
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/time_function.hpp"
#include "kernels/fracture_flow.hpp"  // FluidEos

namespace rift {

// A cut into a generated box, running through the whole box along `through_axis`.
struct NotchSpec {
  enum class Shape { wedge, slot };  // wedge: opening tapers linearly to zero at the tip; slot: constant
  Shape shape = Shape::wedge;
  std::string face = "xmin";   // box face the notch opens on: xmin xmax ymin ymax zmin zmax
  int opening_axis = 1;        // axis along which the opening is measured (0 x, 1 y, 2 z)
  double center = 0.0;         // coordinate of the notch mid-plane along opening_axis [m]
  double depth = 0.0;          // distance from the face to the tip [m]
  double opening = 0.0;        // width at the face [m]
  std::string name = "notch";  // surface name of the notch faces
};

// A disc (short cylinder) for the Brazilian test: axis along z, loaded on two arcs centred on +y and -y.
struct CylinderSpec {
  double diameter = 0.0;   // [m]
  double thickness = 0.0;  // length along the axis (z) [m]
  double load_arc = 10.0;  // full angle of each loading arc [deg], 0 < load_arc < 90
};

// One block of a `blocks` mesh: a box cut into cells[0] x cells[1] x cells[2] cubes of 6 Kuhn tets each
// (engine/mesh/lattice_box.hpp). Blocks share no nodes, so each is a separate body (contact between
// them needs solid.contact); block k is mesh region `name`, its faces the surfaces `name`_xmin ... _zmax.
struct BlockSpec {
  std::string name;
  std::array<double, 3> origin{};      // lower corner [m]
  std::array<double, 3> size{};        // edge lengths [m]
  std::array<int, 3> cells{1, 1, 1};   // a Kuhn lattice of these cubes, or
  std::optional<double> element_size;  // an unstructured mesh of this element size [m] (CGAL Mesh_3)
};

// 20 million tets: about 13 GB to mesh and run an unjointed solid, most of this machine class's memory.
inline constexpr uint64_t kDefaultMaxElements = 20'000'000;

// A lattice whose cells are `size` inside the box [fine_min, fine_max] and grow by `growth` per cell
// outside it, axis by axis, up to the box's faces.
struct LatticeGradingSpec {
  std::array<double, 3> fine_min{}, fine_max{};  // [m], absolute (origin included)
  double size = 0.0;                             // cell size in the fine box [m]
  double growth = 1.25;                          // ratio of neighbouring cells outside it
};

// A box with a cylindrical hole along z through (axis_x, axis_y), an O-grid lattice graded towards the
// hole (engine/mesh/borehole_box.hpp).
struct BoreholeMeshSpec {
  double axis_x = 0.0, axis_y = 0.0;  // [m], absolute: inside the box, on a side or a corner of it
  double radius = 0.0;                // [m]
  double size = 0.0;                  // cell size at the wall [m]
  double growth = 1.0;                // ratio of neighbouring rings' radial sizes
};

struct MeshGenerateSpec {
  enum class Shape { box, cylinder, blocks };
  Shape shape = Shape::box;
  std::vector<BlockSpec> blocks;  // blocks only
  std::array<double, 3> size{};   // box: edge lengths [m]
  CylinderSpec cylinder;          // cylinder: its dimensions
  // box: lower corner; cylinder: (x, y) of the axis and z of the lower flat face [m]
  std::array<double, 3> origin{};
  std::vector<NotchSpec> notches;  // box only
  double size_min = 0.0;           // element size at the features (notch faces, loading arcs) [m]
  double size_max = 0.0;           // element size far from them [m]
  double grading = 0.5;            // growth of element size per unit distance from a feature [-]
  uint32_t seed = 1;               // same seed, same mesh; another seed, another mesh of the same sizing
  // box only, instead of size_min/size_max: a structured Kuhn lattice of nx x ny x nz cells (6 tets each)
  std::optional<std::array<int, 3>> cells;
  // box only, instead of cells and sizing: a Kuhn lattice graded from a fine box outward (graded_axis.hpp)
  std::optional<LatticeGradingSpec> graded;
  // box only, instead of cells and sizing: a hole along z, the lattice graded towards it
  std::optional<BoreholeMeshSpec> borehole;
  // The mesh section's max_elements and its key path: meshing is refused, before it starts, when it is
  // expected to make more tets (element_estimate.hpp; a lattice's count is exact).
  uint64_t max_elements = kDefaultMaxElements;
  std::string max_elements_key = "mesh.max_elements";
};

struct MeshSpec {
  std::optional<std::string> file;           // Gmsh MSH 4.1 or 2.2, path resolved against the scene's folder
  std::optional<MeshGenerateSpec> generate;  // exactly one of file / generate
  double scale = 1.0;                        // multiplies file coordinates (1e-3 for a mesh drawn in mm)
  uint64_t max_file_bytes = uint64_t{2} << 30;  // a larger file is refused before it is read
  std::string file_fnv1a64;  // FNV-1a 64 of the file's bytes when the scene was read (16 hex digits)
};

// Joint (cohesive) properties of a material: the Munjiza law with Mohr-Coulomb and a tension cut-off
// (docs/reference femdem.md 1b). A joint between two different materials takes the weaker value of each.
struct FractureMaterialSpec {
  double tensile_strength = 0.0;   // f_t [Pa]
  double cohesion = 0.0;           // c [Pa]
  double friction_angle = 0.0;     // phi [degrees], Mohr-Coulomb envelope in compression
  double residual_friction = 0.0;  // mu_res of a fully softened point in compression [-]
  double G_I = 0.0, G_II = 0.0;    // fracture energies [J/m^2]
  double penalty = 0.0;            // p [Pa]; the joint stiffness per unit area is p / h
};

struct MaterialSpec {
  std::string name;
  std::vector<std::string> regions;  // mesh regions it applies to; {"all"} for every tet
  double density = 0.0;              // [kg/m^3]
  double young = 0.0;                // Young's modulus [Pa]
  double poisson = 0.0;              // [-], 0 <= nu < 0.5
  double damping = 0.0;              // viscous damping as a fraction of critical at the element scale [-]
  std::optional<FractureMaterialSpec> fracture;  // required for materials inside the fracture zone
};

// Where joints exist: tets of the listed regions whose centroid lies in the box (if one is given).
// A crack that exists at t = 0: the joints whose three corners lie on the plane through `point` with
// normal `normal` (within 1e-6 of the joint's longest edge), and within `radius` of `point` if one is
// given, start broken (no cohesion, no fracture energy; their faces interact only by contact). The mesh
// must have faces on the plane (a lattice mesh, or a file meshed with the crack as an internal surface).
struct CrackPlaneSpec {
  std::array<double, 3> point{};
  std::array<double, 3> normal{0, 0, 1};  // need not be unit length
  std::optional<double> radius;           // [m]; absent: the whole plane
};

struct FractureSpec {
  std::vector<std::string> regions{"all"};
  std::vector<CrackPlaneSpec> initial_cracks;
  std::optional<std::array<double, 3>> box_min, box_max;  // both or neither [m]
  int integration_points = 3;                             // 3 or 7 per joint
  bool y_compatible = false;  // softening length 3 G / f (Y code) instead of the energy-exact one
  // A uniform pressure on both faces of every broken joint (initial cracks and new breaks) [Pa]: the fluid
  // in the cracks when its flow is not modelled (the inviscid, connected limit). Absent: none.
  std::optional<TimeFunction> crack_pressure;
};

// A uniform in-situ stress, present at t = 0 in every tet and joint (compression negative).
struct InitialStressSpec {
  std::array<double, 3> principal{};           // principal stresses [Pa]
  std::array<double, 3> direction_1{1, 0, 0};  // direction of principal[0]; need not be unit length
  std::array<double, 3> direction_2{0, 1, 0};  // of principal[1], orthogonal to direction_1
  // Cauchy tensor xx yy zz xy yz zx: sum_k principal[k] e_k e_k^T with e_3 = e_1 x e_2 (unit vectors;
  // the reader checks that the two directions are orthogonal).
  std::array<double, 6> tensor() const {
    std::array<double, 3> e[3];
    auto unit = [](std::array<double, 3> v) {
      const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      return std::array<double, 3>{v[0] / n, v[1] / n, v[2] / n};
    };
    e[0] = unit(direction_1);
    e[1] = unit(direction_2);
    e[2] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
            e[0][0] * e[1][1] - e[0][1] * e[1][0]};
    static constexpr int kI[6] = {0, 1, 2, 0, 1, 2}, kJ[6] = {0, 1, 2, 1, 2, 0};
    std::array<double, 6> s{};
    for (int c = 0; c < 6; ++c)
      for (int k = 0; k < 3; ++k) s[c] += principal[k] * e[k][kI[c]] * e[k][kJ[c]];
    return s;
  }
};

struct SolidBoundarySpec {
  // in_situ: the traction initial_stress . n on the surface (outward n), scaled by `function`.
  // fluid_pressure (only with a fluid): the fluid's pressure sampled at each face's centroid, once per fluid
  // step (systems/coupling): a wetted surface such as a notch the fluid fills.
  enum class Kind { fixed, velocity, traction, pressure, in_situ, fluid_pressure };
  Kind kind = Kind::fixed;
  std::string surface;  // mesh surface name ("" when a node box is used)
  // fixed / velocity only, instead of a surface: the node set of all solid nodes whose reference
  // position lies in [box_min, box_max] (both given or neither) [m].
  std::optional<std::array<double, 3>> box_min, box_max;
  std::array<bool, 3> components{true, true, true};  // fixed / velocity: which axes are constrained
  std::array<double, 3> direction{};  // velocity [m/s] / traction [Pa]: vector scaled by `function`
  TimeFunction function;              // scales `direction` (velocity, traction) or is the pressure [Pa]
};

// Contact between free faces (femdem.md 1c; systems/contact_system.hpp): Munjiza's potential with
// penalty p, Coulomb friction with a tangential penalty, optional normal damping.
struct ContactSpec {
  std::optional<double> penalty;    // p [Pa]; absent: 10 x the largest Young's modulus
  double friction = 0.0;            // mu [-]
  double tangential_penalty = 0.1;  // k_t / (p L): Y's default of 0.1 x the normal stiffness
  double damping = 0.0;             // xi: fraction of critical of a pair's normal oscillation [-]
  std::optional<double> buffer;     // b [m]; absent: 0.1 x the mean tet edge
};

// A uniform velocity at t = 0 for every node of the tets in `regions` (later entries win where regions
// overlap): a block thrown at another, a projectile.
struct InitialVelocitySpec {
  std::vector<std::string> regions{"all"};
  std::array<double, 3> velocity{};  // [m/s]
};

struct SolidSpec {
  std::vector<MaterialSpec> materials;
  std::vector<InitialVelocitySpec> initial_velocity;
  std::optional<ContactSpec> contact;  // absent: no contact system
  std::vector<SolidBoundarySpec> boundaries;
  std::array<double, 3> gravity{};  // [m/s^2]
  // c [1/s]: a drag -c m v on every node (dynamic relaxation to a static state), a function of time so that
  // a run can first settle under its initial loads and then go on undamped.
  TimeFunction mass_damping;
  // Selective mass scaling [s], 0: off. Nodes whose own stable step (the per-node Gershgorin bound of tets,
  // joints and contact) is below it get the mass that brings them to it; the step is then the per-node one.
  double mass_scaling_step = 0.0;
  // The node pass computes the forces of tets with nodes of their own (a fracture zone) and gathers their
  // nodes per tet (systems/tet_force_system.hpp): the same physics, rounded in another order, 1.25 x faster
  // on a jointed block. false: the tet pass and the per-node gather, for comparison.
  bool fused_tet_pass = true;
  std::optional<FractureSpec> fracture;             // absent: continuous mesh, no joints
  std::optional<InitialStressSpec> initial_stress;  // absent: stress-free start
};

// A fluid boundary condition on a named mesh surface; the fluid's solver takes Kind as it is
// (systems/fluid/fluid_solver.hpp BoundaryKind).
struct FluidBoundarySpec {
  enum class Kind {
    no_slip,    // u = 0
    velocity,   // u = velocity(x, t)
    free_slip,  // u . n = 0, zero tangential traction; the surface must be an axis-aligned plane
    pressure,   // p = pressure(x, t), mu du/dn = 0 (do-nothing)
    outflow,    // p = 0, mu du/dn = 0
  };
  Kind kind = Kind::no_slip;
  std::string surface;
  std::array<double, 3> direction{};  // velocity: the vector [m/s] `function` scales
  TimeFunction function;              // velocity: scales `direction` (1 by default); pressure: p [Pa]
  // velocity: axes along which the value falls parabolically to 0 at the surface's bounding box (peak 1 in
  // the middle): 4 (x - lo)(hi - x) / (hi - lo)^2 per axis; none: uniform.
  std::array<bool, 3> parabolic{};
};

// The adaptive fluid mesh around an immersed solid (docs/fluid.md, "Adaptive mesh"): fluid.mesh.generate
// is a box whose size_min applies at the solid's surface (outer faces, notches and cracks), growing by
// `grading` per unit distance up to size_max. The mesh is made around the solid at t = 0 and remade every
// `interval` fluid steps (0: never again), the fluid's fields interpolated onto the new mesh.
struct FluidAdaptSpec {
  int64_t interval = 0;
  // Which parts of the solid's surface the mesh is refined at (mesh_conversion.hpp's tags): its outer
  // boundary, its pre-existing notches, the faces of broken joints.
  bool boundary = true, notch = true, fracture = true;
};

// Incompressible Navier-Stokes (systems/fluid, docs/fluid.md) on its own mesh.
struct FluidSpec {
  // How velocity and pressure are solved together (the solver's PressureCoupling is this enum).
  enum class Coupling {
    schur_gmres,  // each Picard iteration solves the linearised stabilised system exactly (FGMRES on the
                  // pressure Schur complement): robust for any viscosity and dt
    projection,   // one pressure correction per Picard iteration (iterated incremental projection): cheap,
                  // converges slowly when mu dt / (rho h^2) >> 1
  };
  enum class OnPicardFailure { stop, continue_run };
  std::optional<MeshSpec> mesh;         // absent: the top-level mesh
  std::optional<FluidAdaptSpec> adapt;  // absent: the mesh is fixed
  double density = 1.0;                 // [kg/m^3]
  double viscosity = 0.0;               // dynamic viscosity [Pa s]
  double dt = 0.0;                      // fluid time step [s]
  double theta = 1.0;                   // 1 backward Euler, 0.5 Crank-Nicolson
  bool convection = true;
  bool supg = true;
  bool dynamic_subscale = false;  // pressure_subscale: dynamic (kernels/fluid_subscale.hpp)
  Coupling coupling = Coupling::schur_gmres;
  int picard_max_iterations = 20;
  double picard_tolerance = 1e-6;
  OnPicardFailure on_picard_failure = OnPicardFailure::stop;
  double velocity_tolerance = 1e-10;
  int velocity_max_iterations = 2000;
  double schur_tolerance = 1e-8;
  int schur_max_iterations = 200;
  int schur_restart = 100;  // a restart discards the Krylov space (docs/fluid.md)
  double pressure_tolerance = 1e-8;
  int pressure_max_iterations = 200;
  std::array<double, 3> body_force{};        // [N/m^3]
  std::array<double, 3> initial_velocity{};  // [m/s], then the boundary values on Dirichlet nodes
  double initial_pressure = 0.0;             // [Pa], uniform at t = 0
  std::vector<FluidBoundarySpec> boundaries;
};

// The two-way fluid-solid coupling (systems/coupling, docs/coupling.md): the solid immersed in the fluid
// mesh as a volume fraction. Present exactly when the scene has both a solid and a fluid.
struct FluidSolidSpec {
  // How the fluid pushes on the solid. volume: the force over the solid's volume (absorption reaction,
  // displaced fluid's momentum change, buoyancy). wetted_faces: only the fluid's pressure on the solid's
  // boundaries of type fluid_pressure (a notch the fluid fills), as the paper's fracture coupling does; the
  // absorption still makes the flow follow the solid. Not both: the pressure would count twice.
  enum class Force { volume, wetted_faces };
  Force force = Force::volume;
  int64_t substeps = 0;  // solid steps per fluid step; 0: the fewest with dt_s <= time.safety x stable step
  double beta = 1.0;     // absorption weight: sigma = beta rho_f alpha_s / fluid.dt
  // > 0: the absorption's relaxation time instead, sigma = rho_f alpha_s / relaxation_time, the same at every
  // fluid.dt (beta = fluid.dt / relaxation_time), so that a shorter fluid step does not stiffen the pull of
  // the solid on the fluid of the cells it cuts (docs/coupling.md). 0: beta is given.
  double relaxation_time = 0.0;
  // c_a: virtual mass c_a rho_f V added to the solid's nodes (V: their share of the solid inside the fluid at
  // t = 0) and c_a rho_f V a (a: the node's mean acceleration over the last window) added to its fluid force,
  // so the staggered exchange stays stable for a solid lighter than about the fluid (added-mass
  // instability). 0: off. It lags the fluid's added mass by one window; no effect at steady acceleration.
  double added_mass = 0.0;
  // The fluid's continuity allows the solid's rate of volume change where the solid is (div u = s_K,
  // docs/coupling.md); off: div u = 0 everywhere. Off by default: with the lagged exchange it made the
  // wedge scene's coupling unstable (docs/speed-accuracy.md).
  bool dilatation = false;
  // Where the fluid's continuity holds. mixture: div u = s in every cell, also those the solid fills (the
  // fictitious fluid inside the solid must follow the solid's volume changes). fluid: weighted by the
  // fluid's fraction 1 - alpha of each cell, the pressure inside the solid being the extension of the
  // fluid's that lets no fluid through the solid relative to it (docs/coupling.md).
  enum class Continuity { mixture, fluid };
  Continuity continuity = Continuity::mixture;
  // A point in the fluid [m] (the notch's mouth): the fracture-flow network's well takes the fluid's
  // pressure there after every fluid step, and what the network takes in leaves the fluid there (the cell
  // that holds it, or the cells of network_inlet_extent), as a sink (docs/coupling.md "The fluid feeds the
  // cracks"). Needs fracture_flow, whose injection then gives neither rate nor pressure.
  std::optional<std::array<double, 3>> network_inlet;
  // The box centred on network_inlet [m] over which the sink spreads and the pressure is averaged: the
  // fluid cells whose centres lie in it, each in proportion to the fluid it holds, (1 - alpha) |K|. All
  // zero: the one cell that holds the point, and the pressure interpolated at the point.
  std::array<double, 3> network_inlet_extent{};
  // When the fluid step runs (docs/coupling.md). sequential: on the last solid step of each window, from
  // the solid at the window's end. concurrent: from the solid at the window's start, as a task beside the
  // window's solid sub-steps (the fluid sees the solid one window earlier; the force lag is the same).
  enum class Coupling { sequential, concurrent };
  Coupling coupling = Coupling::sequential;
};

// Fluid in the fractures (systems/fracture_flow, docs/hydraulic-fracture.md): lubrication flow of a
// slightly compressible fluid on the crack network (broken joints and initial cracks), injected at a
// well. Needs solid.fracture; not with solid.fracture.crack_pressure (the prescribed limit of this flow).
struct FractureFlowSpec {
  // The equation of state as the kernels take it: density (rho0 [kg/m^3] at reference_pressure),
  // reference_pressure (p0 [Pa]) and bulk_modulus (K_f [Pa]) are read straight into it.
  kernels::FluidEos eos{1000.0, 0.0, 2.2e9};
  double viscosity = 1.0e-3;       // mu [Pa s]; 0: zero-viscosity mode (one pressure per connected crack)
  double aperture_floor = 1.0e-6;  // [m]: hydraulic aperture and storage never below it
  double lag_pressure = 0.0;       // [Pa]: held by crack regions the fluid has not reached
  double initial_pressure = 0.0;   // [Pa]: the fluid filling the initial cracks at t = 0
  int64_t interval = 1;            // solid steps per flow solve (in between: each vertex on its own)
  // A joint joins the network when its damage (the largest D_max of its points) reaches this: 1, only
  // broken joints; below 1, the fluid also enters the process zone ahead of the crack.
  double wet_damage = 1.0;
  // The pressure solve: automatic (factorisation below 2000 network vertices, CG above), direct (the
  // factorisation), cg (conjugate gradients); the network's solver takes this enum as it is
  // (systems/fracture_flow/network_flow.hpp NetworkSolver).
  enum class Solver { automatic, direct, cg };
  Solver solver = Solver::automatic;
  // The well: the crack vertex nearest `point` (within an element of it), given extra storage; or, with
  // well_surfaces, those surfaces (a borehole's wall): one lumped vertex that every crack point on them
  // joins, whose pressure loads them. `point` then only places the well (extents are measured from it).
  std::array<double, 3> point{};
  std::vector<std::string> well_surfaces;
  std::optional<TimeFunction> rate;      // injected volume rate at rho0 [m^3/s] (one of rate, pressure)
  std::optional<TimeFunction> pressure;  // well pressure [Pa]
  bool pressure_from_fluid = false;      // the well's pressure is the surrounding fluid's (network_inlet)
  double well_volume = 0.0;              // [m^3]: the borehole and line the injection fills first
  double well_compliance = 0.0;          // [m^3/Pa]: the line's and pump's compliance
  // Crack vertices on the named surfaces (all of the mesh's when empty) hold this pressure and take what
  // flows out (absent: sealed).
  std::optional<double> vent_pressure;
  std::vector<std::string> vent_surfaces;
  double leak_off = 0.0;  // Carter coefficient C_L [m/s^0.5]: each wet face loses C_L / sqrt(t - t_wet)
  double spurt = 0.0;     // [m]: volume per face area lost at wetting
};

struct TimeSpec {
  double end = 0.0;                // simulated end time [s]
  std::optional<double> dt;        // requested step [s]; absent: safety x stable step, or fluid.dt
  double safety = 0.5;             // fraction of the stable step used when dt is absent (0, 1]
  bool allow_unstable_dt = false;  // run a dt above the stable step on purpose (stability studies)
};

struct OutputSpec {
  double interval = 0.0;            // simulated time between field outputs [s]; 0: first and last only
  std::vector<std::string> fields;  // field names; empty: every field the systems offer
  bool surface = false;             // also write the solid's surface mesh (consumer of mesh conversion)
};

struct CheckpointSpec {
  int64_t every_steps = 0;     // 0: off
  double every_seconds = 0.0;  // wall-clock seconds; 0: off
  int32_t keep = 2;            // newest checkpoints kept
};

// A number a run produces that the scene can compare with a known answer (`reference` section): the
// sweep's error metrics. From a time-series column reduced over the run, or a summary.json value.
struct ReferenceMetricSpec {
  enum class Reduce { max, min, final, max_abs };
  std::string name;
  std::string series;           // a timeseries.csv column ("" when `summary` is used)
  std::string summary;          // a summary.json value as a dot path, e.g. metrics.solid.energy.fracture
  Reduce reduce = Reduce::max;  // series only
  double factor = 1.0;          // the metric is factor x the value read (e.g. 1 / area)
  std::optional<double> value;  // the analytic answer; absent: a sweep compares with its finest variant
};

// A gauge: a field read at fixed points (`probes` section), each a time-series column, with its final
// values and, where the scene gives known values, their errors in summary.json.
struct ProbePointSpec {
  std::array<double, 3> at{};   // [m]: fluid probes in space, solid probes in the reference configuration
  std::optional<double> value;  // the known value of factor x the reading here (a table, a lab gauge)
};
struct ProbeSpec {
  std::string name;
  std::string field;      // "<model>.<field>", one of probe_fields()
  std::string component;  // one of the field's components (probe_fields())
  double factor = 1.0;    // the probe reads factor x the field (e.g. 1 / lid speed)
  std::vector<ProbePointSpec> points;
};

struct Scene {
  std::string name;
  std::string description;
  std::string source_file;  // the file it was read from ("" when built in code)
  TimeSpec time;
  MeshSpec mesh;                   // neither file nor generate when absent (a fluid scene with fluid.mesh)
  std::optional<SolidSpec> solid;  // absent: no solid systems in the run
  std::optional<FluidSpec> fluid;  // absent: no fluid; with a solid, fluid.mesh is required
  std::optional<FluidSolidSpec> fluid_solid;      // with both a solid and a fluid (defaults when not written)
  std::optional<FractureFlowSpec> fracture_flow;  // fluid in the cracks (needs solid.fracture)
  OutputSpec output;
  CheckpointSpec checkpoint;
  std::vector<ReferenceMetricSpec> reference;  // empty: the scene names no error metrics
  std::vector<ProbeSpec> probes;               // empty: no gauges
  std::string resolved_yaml;                   // the complete scene (defaults filled, overrides applied)
  // FNV-1a 64 of resolved_yaml followed by the content hash of every mesh file it names, 16 hex digits
  // (stable across runs): a mesh file replaced at the same path makes another scene.
  std::string hash;
};

}  // namespace rift
