#pragma once
// Shape statistics of a tet mesh, for the run log and the run manifest. Explicit dynamics cares most
// about the worst element (its smallest height sets the stable time step), so extremes are reported
// next to means.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "engine/mesh/tet_mesh.hpp"

namespace rift {

struct MeshQuality {
  size_t nodes = 0, tets = 0, triangles = 0;
  double volume = 0.0;            // sum of signed tet volumes [m^3]
  double min_dihedral_deg = 0.0;  // over all tets; 70.53 for a regular tet
  double max_dihedral_deg = 0.0;
  double worst_radius_ratio = 0.0;  // 3 r_in / R_circ: 1 for a regular tet, 0 for a flat one
  double mean_radius_ratio = 0.0;
  double min_edge = 0.0, max_edge = 0.0;                          // [m]
  size_t inverted = 0;                                            // tets with det[x1-x0, x2-x0, x3-x0] <= 0
  std::vector<std::pair<std::string, size_t>> surface_triangles;  // per surface name, in name order
  std::vector<std::pair<std::string, size_t>> region_tets;        // per region name, in name order
};

// One pass over the tets; O(tets).
MeshQuality measure_quality(const TetMesh& mesh);
// A few readable lines for the log.
std::string format_quality(const MeshQuality& q);
nlohmann::json quality_to_json(const MeshQuality& q);

// Per-tet measures used above (exposed for tests and for systems that want them per element).
struct TetShape {
  double six_volume;    // det[x1-x0, x2-x0, x3-x0]
  double radius_ratio;  // 3 r_in / R_circ (0 when degenerate)
  double min_dihedral_rad, max_dihedral_rad;
  double min_edge, max_edge;
  double circumradius;                 // infinity when degenerate
  std::array<double, 3> circumcenter;  // x0 when degenerate
};
TetShape tet_shape(const std::array<double, 3>& x0, const std::array<double, 3>& x1,
                   const std::array<double, 3>& x2, const std::array<double, 3>& x3);

}  // namespace rift
