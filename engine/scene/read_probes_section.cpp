// The `probes` section: gauges that read a field at points (probe_fields.hpp).
#include <algorithm>
#include <string>
#include <vector>

#include "engine/scene/probe_fields.hpp"
#include "engine/scene/scene_sections.hpp"

namespace rift {
namespace {

// A probe's name becomes a time-series column and a summary.json key: letters, digits and '_' only.
bool plain_name(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::vector<std::string_view> field_names() {
  std::vector<std::string_view> names;
  for (const ProbeField& f : kProbeFields) names.push_back(f.name);
  return names;
}

std::vector<ProbePointSpec> read_points(MapReader& sec, size_t min_items) {
  std::vector<ProbePointSpec> points;
  for (MapReader& point : sec.section_list("points", min_items)) {
    ProbePointSpec q;
    q.at = point.vec3("at", any_real("m"), std::nullopt);
    q.value = point.optional_real("value", any_real(""));
    point.finish();
    points.push_back(q);
  }
  return points;
}

// `count` points from `from` to `to`, both ends included.
std::vector<ProbePointSpec> read_line(MapReader& sec) {
  MapReader line = sec.section("line", true);
  const auto from = line.vec3("from", any_real("m"), std::nullopt);
  const auto to = line.vec3("to", any_real("m"), std::nullopt);
  const auto count = line.integer("count", IntRule{2, 100000}, std::nullopt);
  line.finish();
  std::vector<ProbePointSpec> points(static_cast<size_t>(count));
  for (size_t i = 0; i < points.size(); ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(count - 1);
    for (int d = 0; d < 3; ++d) points[i].at[d] = from[d] + s * (to[d] - from[d]);
  }
  return points;
}

}  // namespace

ProbeSpec read_probe(MapReader& sec, bool has_solid, bool has_fluid) {
  ProbeSpec p;
  p.name = sec.string("name", std::nullopt);
  if (sec.ok("name") && !plain_name(p.name))
    sec.error("name",
              "letters, digits and '_' only (it names a timeseries.csv column and a summary.json key)");
  static const std::vector<std::string_view> names = field_names();
  const ProbeField& field = kProbeFields[sec.choice("field", names, std::nullopt)];
  p.field = std::string(field.name);
  const bool model_present = field.name.starts_with("fluid.") ? has_fluid : has_solid;
  if (sec.ok("field") && !model_present)
    sec.error("field", std::string("a field of a model in the scene (") + std::string(field.name) +
                           " needs a " + (field.name.starts_with("fluid.") ? "fluid" : "solid") +
                           " section)");
  p.component = sec.string("component", std::string(field.components.front()));
  if (sec.ok("component") &&
      std::find(field.components.begin(), field.components.end(), p.component) == field.components.end())
    sec.error("component", "one of " + join_names(field.components) + " for " + std::string(field.name));
  p.factor = sec.real("factor", any_real(""), 1.0);
  // Either a list of points (each with its known value, if any) or a line of evenly spaced points.
  const bool line = sec.has("line");
  if (line && sec.has("points")) sec.error("line", "either points or line, not both");
  if (line) {
    p.points = read_line(sec);
    MapReader unused = sec.unused();
    read_points(unused, 0);
  } else {
    p.points = read_points(sec, 1);
    MapReader unused = sec.unused();
    read_line(unused);
  }
  sec.finish();
  return p;
}

}  // namespace rift
