#include "engine/render/run_render.hpp"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "engine/core/spawn.hpp"
#include "engine/io/atomic_file.hpp"
#include "rift/render_script.hpp"

namespace rift {

namespace fs = std::filesystem;

namespace {

// pvpython from Debian draws through X: without a display it runs inside xvfb-run's virtual one.
std::vector<std::string> pvpython_command(std::string& problem) {
  const std::string pvpython = find_program("pvpython");
  if (pvpython.empty()) {
    problem = "ParaView's pvpython is missing (Debian: apt-get install paraview python3-paraview xvfb)";
    return {};
  }
  const char* display = std::getenv("DISPLAY");
  if (display && *display) return {pvpython};
  const std::string xvfb = find_program("xvfb-run");
  if (xvfb.empty()) {
    problem = "no display and no xvfb-run to draw without one (Debian: apt-get install xvfb)";
    return {};
  }
  return {xvfb, "-a", "-s", "-screen 0 1280x1024x24", pvpython};
}

bool display_was_refused(const fs::path& log) {
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);)
    for (const char* sign :
         {"bad X server connection", "Xvfb failed to start", "cannot open display", "Can't open display"})
      if (line.find(sign) != std::string::npos) return true;
  return false;
}

}  // namespace

RenderResult render_run(const fs::path& run_dir, const RenderOptions& o) {
  RenderResult r;
  if (!fs::is_regular_file(run_dir / "rift.series.json")) {
    r.problem = "no " + (run_dir / "rift.series.json").string() +
                ": give the output folder of a run that wrote fields (output.interval)";
    return r;
  }
  const fs::path out = o.out_dir.empty() ? run_dir / "pictures" : o.out_dir;
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) {
    r.problem = "cannot create " + out.string() + ": " + ec.message();
    return r;
  }
  const fs::path script = out / "render_run.py";
  std::string text;
  for (const std::string_view part : generated::render_run_script_parts) text += part;
  write_text_atomic(script, text);
  std::vector<std::string> command = pvpython_command(r.problem);
  std::vector<std::string> args = {script.string(), run_dir.string(), out.string(), "--normal", o.normal,
                                   "--times",       o.times,          "--size",     o.size};
  if (!o.field.empty()) args.insert(args.end(), {"--field", o.field});
  if (!o.at.empty()) args.insert(args.end(), {"--at", o.at});
  if (!o.range.empty()) args.insert(args.end(), {"--range", o.range});
  if (command.empty()) {
    r.problem += "; then run: xvfb-run -a pvpython";
    for (const auto& a : args) r.problem += " " + a;
    return r;
  }
  command.insert(command.end(), args.begin(), args.end());
  const fs::path log = out / "render_run.log";
  // xvfb-run -a takes the first display number without a lock file: two runs starting together may both
  // take it (one server fails to start), or find a server that another run is stopping (the connection
  // is refused). Those, and only those, are tried again, waiting 1, 2, 4 and 8 s: on a loaded machine
  // three tries 0.5 and 1 s apart were all refused once (a CI run beside a 1e7-tet partition).
  int status = 0;
  for (int attempt = 0; attempt < 5; ++attempt) {
    fs::remove(log, ec);
    status = run_program(command, {}, log);
    if (status == 0 || !display_was_refused(log)) break;
    std::this_thread::sleep_for(std::chrono::seconds(1 << attempt));
  }
  std::ifstream written(log);
  std::string message;
  for (std::string line; std::getline(written, line);) {
    if (line.ends_with(".png"))
      r.pictures.emplace_back(line);
    else if (line.starts_with("rift render: "))
      message = line.substr(13);
  }
  if (status != 0)
    r.problem = !message.empty() ? message : "render_run.py failed, see " + log.string();
  else if (r.pictures.empty())
    r.problem = "nothing was drawn, see " + log.string();
  return r;
}

}  // namespace rift
