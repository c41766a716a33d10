#include "engine/plot/run_plot.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/spawn.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/plot/run_plot_script.hpp"

namespace rift {

namespace fs = std::filesystem;

RunPlotResult plot_run(const fs::path& run_dir, const fs::path& out_dir) {
  RunPlotResult r;
  const fs::path csv = run_dir / "timeseries.csv";
  if (!fs::is_regular_file(csv)) {
    r.problem = "no " + csv.string() + ": give the output folder of a run (it holds timeseries.csv)";
    return r;
  }
  const fs::path out = out_dir.empty() ? run_dir / "plots" : out_dir;
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) {
    r.problem = "cannot create " + out.string() + ": " + ec.message();
    return r;
  }
  std::string title = run_dir.filename().string();
  std::ifstream summary(run_dir / "summary.json");
  if (summary) {
    const auto j = nlohmann::json::parse(summary, nullptr, /*allow_exceptions=*/false);
    if (!j.is_discarded() && j.contains("scene") && j["scene"].is_object() && j["scene"].contains("name"))
      title = j["scene"]["name"].get<std::string>();
  }
  const fs::path script = out / "plot_run.py";
  write_text_atomic(script, kRunPlotScript);
  const std::string py = python_with("matplotlib");
  if (py.empty()) {
    r.problem =
        "python3 with matplotlib is missing (Debian: apt-get install python3-matplotlib); then run "
        "python3 " +
        script.string() + " " + csv.string() + " " + out.string() + " " + title;
    return r;
  }
  const fs::path log = out / "plot_run.log";
  fs::remove(log, ec);
  if (run_program({py, script.string(), csv.string(), out.string(), title}, {}, log) != 0) {
    r.problem = "plot_run.py failed, see " + log.string();
    return r;
  }
  std::ifstream written(log);
  for (std::string line; std::getline(written, line);)
    if (line.ends_with(".png")) r.pictures.emplace_back(line);
  if (r.pictures.empty()) r.problem = "timeseries.csv has no series to draw";
  return r;
}

}  // namespace rift
