// Polyhedral solids on CGAL Mesh_3 (see polyhedral_mesher.hpp for the sizing and determinism contract).
#include "engine/mesh/polyhedral_mesher.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polyhedral_complex_mesh_domain_3.h>
#include <CGAL/Random.h>
#include <CGAL/exude_mesh_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/perturb_mesh_3.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>
#include <random>
#include <unordered_map>

#include "engine/core/error.hpp"
#include "engine/mesh/element_estimate.hpp"

namespace rift {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Polyhedral_complex_mesh_domain_3<K>;
using Polyhedron = Domain::Polyhedron;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

// Perturbation tries to lift every tet's minimum dihedral angle above this. Higher bounds cost more
// time for no gain on the notched blocks we tried (10 and 15 degrees gave the same mesh).
constexpr double kPerturbBoundDeg = 10.0;
constexpr int kRandomTries = 20;  // random perturbation attempts per vertex (see remove_slivers)
// Exudation works on tets whose minimum dihedral angle is below this. With 0 ("all tets") it took
// 5-10 times longer for the same worst angle on the blocks we tried.
constexpr double kExudeBoundDeg = 20.0;
// Exudation stops after this many pump steps per tet at the latest (see CappedExudeVisitor).
constexpr size_t kExudeStepsPerCell = 2;

// The seed's jitter of the sizing field: j(p) in [1 - kJitter, 1], a smooth field of three plane waves
// with random directions and phases (wavelength a third of the domain's diagonal). Delaunay refinement
// draws no random numbers where features seed it (the protecting balls), so without it every seed gave
// the same mesh; with it each seed gives a different mesh of the same sizing contract (h only lowered).
// Seed 1 is the unjittered mesh.
constexpr double kJitter = 0.1;
struct SizeJitter {
  std::array<Vec3, 3> k{};
  std::array<double, 3> phase{};
  bool on = false;
  double operator()(const Vec3& p) const {
    if (!on) return 1.0;
    double m = 0.0;
    for (int i = 0; i < 3; ++i) m += std::sin(k[i][0] * p[0] + k[i][1] * p[1] + k[i][2] * p[2] + phase[i]);
    return 1.0 - 0.5 * kJitter * (1.0 + m / 3.0);
  }
};

// Uniform in [0, 1) from the 53 high bits of a 64-bit Mersenne twister (fully specified by the standard,
// unlike the distributions): the same jitter on every platform.
double unit_random(std::mt19937_64& g) {
  return static_cast<double>(g() >> 11) * 0x1.0p-53;
}

SizeJitter size_jitter(const std::vector<PolyhedralSurface>& patches, uint32_t seed) {
  SizeJitter j;
  if (seed == 1) return j;
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const auto& s : patches)
    for (const Vec3& p : s.points)
      for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  const double diagonal = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  const double wavenumber = 2.0 * M_PI / (diagonal / 3.0);
  std::mt19937_64 g(seed);
  for (int i = 0; i < 3; ++i) {
    const double z = 2.0 * unit_random(g) - 1.0, a = 2.0 * M_PI * unit_random(g), r = std::sqrt(1.0 - z * z);
    j.k[i] = {wavenumber * r * std::cos(a), wavenumber * r * std::sin(a), wavenumber * z};
    j.phase[i] = 2.0 * M_PI * unit_random(g);
  }
  j.on = true;
  return j;
}

// Mesh_3 sizing field: factor * h(p) * jitter(p). Mesh_3 calls it with (point, dimension, index).
struct SizingField {
  const std::function<double(const Vec3&)>* size;
  double factor;
  const SizeJitter* jitter;
  template <class Index>
  K::FT operator()(const K::Point_3& p, int, const Index&) const {
    const Vec3 q{p.x(), p.y(), p.z()};
    return factor * (*size)(q) * (*jitter)(q);
  }
};

// The surface as a CGAL polyhedron, every face triangulated (caps need not be convex).
Polyhedron to_polyhedron(const PolyhedralSurface& s) {
  std::vector<K::Point_3> points;
  for (const Vec3& p : s.points) points.emplace_back(p[0], p[1], p[2]);
  Polyhedron surface;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, s.faces, surface);
  CGAL::Polygon_mesh_processing::triangulate_faces(surface);
  return surface;
}

