#include "systems/probe_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/scene/probe_fields.hpp"
#include "systems/fluid/fluid_tables.hpp"
#include "systems/solid_tables.hpp"

namespace rift {
namespace {

// A point counts as inside a tet down to this barycentric coordinate: round-off on a face or corner.
constexpr double kInsideTolerance = 1e-9;

std::string describe(const std::array<double, 3>& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
  return buf;
}

}  // namespace

ProbeModel::ProbeModel(const Store& store, std::vector<ProbeSpec> probes) : store_(store) {
  for (ProbeSpec& spec : probes) {
    Gauge g;
    const ProbeField& field = *find_probe_field(spec.field);
    g.component =
        static_cast<size_t>(std::find(field.components.begin(), field.components.end(), spec.component) -
                            field.components.begin());
    g.fluid = spec.field.starts_with("fluid.");
    if (spec.field == "fluid.pressure") {
      g.column = "pressure";
    } else if (spec.field == "fluid.velocity") {
      g.read = Read::nodal_vector, g.column = "velocity";
    } else if (spec.field == "solid.velocity") {
      g.read = Read::nodal_vector, g.column = "v";
    } else if (spec.field == "solid.displacement") {
      g.read = Read::displacement, g.column = "x";
    } else {
      g.read = Read::tet_stress, g.column = "stress";
    }
    g.spec = std::move(spec);
    const size_t n = g.spec.points.size();
    for (size_t i = 0; i < n; ++i)
      g.names.push_back("probe_" + g.spec.name + (n == 1 ? "" : "_" + std::to_string(i)));
    g.reading.assign(n, 0.0);
    locate(g);
    gauges_.push_back(std::move(g));
  }
  fluid_revision_ = fluid_mesh_revision();
}

int64_t ProbeModel::fluid_mesh_revision() const {
  return fluid::step::remeshes.exists(store_) ? fluid::step::remeshes.read(store_)[0] : 0;
}

void ProbeModel::locate(Gauge& g) const {
  const Table& nodes = store_.table(g.fluid ? fluid::node_table : solid::node_table);
  const Table& tets = store_.table(g.fluid ? fluid::tet_table : solid::tet_table);
  const auto x = nodes.span<const double>(g.fluid ? "x" : "x0");
  const auto tet_nodes = tets.span<const int32_t>("nodes");
  g.where.clear();
  for (size_t i = 0; i < g.spec.points.size(); ++i) {
    const auto& at = g.spec.points[i].at;
    const kernels::TetPointLocation where = kernels::locate_in_tets(at.data(), x, tet_nodes, 0.0);
    if (where.tet < 0 || where.lowest < -kInsideTolerance)
      throw Error("probes: point " + std::to_string(i) + " of '" + g.spec.name + "' at " + describe(at) +
                  " lies outside the " + (g.fluid ? "fluid mesh" : "solid in its reference configuration") +
                  "; a probe reads inside the mesh (check its coordinates against the mesh's extent, in m)");
    g.where.push_back(where);
  }
}

double ProbeModel::read(const Gauge& g, const kernels::TetPointLocation& where) const {
  const Table& tets = store_.table(g.fluid ? fluid::tet_table : solid::tet_table);
  if (g.read == Read::tet_stress)
    return tets.span<const double>(g.column)[6 * static_cast<size_t>(where.tet) + g.component];
  const Table& nodes = store_.table(g.fluid ? fluid::node_table : solid::node_table);
  const auto tet_nodes = tets.span<const int32_t>("nodes");
  const auto f = nodes.span<const double>(g.column);
  if (g.read == Read::nodal_scalar) return kernels::interpolate_p1(where, tet_nodes, f, 1, 0);
  double v[3];
  for (size_t d = 0; d < 3; ++d) {
    v[d] = kernels::interpolate_p1(where, tet_nodes, f, 3, d);
    if (g.read == Read::displacement)
      v[d] -= kernels::interpolate_p1(where, tet_nodes, nodes.span<const double>("x0"), 3, d);
  }
  return g.component < 3 ? v[g.component] : std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

void ProbeModel::metrics(double, std::vector<std::pair<std::string, double>>& row) {
  const int64_t revision = fluid_mesh_revision();
  const bool relocate = revision != fluid_revision_;
  fluid_revision_ = revision;
  for (Gauge& g : gauges_) {
    if (g.fluid && relocate) locate(g);
    for (size_t i = 0; i < g.where.size(); ++i) {
      g.reading[i] = g.spec.factor * read(g, g.where[i]);
      row.emplace_back(g.names[i], g.reading[i]);
    }
  }
}

void ProbeModel::summarize(nlohmann::json& summary) const {
  auto& all = summary["probes"];
  for (const Gauge& g : gauges_) {
    auto& s = all[g.spec.name];
    s["field"] = g.spec.field;
    s["component"] = g.spec.component;
    s["field_unit"] = std::string(find_probe_field(g.spec.field)->unit);
    s["factor"] = g.spec.factor;
    s["values"] = g.reading;
    nlohmann::json known = nlohmann::json::array();
    double max_error = 0.0, sum2 = 0.0;
    size_t compared = 0;
    for (size_t i = 0; i < g.reading.size(); ++i) {
      const auto& value = g.spec.points[i].value;
      known.push_back(value ? nlohmann::json(*value) : nlohmann::json(nullptr));
      if (!value) continue;
      const double e = std::abs(g.reading[i] - *value);
      max_error = std::max(max_error, e);
      sum2 += e * e;
      ++compared;
    }
    if (compared == 0) continue;
    s["known"] = known;
    s["compared"] = compared;
    s["max_error"] = max_error;
    s["rms_error"] = std::sqrt(sum2 / static_cast<double>(compared));
  }
}

}  // namespace rift
