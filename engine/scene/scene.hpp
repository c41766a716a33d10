#pragma once
// The typed scene: what a scene file means once it has been read, checked and completed with
// defaults. Every run, test and benchmark builds its world from one of these. SI units throughout.
// The YAML layout, units, defaults and ranges are documented in docs/scene-format.md.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/time_function.hpp"

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

struct MeshGenerateSpec {
  enum class Shape { box, cylinder };
  Shape shape = Shape::box;
  std::array<double, 3> size{};  // box: edge lengths [m]
  CylinderSpec cylinder;         // cylinder: its dimensions
  // box: lower corner; cylinder: (x, y) of the axis and z of the lower flat face [m]
  std::array<double, 3> origin{};
  std::vector<NotchSpec> notches;  // box only
  double size_min = 0.0;           // element size at the features (notch faces, loading arcs) [m]
  double size_max = 0.0;           // element size far from them [m]
  double grading = 0.5;            // growth of element size per unit distance from a feature [-]
  uint32_t seed = 1;               // generator seed: the same seed gives the same mesh
};

struct MeshSpec {
  std::optional<std::string> file;           // Gmsh MSH 4.1 ASCII, path resolved against the scene's folder
  std::optional<MeshGenerateSpec> generate;  // exactly one of file / generate
  double scale = 1.0;                        // multiplies file coordinates (1e-3 for a mesh drawn in mm)
};

struct MaterialSpec {
  std::string name;
  std::vector<std::string> regions;  // mesh regions it applies to; {"all"} for every tet
  double density = 0.0;              // [kg/m^3]
  double young = 0.0;                // Young's modulus [Pa]
  double poisson = 0.0;              // [-], 0 <= nu < 0.5
  double damping = 0.0;              // viscous damping as a fraction of critical at the element scale [-]
};

struct SolidBoundarySpec {
  enum class Kind { fixed, velocity, traction, pressure };
  Kind kind = Kind::fixed;
  std::string surface;                               // mesh surface name
  std::array<bool, 3> components{true, true, true};  // fixed / velocity: which axes are constrained
  std::array<double, 3> direction{};  // velocity [m/s] / traction [Pa]: vector scaled by `function`
  TimeFunction function;              // scales `direction` (velocity, traction) or is the pressure [Pa]
};

struct SolidSpec {
  std::vector<MaterialSpec> materials;
  std::vector<SolidBoundarySpec> boundaries;
  std::array<double, 3> gravity{};  // [m/s^2]
};

struct TimeSpec {
  double end = 0.0;                // simulated end time [s]
  std::optional<double> dt;        // requested solid step [s]; absent: safety x stable step
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

struct Scene {
  std::string name;
  std::string description;
  std::string source_file;  // the file it was read from ("" when built in code)
  TimeSpec time;
  MeshSpec mesh;
  std::optional<SolidSpec> solid;  // absent: no solid systems in the run
  OutputSpec output;
  CheckpointSpec checkpoint;
  std::string resolved_yaml;  // the complete scene (defaults filled, overrides applied)
  std::string hash;           // FNV-1a 64 of resolved_yaml, 16 hex digits (stable across runs)
};

}  // namespace rift