// Sliver exudation in CGAL 5.5 can cycle forever on some meshes (seen on a slotted box without prior
// perturbation: the same 67 cells re-queued for minutes); its only stop is a wall-clock limit, which would
// make the mesh depend on machine speed. So it runs with no time limit and a deterministic cap on the number
// of pump steps, enforced from the visitor that Mesh_3 calls after each step (between steps the mesh is
// consistent).
struct ExudeStepCap {};
struct CappedExudeVisitor {
  size_t steps = 0, cap = 0;
  void after_cell_pumped(std::size_t /*cells_left*/) {
    if (++steps >= cap) throw ExudeStepCap{};
  }
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// CGAL's default perturbation set, except that the random perturbation gets kRandomTries per vertex
// instead of 100. Its cost is erratic (a bound it cannot reach is retried at length): on the blocks we
// tried, 100 tries took up to 10 s and 20 tries at most 1.5 s, for worst dihedral angles that differed
// by a degree or two either way. The deterministic perturbations alone gave nothing.
void perturb(C3t3& c3t3, const Domain& domain) {
  namespace M = CGAL::Mesh_3;
  using Criterion = M::Min_dihedral_angle_criterion<Tr>;
  M::Sliver_perturber<C3t3, Domain, Criterion> perturber(c3t3, domain,
                                                         Criterion(kPerturbBoundDeg, c3t3.triangulation()));
  // The perturber takes ownership of these.
  perturber.add_perturbation(new M::Sq_radius_perturbation<C3t3, Domain, Criterion>(40, 0.05));
  perturber.add_perturbation(new M::Volume_perturbation<C3t3, Domain, Criterion>(40, 0.05));
  perturber.add_perturbation(new M::Dihedral_angle_perturbation<C3t3, Domain, Criterion>(40, 0.05));
  perturber.add_perturbation(new M::Li_random_perturbation<C3t3, Domain, Criterion>(kRandomTries, 0.15));
  perturber.set_time_limit(0);  // no wall-clock dependence: the tries bound the work
  perturber();
}

// Returns true when the step cap stopped it.
bool exude(C3t3& c3t3) {
  using Criterion = CGAL::Mesh_3::Min_dihedral_angle_criterion<Tr>;
  CGAL::Mesh_3::Slivers_exuder<C3t3, Criterion, CappedExudeVisitor> exuder(
      c3t3, Criterion(kExudeBoundDeg, c3t3.triangulation()));
  try {
    exuder(CappedExudeVisitor{0, kExudeStepsPerCell * c3t3.number_of_cells_in_complex()});
  } catch (const ExudeStepCap&) {
    return true;
  }
  return false;
}

// Perturbation then exudation, both aiming at the minimum dihedral angle. Global smoothers (ODT,
// Lloyd) are not used: on a narrow wedge they moved the boundary off the notch planes (volume error
// 1e-4 relative), which breaks the exact geometry promised in the header.
void remove_slivers(C3t3& c3t3, const Domain& domain, Mesh3Stats& stats) {
  auto start = std::chrono::steady_clock::now();
  perturb(c3t3, domain);
  stats.perturb_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  stats.exude_capped = exude(c3t3);
  stats.exude_seconds = seconds_since(start);
}

C3t3 run_mesh_3(const PolyhedralMeshInput& in, Mesh3Stats& stats) {
  // Every random draw in Mesh_3 comes from one of these two generators; seeding both pins the result.
  CGAL::get_default_random() = CGAL::Random(in.seed);
  CGAL::Random domain_random(in.seed);
  std::vector<Polyhedron> patches;
  for (const auto& patch : in.patches) patches.push_back(to_polyhedron(patch));
  // Every patch has the solid (subdomain 1) behind its outward faces and nothing (0) in front.
  const std::vector<std::pair<int, int>> sides(patches.size(), {1, 0});
  Domain domain(patches.begin(), patches.end(), sides.begin(), sides.end(), &domain_random);
  domain.detect_features(in.feature_angle_deg);

  const SizeJitter jitter = size_jitter(in.patches, in.seed);
  const SizingField size{&in.size, 1.0, &jitter}, distance{&in.size, 0.1, &jitter};
  namespace p = CGAL::parameters;
  const Criteria criteria(p::edge_size = size, p::facet_angle = 25.0, p::facet_size = size,
                          p::facet_distance = distance,
                          p::facet_topology = CGAL::FACET_VERTICES_ON_SAME_SURFACE_PATCH,
                          p::cell_radius_edge_ratio = 3.0, p::cell_size = size);
  // Optimisers are run separately: inside make_mesh_3 they get a time limit equal to the refinement
  // time, which would make the result depend on the machine's speed.
  const auto start = std::chrono::steady_clock::now();
  C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, p::no_perturb(), p::no_exude());
  stats.refine_seconds = seconds_since(start);
  remove_slivers(c3t3, domain, stats);
  return c3t3;
}

Vec3 point_of(const Tr::Vertex_handle& v) {
  const auto& p = v->point().point();
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

double det3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]},
      w{d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Tets of the complex with their vertices numbered in order of first appearance; `index` maps CGAL
// vertices to node numbers (lookup only, so hashing by address does not affect the order).
void extract_tets(const C3t3& c3t3, TetMesh& mesh, std::unordered_map<const void*, int32_t>& index) {
  auto node = [&](const Tr::Vertex_handle& v) {
    const auto [it, added] = index.emplace(&*v, static_cast<int32_t>(mesh.nodes.size()));
    if (added) mesh.nodes.push_back(point_of(v));
    return it->second;
  };
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    std::array<int32_t, 4> t{node(c->vertex(0)), node(c->vertex(1)), node(c->vertex(2)), node(c->vertex(3))};
    if (det3(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]) < 0)
      std::swap(t[1], t[2]);
    mesh.tets.push_back(t);
  }
  mesh.region_names = {"domain"};
  mesh.tet_region.assign(mesh.tets.size(), 0);
}

