// The sections that describe the run rather than the physics: scene, time, output, checkpoint.
#include <algorithm>
#include <array>

#include "engine/scene/output_fields.hpp"
#include "engine/scene/scene_names.hpp"
#include "engine/scene/scene_sections.hpp"

namespace rift {

void read_scene_section(MapReader& sec, Scene& scene) {
  scene.name = sec.string("name", std::nullopt);
  scene.description = sec.string("description", std::string(), /*allow_empty=*/true);
  sec.finish();
}

TimeSpec read_time_section(MapReader& sec) {
  TimeSpec t;
  t.end = sec.real("end", positive("s"), std::nullopt);
  t.dt = sec.optional_real("dt", positive("s"));
  t.safety = sec.real("safety", RealRule{"", 0.0, 1.0, true, false}, 0.5);
  t.allow_unstable_dt = sec.boolean("allow_unstable_dt", false);
  sec.finish();
  return t;
}

OutputSpec read_output_section(MapReader& sec) {
  OutputSpec o;
  o.interval = sec.real("interval", non_negative("s"), 0.0);
  for (size_t i : sec.choice_list("fields", kOutputFieldNames, {}, 0))
    o.fields.emplace_back(kOutputFieldNames[i]);
  o.surface = sec.boolean("surface", false);
  sec.finish();
  return o;
}

CheckpointSpec read_checkpoint_section(MapReader& sec) {
  CheckpointSpec c;
  c.every_steps = sec.integer("every_steps", IntRule{0, INT64_MAX}, 0);
  c.every_seconds = sec.real("every_seconds", non_negative("s"), 0.0);
  c.keep = static_cast<int32_t>(sec.integer("keep", IntRule{1, INT32_MAX}, 2));
  sec.finish();
  return c;
}

ReferenceMetricSpec read_reference_metric(MapReader& sec) {
  ReferenceMetricSpec m;
  m.name = sec.string("name", std::nullopt);
  const bool series = sec.has("series"), summary = sec.has("summary");
  if (series == summary)
    sec.error(series ? "summary" : "series",
              "exactly one of 'series' (a timeseries.csv column) or 'summary' (a summary.json path)");
  if (series) m.series = sec.string("series", std::nullopt);
  if (summary) {
    m.summary = sec.string("summary", std::nullopt);
    if (sec.has("reduce")) sec.forbid("reduce", "'reduce' applies to a 'series' only");
  }
  if (!summary)
    m.reduce = sec.choice("reduce", scene_names::kReduce, std::optional(ReferenceMetricSpec::Reduce::max));
  m.factor = sec.real("factor", any_real(""), 1.0);
  m.value = sec.optional_real("value", any_real(""));
  sec.finish();
  return m;
}

}  // namespace rift
