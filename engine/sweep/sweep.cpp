#include "engine/sweep/sweep.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/spawn.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/output_dir.hpp"
#include "engine/run_loop.hpp"
#include "engine/scene/load_scene.hpp"
#include "engine/sweep/reference_metrics.hpp"
#include "engine/sweep/sweep_plot.hpp"

namespace rift {

namespace fs = std::filesystem;
using nlohmann::json;

SweepAxis parse_sweep_axis(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw Error("--vary '" + text +
                "': expected key.path=value1,value2,... (e.g. mesh.generate.size_max=4e-3,2e-3)");
  SweepAxis axis{text.substr(0, eq), {}};
  std::string current;
  int depth = 0;
  for (char c : text.substr(eq + 1)) {
    depth += (c == '[') - (c == ']');
    if (c == ',' && depth == 0) {
      axis.values.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  axis.values.push_back(current);
  for (const auto& v : axis.values)
    if (v.empty()) throw Error("--vary '" + text + "': an empty value in the list");
  return axis;
}

namespace {

// Variant i's value index on each axis (the first axis varies slowest).
std::vector<size_t> digits_of(size_t i, const std::vector<SweepAxis>& axes) {
  std::vector<size_t> d(axes.size());
  for (size_t a = axes.size(); a-- > 0;) {
    d[a] = i % axes[a].values.size();
    i /= axes[a].values.size();
  }
  return d;
}

std::vector<std::string> variant_overrides(const SweepOptions& o, size_t i) {
  std::vector<std::string> out = o.overrides;
  const auto d = digits_of(i, o.axes);
  for (size_t a = 0; a < o.axes.size(); ++a) out.push_back(o.axes[a].key + "=" + o.axes[a].values[d[a]]);
  return out;
}

json definition(const SweepOptions& o, const std::vector<std::string>& metrics) {
  json axes = json::array();
  for (const auto& a : o.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
  return {{"scene", fs::absolute(o.scene_path).lexically_normal().string()},
          {"overrides", o.overrides},
          {"axes", axes},
          {"metrics", metrics}};
}

json row_to_json(const SweepRow& r) {
  json m = json::array();
  for (const auto& v : r.metrics) m.push_back(v ? json(*v) : json());
  return {{"index", r.index}, {"values", r.values}, {"status", r.status}, {"wall_seconds", r.wall_seconds},
          {"steps", r.steps}, {"tets", r.tets},     {"metrics", m}};
}

SweepRow row_from_json(const json& j) {
  SweepRow r;
  r.index = j.at("index").get<int>();
  r.values = j.at("values").get<std::vector<std::string>>();
  r.status = j.at("status").get<std::string>();
  r.wall_seconds = j.at("wall_seconds").get<double>();
  r.steps = j.at("steps").get<int64_t>();
  r.tets = j.at("tets").get<int64_t>();
  for (const auto& v : j.at("metrics"))
    r.metrics.push_back(v.is_null() ? std::nullopt : std::optional(v.get<double>()));
  return r;
}

// Errors against the analytic values, or against the finest variant; then the Pareto front.
void score(std::vector<SweepRow>& rows, const std::vector<std::optional<double>>& analytic) {
  const SweepRow* finest = nullptr;
  for (const auto& r : rows)
    if (r.status == "done" && (!finest || r.steps * r.tets >= finest->steps * finest->tets)) finest = &r;
  for (auto& r : rows) {
    r.errors.assign(analytic.size(), std::nullopt);
    r.error.reset();
    r.pareto = false;
    if (r.status != "done") continue;
    for (size_t m = 0; m < analytic.size(); ++m) {
      const std::optional<double> ref =
          analytic[m] ? analytic[m] : (finest ? finest->metrics[m] : std::nullopt);
      if (r.metrics[m] && ref) r.errors[m] = relative_error(*r.metrics[m], *ref);
      if (r.errors[m]) r.error = std::max(r.error.value_or(0.0), *r.errors[m]);
    }
  }
  for (auto& r : rows) {
    if (!r.error) continue;
    r.pareto = true;
    for (const auto& o : rows)
      if (&o != &r && o.error && o.wall_seconds <= r.wall_seconds && *o.error <= *r.error &&
          (o.wall_seconds < r.wall_seconds || *o.error < *r.error))
        r.pareto = false;
  }
}

std::string to_csv(const SweepOptions& o, const std::vector<std::string>& metrics,
                   const std::vector<SweepRow>& rows) {
  std::string csv = "variant";
  for (const auto& a : o.axes) csv += "," + a.key;
  csv += ",status,wall_seconds,steps,tets";
  for (const auto& m : metrics) csv += "," + m;
  for (const auto& m : metrics) csv += ",error_" + m;
  csv += ",error,pareto\n";
  auto number = [](const std::optional<double>& v) { return v ? fmt::format("{:.17g}", *v) : std::string(); };
  for (const auto& r : rows) {
    csv += fmt::format("v{:03d}", r.index);
    for (const auto& v : r.values) csv += ",\"" + v + "\"";
    std::string status = r.status;
    for (char& c : status)
      if (c == '"' || c == '\n' || c == ',') c = ' ';
    csv += fmt::format(",\"{}\",{:.6g},{},{}", status, r.wall_seconds, r.steps, r.tets);
    for (const auto& v : r.metrics) csv += "," + number(v);
    for (const auto& v : r.errors) csv += "," + number(v);
    csv += "," + number(r.error) + "," + (r.pareto ? "1" : "0") + "\n";
  }
  return csv;
}

// The plotter runs from an argument vector in the sweep's folder: the title (the scene's name) and the
// folder's path reach it as plain arguments, never through a shell.
std::string plot(const fs::path& dir, const std::string& title) {
  write_text_atomic(dir / "plot_sweep.py", kSweepPlotScript);
  const std::string py = python_with("matplotlib");
  if (py.empty())
    return "no plot: python3 with matplotlib is missing (Debian: apt-get install python3-matplotlib); then "
           "run python3 " +
           (dir / "plot_sweep.py").string() + " sweep.csv sweep.png";
  const fs::path log = dir / "plot_sweep.log";
  fs::remove(log);
  if (run_program({py, "plot_sweep.py", "sweep.csv", "sweep.png", title}, dir, log) != 0)
    return "no plot: plot_sweep.py failed, see " + log.string();
  return "plot: " + (dir / "sweep.png").string();
}

}  // namespace

SweepResult run_sweep(const SweepOptions& o) {
  if (!o.build_world) throw Error("rift sweep: no world builder was handed in (SweepOptions::build_world)");
  if (o.axes.empty()) throw Error("rift sweep: give at least one --vary key.path=v1,v2,...");
  size_t variants = 1;
  for (const auto& a : o.axes) variants *= a.values.size();
  // Every variant must be a valid scene before anything runs.
  std::vector<Scene> scenes;
  for (size_t i = 0; i < variants; ++i) scenes.push_back(load_scene(o.scene_path, variant_overrides(o, i)));
  SweepResult result;
  std::vector<std::optional<double>> analytic;
  for (const auto& m : scenes[0].reference) {
    result.metric_names.push_back(m.name);
    analytic.push_back(m.value);
  }
  const json def = definition(o, result.metric_names);
  const fs::path state = o.out_dir / "sweep.json";
  std::error_code ec;
  if (fs::exists(state, ec)) {
    std::ifstream in(state);
    const json old = json::parse(in, nullptr, false);
    if (!old.is_object() || old.value("definition", json()) != def)
      throw Error("rift sweep: " + o.out_dir.string() +
                  " holds a different sweep (sweep.json); give another --out, "
                  "or remove that folder to start again");
    try {
      for (const auto& r : old.at("rows")) result.rows.push_back(row_from_json(r));
    } catch (const json::exception& e) {
      throw Error("rift sweep: " + state.string() + " is damaged (" + e.what() +
                  "); remove that folder to start the sweep again");
    }
  }
  create_output_dir(o.out_dir);
  auto save = [&] {
    std::sort(result.rows.begin(), result.rows.end(),
              [](const auto& a, const auto& b) { return a.index < b.index; });
    score(result.rows, analytic);
    json rows = json::array();
    for (const auto& r : result.rows) rows.push_back(row_to_json(r));
    write_text_atomic(state, json{{"definition", def}, {"rows", rows}}.dump(1));
    write_text_atomic(o.out_dir / "sweep.csv", to_csv(o, result.metric_names, result.rows));
  };
  for (size_t i = 0; i < variants; ++i) {
    if (std::any_of(result.rows.begin(), result.rows.end(), [&](const auto& r) { return r.index == int(i); }))
      continue;
    const fs::path dir = o.out_dir / fmt::format("v{:03d}", i);
    fs::remove_all(dir, ec);  // what an interrupted variant left: it runs again from the start
    if (ec)
      throw Error("rift sweep: cannot remove " + dir.string() +
                  " to run that variant again: " + ec.message());
    SweepRow row;
    row.index = static_cast<int>(i);
    const auto d = digits_of(i, o.axes);
    std::string label;
    for (size_t a = 0; a < o.axes.size(); ++a) {
      row.values.push_back(o.axes[a].values[d[a]]);
      label += (label.empty() ? "" : " ") + o.axes[a].key + "=" + o.axes[a].values[d[a]];
    }
    std::cout << fmt::format("sweep: v{:03d} ({}/{}) {} ...", i, i + 1, variants, label) << std::flush;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      RunOptions ro;
      ro.out_dir = dir;
      ro.threads = o.threads;
      ro.progress = false;
      ro.overwrite = true;  // a variant not done (interrupted, failed) is run again from the start
      RunLoop sim(scenes[i], ro, o.build_world);
      const RunResult r = sim.run();
      row.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (r.stop_reason == "signal") {
        result.interrupted = true;
        std::cout << " interrupted\n";
        break;
      }
      row.status = "done";
      row.steps = r.steps;
      row.tets = int64_t(sim.world().mesh.tets.size());  // the solid's or the fluid's mesh
    } catch (const Error& e) {
      row.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      row.status = std::string("failed: ") + e.what();
    }
    for (const auto& m : read_reference_metrics(scenes[i].reference, dir)) row.metrics.push_back(m.value);
    if (row.status != "done") row.metrics.assign(result.metric_names.size(), std::nullopt);
    std::cout << fmt::format(" {} in {:.3g} s\n", row.status.substr(0, 120), row.wall_seconds);
    result.rows.push_back(std::move(row));
    ++result.ran;
    save();
  }
  save();
  if (!result.interrupted && o.plot) result.plot_note = plot(o.out_dir, scenes[0].name);
  return result;
}

}  // namespace rift