// Boundary facets as outward triangles, classified, then grouped by surface (stable within a group).
void extract_triangles(const C3t3& c3t3, const PolyhedralMeshInput& in, TetMesh& mesh,
                       const std::unordered_map<const void*, int32_t>& index) {
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<int32_t> surfaces;
  for (auto f = c3t3.facets_in_complex_begin(); f != c3t3.facets_in_complex_end(); ++f) {
    Tr::Facet facet = *f;  // (cell, index of the vertex opposite the facet), taken from the inside
    if (!c3t3.is_in_complex(facet.first)) facet = c3t3.triangulation().mirror_facet(facet);
    const auto& cell = facet.first;
    const int i = facet.second;
    std::array<int32_t, 3> tri{index.at(&*cell->vertex((i + 1) & 3)), index.at(&*cell->vertex((i + 2) & 3)),
                               index.at(&*cell->vertex((i + 3) & 3))};
    const int32_t inside = index.at(&*cell->vertex(i));
    // Outward normal: the tet's own vertex must be on the negative side.
    if (det3(mesh.nodes[tri[0]], mesh.nodes[tri[1]], mesh.nodes[tri[2]], mesh.nodes[inside]) > 0)
      std::swap(tri[1], tri[2]);
    triangles.push_back(tri);
    surfaces.push_back(in.classify(mesh, tri));
  }
  std::vector<size_t> order(triangles.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return surfaces[a] < surfaces[b]; });
  mesh.surface_names = in.surface_names;
  for (const size_t k : order) {
    mesh.triangles.push_back(triangles[k]);
    mesh.triangle_surface.push_back(surfaces[k]);
  }
}

double check_tet_budget(const PolyhedralMeshInput& in) {
  const double budget = static_cast<double>(in.max_tets);
  const TetEstimate e = estimate_mesh3_tets(in.patches, in.size, budget);
  if (e.tets <= budget) return e.tets;
  const std::string key = in.max_tets_key.empty() ? "the mesher's tet bound" : in.max_tets_key;
  const std::string how =
      fmt::format("estimated before meshing as the solid's volume over {} h^3 per tet, h the size field",
                  kMesh3TetVolume);
  const std::string advice = fmt::format(
      "Use a larger size_min / size_max (the count scales as 1 / h^3), or raise {} to mesh it anyway", key);
  if (e.lower_bound)
    throw Error(
        fmt::format("mesh.generate: the sizes ask for more tets than {} = {} ({}; the count passed "
                    "the bound before the whole solid was counted), more than {:.3g} GB of memory. {}",
                    key, in.max_tets, how, budget * kBytesPerTet / 1e9, advice));
  throw Error(
      fmt::format("mesh.generate: the sizes ask for about {:.3g} tets ({}), more than {} = {}; about "
                  "{:.3g} GB of memory to mesh and run. {}",
                  e.tets, how, key, in.max_tets, e.tets * kBytesPerTet / 1e9, advice));
}

}  // namespace

PolyhedralSurface extruded_polygon(const std::vector<std::array<double, 2>>& polygon, double w0, double w1,
                                   const std::function<Vec3(double s, double t, double w)>& to_3d) {
  const size_t n = polygon.size();
  PolyhedralSurface s;
  for (const double w : {w0, w1})
    for (const auto& q : polygon) s.points.push_back(to_3d(q[0], q[1], w));
  std::vector<size_t> bottom(n), top(n);
  for (size_t i = 0; i < n; ++i) bottom[i] = n - 1 - i, top[i] = n + i;  // bottom faces -w: reversed
  s.faces.push_back(bottom);
  s.faces.push_back(top);
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    s.faces.push_back({i, j, n + j, n + i});
  }
  return s;
}

TetMesh mesh_polyhedron(const PolyhedralMeshInput& input, Mesh3Stats* stats) {
  Mesh3Stats local;
  if (input.max_tets > 0) local.estimated_tets = check_tet_budget(input);
  const C3t3 c3t3 = [&] {
    try {
      return run_mesh_3(input, local);
    } catch (const CGAL::Failure_exception& e) {
      // Mesh_3 aborts on configurations its inexact constructions cannot resolve (seen only with many
      // protected edges on slanted faces, see cylinder_generator.hpp); a slightly different size helps.
      const std::string what = e.message().substr(0, e.message().find('\n'));
      throw Error("mesh.generate: expected CGAL Mesh_3 to mesh the shape, found it failed (" + what +
                  "); a slightly different size_min or size_max usually avoids this");
    }
  }();
  if (stats) *stats = local;
  if (c3t3.number_of_cells_in_complex() == 0)
    throw Error("mesh.generate: expected a tet mesh, found none (CGAL Mesh_3 produced no cells)");
  TetMesh mesh;
  std::unordered_map<const void*, int32_t> index;
  extract_tets(c3t3, mesh, index);
  extract_triangles(c3t3, input, mesh, index);
  return mesh;
}

}  // namespace rift
