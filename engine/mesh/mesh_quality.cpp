#include "engine/mesh/mesh_quality.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/core/vec3.hpp"

namespace rift {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

}  // namespace

TetShape tet_shape(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  TetShape s{};
  const Vec3 a = sub(x1, x0), b = sub(x2, x0), c = sub(x3, x0);
  s.six_volume = dot(a, cross(b, c));
  const double edges[6] = {norm(a),           norm(b),           norm(c),
                           norm(sub(x2, x1)), norm(sub(x3, x1)), norm(sub(x3, x2))};
  s.min_edge = *std::min_element(edges, edges + 6);
  s.max_edge = *std::max_element(edges, edges + 6);
  // Area vectors of the faces opposite vertex 0..3, outward for a positive tet (they sum to zero).
  const Vec3 n[4] = {cross(sub(x2, x1), sub(x3, x1)), cross(c, b), cross(a, c), cross(b, a)};
  double len[4], area2 = 0.0;  // area2: twice the total surface area
  for (int k = 0; k < 4; ++k) area2 += (len[k] = norm(n[k]));
  s.circumradius = std::numeric_limits<double>::infinity();
  s.circumcenter = x0;
  if (s.six_volume == 0.0 || std::min({len[0], len[1], len[2], len[3]}) == 0.0) {
    s.radius_ratio = 0.0;
    s.min_dihedral_rad = 0.0;
    s.max_dihedral_rad = std::numbers::pi;
    return s;
  }
  // Inradius r = 3V / A, with A the total face area; circumcentre offset from x0:
  // (|a|^2 b x c + |b|^2 c x a + |c|^2 a x b) / (2 det).
  const double r_in = std::abs(s.six_volume) / area2;
  const Vec3 bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
  Vec3 o;
  for (int k = 0; k < 3; ++k) o[k] = dot(a, a) * bc[k] + dot(b, b) * ca[k] + dot(c, c) * ab[k];
  for (double& c : o) c /= 2.0 * s.six_volume;
  s.circumradius = norm(o);
  for (int k = 0; k < 3; ++k) s.circumcenter[k] = x0[k] + o[k];
  s.radius_ratio = 3.0 * r_in / s.circumradius;
  // Interior dihedral angle between two faces = pi - angle between their outward normals.
  s.min_dihedral_rad = std::numbers::pi;
  s.max_dihedral_rad = 0.0;
  for (int k = 0; k < 4; ++k)
    for (int l = k + 1; l < 4; ++l) {
      const double cosine = std::clamp(-dot(n[k], n[l]) / (len[k] * len[l]), -1.0, 1.0);
      const double angle = std::acos(cosine);
      s.min_dihedral_rad = std::min(s.min_dihedral_rad, angle);
      s.max_dihedral_rad = std::max(s.max_dihedral_rad, angle);
    }
  return s;
}

MeshQuality measure_quality(const TetMesh& mesh) {
  MeshQuality q;
  q.nodes = mesh.nodes.size();
  q.tets = mesh.tets.size();
  q.triangles = mesh.triangles.size();
  if (!mesh.tets.empty()) {
    q.min_dihedral_deg = 180.0;
    q.worst_radius_ratio = 1.0;
    q.min_edge = std::numeric_limits<double>::infinity();
  }
  double ratio_sum = 0.0;
  for (const auto& t : mesh.tets) {
    const TetShape s = tet_shape(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
    q.volume += s.six_volume / 6.0;
    q.inverted += s.six_volume <= 0.0;
    q.min_dihedral_deg = std::min(q.min_dihedral_deg, s.min_dihedral_rad * kDeg);
    q.max_dihedral_deg = std::max(q.max_dihedral_deg, s.max_dihedral_rad * kDeg);
    q.worst_radius_ratio = std::min(q.worst_radius_ratio, s.radius_ratio);
    ratio_sum += s.radius_ratio;
    q.min_edge = std::min(q.min_edge, s.min_edge);
    q.max_edge = std::max(q.max_edge, s.max_edge);
  }
  if (!mesh.tets.empty()) q.mean_radius_ratio = ratio_sum / static_cast<double>(mesh.tets.size());
  for (const auto& name : mesh.surface_names) q.surface_triangles.emplace_back(name, 0);
  for (const int32_t s : mesh.triangle_surface) ++q.surface_triangles.at(s).second;
  for (const auto& name : mesh.region_names) q.region_tets.emplace_back(name, 0);
  for (const int32_t r : mesh.tet_region) ++q.region_tets.at(r).second;
  return q;
}

std::string format_quality(const MeshQuality& q) {
  std::string text = fmt::format("mesh: {} nodes, {} tets, {} surface triangles, volume {:.6g} m^3\n",
                                 q.nodes, q.tets, q.triangles, q.volume);
  text += fmt::format("  dihedral angles {:.2f} .. {:.2f} deg, radius ratio worst {:.3f} mean {:.3f}\n",
                      q.min_dihedral_deg, q.max_dihedral_deg, q.worst_radius_ratio, q.mean_radius_ratio);
  text += fmt::format("  edges {:.4g} .. {:.4g} m, inverted tets {}\n", q.min_edge, q.max_edge, q.inverted);
  text += "  regions:";
  for (const auto& [name, n] : q.region_tets) text += fmt::format(" {} ({} tets)", name, n);
  text += "\n  surfaces:";
  for (const auto& [name, n] : q.surface_triangles) text += fmt::format(" {} ({})", name, n);
  return text;
}

nlohmann::json quality_to_json(const MeshQuality& q) {
  nlohmann::json j = {{"nodes", q.nodes},
                      {"tets", q.tets},
                      {"triangles", q.triangles},
                      {"volume", q.volume},
                      {"min_dihedral_deg", q.min_dihedral_deg},
                      {"max_dihedral_deg", q.max_dihedral_deg},
                      {"worst_radius_ratio", q.worst_radius_ratio},
                      {"mean_radius_ratio", q.mean_radius_ratio},
                      {"min_edge", q.min_edge},
                      {"max_edge", q.max_edge},
                      {"inverted", q.inverted}};
  j["surface_triangles"] = nlohmann::json::object();
  for (const auto& [name, n] : q.surface_triangles) j["surface_triangles"][name] = n;
  j["region_tets"] = nlohmann::json::object();
  for (const auto& [name, n] : q.region_tets) j["region_tets"][name] = n;
  return j;
}

}  // namespace rift
