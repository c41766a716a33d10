#pragma once
// Gauges (the scene's `probes` section, engine/scene/probe_fields.hpp): fields of the solid and the fluid
// read at fixed points. Each point is a time-series column (`probe_<name>` for one point,
// `probe_<name>_<i>` for several); summary.json's metrics.probes.<name> holds the final readings and,
// where the scene gives known values, their errors. A solid probe is located once in the reference
// configuration and moves with the rock; a fluid probe is fixed in space and located again whenever the fluid
// mesh is remade. The model has no systems: it only reads the store between steps.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/table.hpp"
#include "engine/model.hpp"
#include "engine/scene/scene.hpp"
#include "kernels/tet_point_location.hpp"

namespace rift {

class ProbeModel final : public Model {
 public:
  ProbeModel(const Store& store, std::vector<ProbeSpec> probes);
  std::string name() const override { return "probes"; }
  void metrics(double time, std::vector<std::pair<std::string, double>>& row) override;
  void summarize(nlohmann::json& summary) const override;

 private:
  enum class Read { nodal_scalar, nodal_vector, displacement, tet_stress };
  struct Gauge {
    ProbeSpec spec;
    bool fluid = false;
    Read read = Read::nodal_scalar;
    const char* column = "";         // the store column read (nodes or tets of the gauge's model)
    size_t component = 0;            // index into the field's components (probe_fields.hpp)
    std::vector<std::string> names;  // the time-series column of each point
    std::vector<kernels::TetPointLocation> where;
    std::vector<double> reading;  // factor x the field at each point, at the last time-series row
  };
  void locate(Gauge& g) const;  // throws when a point lies outside the mesh
  int64_t fluid_mesh_revision() const;
  double read(const Gauge& g, const kernels::TetPointLocation& where) const;

  const Store& store_;
  std::vector<Gauge> gauges_;
  int64_t fluid_revision_ = 0;  // the fluid mesh the fluid gauges were located in
};

}  // namespace rift
