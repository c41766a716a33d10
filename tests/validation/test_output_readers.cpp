// What a user reads is what Rift computed: a run of a known stress state read back through the XDMF
// index and its HDF5 files by independent readers (Python's XML parser and h5py), component by component.
// The block of scenes/validation/in_situ_block.yaml starts in equilibrium under a polyaxial stress, here
// rotated so that its six components all differ (a swap of any two shows), and at t = 0 every tet holds
// that tensor exactly.
// XDMF's Tensor6 is xx xy xz yy yz zz and ParaView's XDMF Reader expands it in that order: the stress must
// be written so (Rift keeps xx yy zz xy yz zx internally; written as stored, ParaView's YY was sigma_xy).
// Also through meshio, and through ParaView's three XDMF readers where pvpython is installed. Each check
// is skipped, saying so, when its reader is not installed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <string>

#include "engine/core/spawn.hpp"
#include "engine/scene/load_scene.hpp"
#include "tests/unit/test_io_temp_dir.hpp"
#include "tests/unit/test_run_support.hpp"

namespace rift {
namespace {

// argv: the index, then the expected xx xy xz yy yz zz. Checks the first output's solid grid.
constexpr const char* kCheck = R"py(
import sys, os, xml.etree.ElementTree as ET
import h5py, numpy as np
index = sys.argv[1]
expected = np.array([float(v) for v in sys.argv[2:8]])
root = ET.parse(index).getroot()
solid = next(g for g in root.iter("Grid") if g.get("GridType") == "Uniform" and g.get("Name") == "solid")
attribute = next(a for a in solid.iter("Attribute") if a.get("Name") == "stress")
assert attribute.get("AttributeType") == "Tensor6", attribute.get("AttributeType")
assert attribute.get("Center") == "Cell", attribute.get("Center")
item = attribute.find("DataItem")
name, dataset = item.text.strip().split(":", 1)
with h5py.File(os.path.join(os.path.dirname(index), name), "r") as f:
    stress = f[dataset][()]
assert stress.ndim == 2 and stress.shape[1] == 6, stress.shape
scale = np.abs(expected).max()
worst = np.abs(stress - expected).max() / scale
print(f"{stress.shape[0]} tets; first row {stress[0]}; worst deviation {worst:.2e} of |sigma|")
assert worst < 1e-9, worst
)py";

// A run of the rotated in-situ block into dir / "run"; returns its stress in Tensor6 order.
std::array<double, 6> known_stress_run(const test::TempDir& dir) {
  const Scene scene = load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/validation/in_situ_block.yaml",
                                 {"time.end=1.0e-7", "solid.initial_stress.direction_1=[1, 2, 0]",
                                  "solid.initial_stress.direction_2=[-2, 1, 3]"});
  EXPECT_TRUE(scene.solid && scene.solid->initial_stress);
  EXPECT_TRUE(test::run_scene(scene, dir / "run", 1).completed);
  const auto s = scene.solid->initial_stress->tensor();  // xx yy zz xy yz zx
  for (int c = 0; c < 6; ++c)
    for (int d = 0; d < c; ++d) EXPECT_GT(std::abs(s[c] - s[d]), 1e5) << "components must differ: " << c << d;
  return {s[0], s[3], s[5], s[1], s[4], s[2]};
}

// Runs argv followed by the six expected values, prints its output, returns its status.
int run_check(std::vector<std::string> argv, const std::array<double, 6>& tensor6, const test::TempDir& dir) {
  for (double v : tensor6) argv.push_back(fmt::format("{:.17g}", v));
  const std::filesystem::path log = dir / "check.log";
  const int status = run_program(argv, {}, log);
  std::printf("%s", test::slurp(log).c_str());
  return status;
}

TEST(OutputReaders, StressReadsInTensor6OrderWithH5py) {
  const std::string py = python_with("h5py, numpy");
  if (py.empty()) GTEST_SKIP() << "no python3 with h5py and numpy (Debian: apt-get install python3-h5py)";
  test::TempDir dir;
  const auto tensor6 = known_stress_run(dir);
  std::ofstream(dir / "check.py") << kCheck;
  EXPECT_EQ(run_check({py, (dir / "check.py").string(), (dir / "run" / "rift.xdmf").string()}, tensor6, dir),
            0);
}

// meshio reads one grid's index (rift_solid.xdmf, XDMF 3.0) as a time series: the stress at t = 0 in
// Tensor6 order, and the mesh.
constexpr const char* kMeshio = R"py(
import sys
import meshio, numpy as np
expected = np.array([float(v) for v in sys.argv[2:8]])
with meshio.xdmf.TimeSeriesReader(sys.argv[1]) as reader:
    points, cells = reader.read_points_cells()
    assert cells[0].type == "tetra", cells[0].type
    t, point_data, cell_data = reader.read_data(0)
    assert t == 0.0, t
    stress = cell_data["stress"][0]
    assert stress.shape == (len(cells[0].data), 6), stress.shape
    worst = np.abs(stress - expected).max() / np.abs(expected).max()
    print(f"meshio {meshio.__version__}: {reader.num_steps} steps, {len(points)} points, {stress.shape[0]} tets, "
          f"worst {worst:.1e}; point data {sorted(point_data)}")
    assert worst < 1e-9, worst
)py";

TEST(OutputReaders, MeshioReadsOneGridsSeries) {
  const std::string py = python_with("meshio, numpy");
  if (py.empty()) GTEST_SKIP() << "no python3 with meshio (Debian: apt-get install python3-meshio)";
  test::TempDir dir;
  const auto tensor6 = known_stress_run(dir);
  std::ofstream(dir / "check.py") << kMeshio;
  EXPECT_EQ(
      run_check({py, (dir / "check.py").string(), (dir / "run" / "rift_solid.xdmf").string()}, tensor6, dir),
      0);
}

// ParaView's three XDMF readers (scripts/check_paraview_readers.py), where ParaView is installed.
TEST(OutputReaders, ParaViewsThreeXdmfReadersShowTheSameStress) {
  if (find_program("pvpython").empty() || find_program("xvfb-run").empty())
    GTEST_SKIP() << "SKIP: pvpython or xvfb-run not installed (Debian: apt-get install paraview "
                    "python3-paraview xvfb); ParaView's readers not checked";
  test::TempDir dir;
  const auto tensor6 = known_stress_run(dir);
  EXPECT_EQ(
      run_check({"xvfb-run", "-a", "pvpython",
                 std::string(RIFT_SOURCE_DIR) + "/scripts/check_paraview_readers.py", (dir / "run").string()},
                tensor6, dir),
      0);
}

}  // namespace
}  // namespace rift
