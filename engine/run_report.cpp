#include "engine/run_report.hpp"

#include <fmt/format.h>

#include <cmath>

namespace rift {
namespace {

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

void solid_lines(const nlohmann::json& s, std::string& out) {
  if (s.contains("fractures")) {
    const auto& f = s["fractures"];
    out += fmt::format(
        "  solid: {:.0f} of {:.0f} joints broken ({:.0f} tensile, {:.0f} shear; {:.0f} cut at "
        "set-up)\n",
        number(s, "broken_joints"), number(s, "joints"), number(f, "tensile"), number(f, "shear"),
        number(f, "initial"));
  }
  if (!s.contains("energy")) return;
  const auto& e = s["energy"];
  const double work = number(e, "external_work"), error = number(e, "balance_error");
  out += fmt::format(
      "  energy [J]: work {:.4g}; kinetic {:.4g}, elastic {:.4g}, joints {:.4g}, fracture {:.4g}, friction "
      "{:.4g}, damping {:.4g}; balance error {:.3g}",
      work, number(e, "kinetic"), number(e, "elastic"), number(e, "joint_stored"), number(e, "fracture"),
      number(e, "friction"), number(e, "damping"), error);
  if (std::abs(work) > 0.0)
    out += fmt::format(" ({:.3g} % of the work)", 100.0 * std::abs(error) / std::abs(work));
  out += "\n";
}

}  // namespace

std::string run_report(const nlohmann::json& summary) {
  std::string out;
  const nlohmann::json metrics = summary.value("metrics", nlohmann::json::object());
  if (metrics.contains("solid")) solid_lines(metrics["solid"], out);
  if (metrics.contains("mesh_conversion")) {
    const auto& m = metrics["mesh_conversion"];
    out +=
        fmt::format("  surface: {:.0f} fragments, {:.0f} fracture surfaces, {:.0f} fracture triangles\n",
                    number(m, "fragments"), number(m, "fracture_surfaces"), number(m, "fracture_triangles"));
  }
  if (metrics.contains("fracture_flow")) {
    const auto& f = metrics["fracture_flow"];
    out += fmt::format(
        "  fracture flow: well pressure {:.4g} Pa, injected {:.4g} m^3, fluid in the well and the cracks "
        "{:.4g} m^3 (crack volume {:.4g} m^3), wet area {:.4g} of {:.4g} m^2\n",
        number(f, "well_pressure"), number(f, "injected_volume"), number(f, "fluid_volume"),
        number(f, "crack_volume"), number(f, "wet_area"), number(f, "crack_area"));
  }
  if (metrics.contains("fluid")) {
    const auto& f = metrics["fluid"];
    out += fmt::format("  fluid: max CFL {:.3g}, max divergence {:.3g} 1/s, Picard failures {:.0f}",
                       number(f, "max_cfl"), number(f, "max_divergence"), number(f, "picard_failures"));
    if (f.contains("last_step")) {
      const auto& l = f["last_step"];
      out += fmt::format("; last step {:.0f} Picard, {:.0f} FGMRES, {:.0f} BiCGSTAB iterations",
                         number(l, "picard_iterations"), number(l, "schur_iterations"),
                         number(l, "velocity_iterations"));
    }
    out += "\n";
  }
  if (!out.empty()) out = "physics:\n" + out;
  const double run = number(summary, "wall_seconds");
  const double meshing = summary.contains("mesh") ? number(summary["mesh"], "seconds") : NAN;
  if (std::isfinite(run)) {
    if (std::isfinite(meshing))
      out += fmt::format("wall time: {:.3g} s (meshing {:.3g} s, the run {:.3g} s)\n", run + meshing, meshing,
                         run);
    else
      out += fmt::format("wall time: {:.3g} s\n", run);
  }
  return out;
}

}  // namespace rift
