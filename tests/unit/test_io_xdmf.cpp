// XDMF time series: what the index says must be exactly what the HDF5 files hold. Every check reads
// the .xdmf text, follows its DataItem paths into the HDF5 files and compares bytes with the arrays
// that were written; nothing is compared with a hand-written expected index.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/io/hdf5_file.hpp"
#include "engine/io/xdmf_series.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

using test::slurp;

ino_t inode(const std::filesystem::path& path) {
  struct stat st {};
  EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
  return st.st_ino;  // an atomic rewrite (temp + rename) always gives a new inode
}

std::vector<std::string> files_containing(const std::filesystem::path& dir, const std::string& part) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().find(part) != std::string::npos)
      out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

// ---- the data written: two tets on five nodes, fields whose values depend on the step ----

struct Mesh {
  std::vector<double> points{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  std::vector<int32_t> cells{0, 1, 2, 3, 1, 2, 3, 4};
};

struct StepData {
  std::vector<double> pressure;      // node, scalar, f64
  std::vector<double> displacement;  // node, vector, f64
  std::vector<int64_t> node_id;      // node, scalar, i64
  std::vector<float> damage;         // cell, scalar, f32
  std::vector<double> traction;      // cell, vector, f64
  std::vector<uint32_t> region;      // cell, scalar, u32
  std::vector<uint8_t> broken;       // cell, scalar, u8

  explicit StepData(int64_t step) {
    for (int i = 0; i < 5; ++i) {
      pressure.push_back(1e6 * step + i + 0.1);
      for (int c = 0; c < 3; ++c) displacement.push_back(step * 1e-3 + i * 1e-4 + c * 1e-5);
      node_id.push_back(1000000000000ll * step + i);
    }
    for (int e = 0; e < 2; ++e) {
      damage.push_back(0.125f * step + e / 3.0f);
      for (int c = 0; c < 3; ++c) traction.push_back(-step * 7.0 / 3.0 + e + c * 0.1);
      region.push_back(4000000000u + step + e);
      broken.push_back(static_cast<uint8_t>(step + e) & 1);
    }
  }

  XdmfGrid grid(const Mesh& mesh, uint64_t revision) const {
    XdmfGrid g{"solid", Topology::tetrahedron, mesh.points.data(), 5, mesh.cells.data(), 2, revision, false,
               {}};
    g.fields = {{"pressure", Center::node, 1, ElementType::f64, pressure.data(), 5},
                {"displacement", Center::node, 3, ElementType::f64, displacement.data(), 5},
                {"node_id", Center::node, 1, ElementType::i64, node_id.data(), 5},
                {"damage", Center::cell, 1, ElementType::f32, damage.data(), 2},
                {"traction", Center::cell, 3, ElementType::f64, traction.data(), 2},
                {"region", Center::cell, 1, ElementType::u32, region.data(), 2},
                {"broken", Center::cell, 1, ElementType::u8, broken.data(), 2}};
    return g;
  }
};

// ---- reading the index back with plain string search ----

struct Item {
  std::string dimensions, number_type, precision, file, path;
};

struct Attribute {
  std::string type, center;
  Item item;
};

struct Grid {
  std::string name;
  double time = -1;
  std::string topology;
  size_t elements = 0;
  Item cells, points;
  std::map<std::string, Attribute> attributes;
};

// The value of attribute `name` in the tag that starts at `text[at]`.
std::string xml_attr(const std::string& text, size_t at, const std::string& name) {
  const size_t tag_end = text.find('>', at);
  const size_t start = text.find(" " + name + "=\"", at);
  if (start == std::string::npos || start > tag_end) return "(missing " + name + ")";
  const size_t value = start + name.size() + 3;
  return text.substr(value, text.find('"', value) - value);
}

// The first <DataItem> at or after `at`: its attributes and its "file:path" text.
Item parse_item(const std::string& text, size_t at) {
  const size_t open = text.find("<DataItem", at);
  EXPECT_NE(open, std::string::npos);
  if (open == std::string::npos) return {};
  const size_t body = text.find('>', open) + 1;
  const std::string content = text.substr(body, text.find("</DataItem>", body) - body);
  const size_t colon = content.find(':');
  EXPECT_EQ(xml_attr(text, open, "Format"), "HDF");
  return {xml_attr(text, open, "Dimensions"), xml_attr(text, open, "NumberType"),
          xml_attr(text, open, "Precision"), content.substr(0, colon), content.substr(colon + 1)};
}

// Every Uniform grid of the index, in document order (a uniform grid has no nested <Grid>), read
// with plain string search.
std::vector<Grid> parse_index(const std::string& xml) {
  std::vector<Grid> grids;
  for (size_t at = xml.find("GridType=\"Uniform\""); at != std::string::npos;
       at = xml.find("GridType=\"Uniform\"", at + 1)) {
    const size_t open = xml.rfind("<Grid ", at);
    const std::string block = xml.substr(open, xml.find("</Grid>", at) - open);
    Grid g;
    g.name = xml_attr(block, 0, "Name");
    if (const size_t t = block.find("<Time "); t != std::string::npos)
      g.time = std::stod(xml_attr(block, t, "Value"));
    if (const size_t t = block.find("<Topology "); t != std::string::npos) {
      g.topology = xml_attr(block, t, "TopologyType");
      g.elements = std::stoul(xml_attr(block, t, "NumberOfElements"));
      g.cells = parse_item(block, t);
    }
    if (const size_t t = block.find("<Geometry "); t != std::string::npos) {
      EXPECT_EQ(xml_attr(block, t, "GeometryType"), "XYZ");
      g.points = parse_item(block, t);
    }
    for (size_t a = block.find("<Attribute "); a != std::string::npos; a = block.find("<Attribute ", a + 1))
      g.attributes[xml_attr(block, a, "Name")] = {xml_attr(block, a, "AttributeType"),
                                                  xml_attr(block, a, "Center"), parse_item(block, a)};
    grids.push_back(std::move(g));
  }
  return grids;
}

// The item must describe `rows x components` values of `type`, and the HDF5 dataset it names must
// hold exactly the bytes of `expected`.
template <class T>
void expect_item(const std::filesystem::path& dir, const Item& item, const std::vector<T>& expected,
                 int components) {
  constexpr ElementType type = element_type_of<T>();
  const size_t rows = expected.size() / components;
  SCOPED_TRACE(item.file + ":" + item.path);
  EXPECT_EQ(item.dimensions,
            components == 1 ? std::to_string(rows) : std::to_string(rows) + " " + std::to_string(components));
  const std::map<ElementType, std::pair<std::string, std::string>> xdmf_type{
      {ElementType::f64, {"Float", "8"}}, {ElementType::f32, {"Float", "4"}},
      {ElementType::i64, {"Int", "8"}},   {ElementType::i32, {"Int", "4"}},
      {ElementType::u32, {"UInt", "4"}},  {ElementType::u8, {"UChar", "1"}}};
  EXPECT_EQ(item.number_type, xdmf_type.at(type).first);
  EXPECT_EQ(item.precision, xdmf_type.at(type).second);
  H5File h5(dir / item.file, H5File::Mode::read);
  const H5DatasetInfo info = h5.info(item.path);
  ASSERT_EQ(info.type, type);
  ASSERT_EQ(info.rows, rows);
  ASSERT_EQ(info.components, components);
  const std::vector<T> back = h5.read<T>(item.path);
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(std::memcmp(back.data(), expected.data(), expected.size() * sizeof(T)), 0);
}

void expect_step(const std::filesystem::path& dir, const Grid& g, int64_t step, const Mesh& mesh) {
  SCOPED_TRACE("step " + std::to_string(step));
  const StepData d(step);
  EXPECT_EQ(g.topology, "Tetrahedron");
  EXPECT_EQ(g.elements, 2u);
  expect_item(dir, g.cells, mesh.cells, 4);
  expect_item(dir, g.points, mesh.points, 3);
  ASSERT_EQ(g.attributes.size(), 7u);
  const auto& a = g.attributes;
  EXPECT_EQ(a.at("pressure").center, "Node");
  EXPECT_EQ(a.at("pressure").type, "Scalar");
  EXPECT_EQ(a.at("displacement").type, "Vector");
  EXPECT_EQ(a.at("traction").center, "Cell");
  expect_item(dir, a.at("pressure").item, d.pressure, 1);
  expect_item(dir, a.at("displacement").item, d.displacement, 3);
  expect_item(dir, a.at("node_id").item, d.node_id, 1);
  expect_item(dir, a.at("damage").item, d.damage, 1);
  expect_item(dir, a.at("traction").item, d.traction, 3);
  expect_item(dir, a.at("region").item, d.region, 1);
  expect_item(dir, a.at("broken").item, d.broken, 1);
}

void write_step(XdmfSeries& series, double time, int64_t step, const Mesh& mesh, uint64_t revision) {
  const StepData d(step);
  const std::vector<XdmfGrid> grids{d.grid(mesh, revision)};
  series.write(time, step, grids);
}

// Tags open and close in matching pairs with one root element: enough to catch a torn or
// mis-nested index without an XML parser.
bool balanced_tags(const std::string& xml) {
  std::vector<std::string> open;
  int roots = 0;
  for (size_t i = xml.find('<'); i != std::string::npos; i = xml.find('<', i)) {
    const size_t end = xml.find('>', i);
    if (end == std::string::npos) return false;
    const std::string tag = xml.substr(i + 1, end - i - 1);
    i = end + 1;
    if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
      continue;
    }
    if (open.empty()) ++roots;
    if (tag.back() != '/') open.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
  }
  return open.empty() && roots == 1;
}

// ---- tests ----

TEST(XdmfSeries, ThreeOutputsReadBackThroughTheIndex) {
  test::TempDir dir;
  const Mesh mesh;
  XdmfSeries series(dir.path(), "out");
  write_step(series, 0.0, 0, mesh, 3);
  const auto mesh_file = dir / "out_mesh_solid_3.h5";
  const ino_t mesh_inode = inode(mesh_file);
  write_step(series, 0.25, 5, mesh, 3);
  write_step(series, 0.5, 10, mesh, 3);
  EXPECT_EQ(series.entries(), 3u);

  const std::string xml = slurp(dir / "out.xdmf");
  EXPECT_TRUE(balanced_tags(xml)) << xml;
  EXPECT_NE(xml.find("<Xdmf Version=\"2.0\">"), std::string::npos);
  EXPECT_NE(xml.find("CollectionType=\"Temporal\""), std::string::npos);
  const std::vector<Grid> grids = parse_index(xml);
  ASSERT_EQ(grids.size(), 3u);
  const double times[] = {0.0, 0.25, 0.5};
  const int64_t steps[] = {0, 5, 10};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(grids[i].name, "solid");
    EXPECT_EQ(grids[i].time, times[i]);  // quarter values print and parse exactly
    EXPECT_EQ(grids[i].cells.file, "out_mesh_solid_3.h5");
    expect_step(dir.path(), grids[i], steps[i], mesh);
  }
  EXPECT_EQ(grids[2].attributes.at("pressure").item.file, "out_00000010.h5");

  // One mesh file, written once; one data file per output; no temporaries left.
  EXPECT_EQ(files_containing(dir.path(), "_mesh_"), std::vector<std::string>{"out_mesh_solid_3.h5"});
  EXPECT_EQ(inode(mesh_file), mesh_inode);
  EXPECT_EQ(files_containing(dir.path(), "out_000"),
            (std::vector<std::string>{"out_00000000.h5", "out_00000005.h5", "out_00000010.h5"}));
  EXPECT_TRUE(files_containing(dir.path(), ".tmp-").empty());
  EXPECT_TRUE(std::filesystem::exists(dir / "out.series.json"));
}

TEST(XdmfSeries, MeshFileRewrittenOnlyWhenRevisionChanges) {
  test::TempDir dir;
  const Mesh before;
  Mesh after;
  after.cells = {0, 1, 2, 3, 4, 3, 2, 1};  // e.g. a re-mesh that renumbered the second tet
  XdmfSeries series(dir.path(), "run");
  write_step(series, 0.0, 0, before, 1);
  write_step(series, 1.0, 1, before, 1);
  EXPECT_EQ(files_containing(dir.path(), "_mesh_").size(), 1u);
  write_step(series, 2.0, 2, after, 2);
  const ino_t second = inode(dir / "run_mesh_solid_2.h5");
  write_step(series, 3.0, 3, after, 2);
  EXPECT_EQ(files_containing(dir.path(), "_mesh_"),
            (std::vector<std::string>{"run_mesh_solid_1.h5", "run_mesh_solid_2.h5"}));
  EXPECT_EQ(inode(dir / "run_mesh_solid_2.h5"), second);

  const std::vector<Grid> grids = parse_index(slurp(dir / "run.xdmf"));
  ASSERT_EQ(grids.size(), 4u);
  for (int i = 0; i < 4; ++i) expect_step(dir.path(), grids[i], i, i < 2 ? before : after);

  // Reusing revision 1 for another mesh would change what the first two outputs show.
  try {
    write_step(series, 4.0, 4, before, 1);
    FAIL() << "expected rift::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mesh_revision 1"), std::string::npos) << e.what();
  }
}

TEST(XdmfSeries, SeveralGridsFormASpatialCollection) {
  test::TempDir dir;
  const Mesh mesh;
  const StepData d(4);
  // One 6-node joint element between two triangles, whose points move with every output.
  const std::vector<double> joint_points_0{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.01, 1, 0, 0.01, 0, 1, 0.01};
  std::vector<double> joint_points_1 = joint_points_0;
  joint_points_1[11] = joint_points_1[14] = joint_points_1[17] = 0.02;
  const std::vector<int32_t> wedge{0, 1, 2, 3, 4, 5};
  const std::vector<double> opening{0.01};
  const std::vector<int32_t> no_triangles;

  XdmfSeries series(dir.path(), "multi");
  for (int out = 0; out < 2; ++out) {
    const auto& jp = out == 0 ? joint_points_0 : joint_points_1;
    std::vector<XdmfGrid> grids{d.grid(mesh, 0)};
    grids.push_back({"joints",
                     Topology::wedge,
                     jp.data(),
                     6,
                     wedge.data(),
                     1,
                     0,
                     true,
                     {{"opening", Center::cell, 1, ElementType::f64, opening.data(), 1}}});
    grids.push_back(
        {"surface", Topology::triangle, mesh.points.data(), 5, no_triangles.data(), 0, 0, false, {}});
    series.write(0.5 * out, 4 + out, grids);
  }
  const std::string xml = slurp(dir / "multi.xdmf");
  EXPECT_TRUE(balanced_tags(xml)) << xml;
  EXPECT_NE(xml.find("CollectionType=\"Spatial\""), std::string::npos);
  EXPECT_EQ(xml.find("surface"), std::string::npos) << "a grid without cells is left out";

  const std::vector<Grid> grids = parse_index(xml);
  ASSERT_EQ(grids.size(), 4u);  // solid + joints, twice
  for (int out = 0; out < 2; ++out) {
    const Grid& joints = grids[2 * out + 1];
    ASSERT_EQ(joints.name, "joints");
    EXPECT_EQ(joints.topology, "Wedge");
    EXPECT_EQ(joints.time, 0.5 * out);
    expect_item(dir.path(), joints.cells, wedge, 6);
    EXPECT_EQ(joints.points.path, "/joints/points");  // moving geometry lives in the step file
    expect_item(dir.path(), joints.points, out == 0 ? joint_points_0 : joint_points_1, 3);
    expect_item(dir.path(), joints.attributes.at("opening").item, opening, 1);
  }
  H5File joint_mesh(dir / "multi_mesh_joints_0.h5", H5File::Mode::read);
  EXPECT_FALSE(joint_mesh.exists("/points"));
  EXPECT_EQ(files_containing(dir.path(), "_mesh_").size(), 2u);
}

TEST(XdmfSeries, ResumeDropsLaterEntriesAndKeepsTheMesh) {
  test::TempDir dir;
  const Mesh mesh;
  {
    XdmfSeries series(dir.path(), "out");
    write_step(series, 0.0, 0, mesh, 7);
    write_step(series, 0.5, 10, mesh, 7);
    write_step(series, 1.0, 20, mesh, 7);
  }
  const ino_t mesh_inode = inode(dir / "out_mesh_solid_7.h5");

  XdmfSeries restarted(dir.path(), "out");  // a new process restarting from the checkpoint at t = 0.5
  restarted.resume(0.5);
  EXPECT_EQ(restarted.entries(), 2u);
  EXPECT_FALSE(std::filesystem::exists(dir / "out_00000020.h5")) << "only the dropped entry used it";
  std::string xml = slurp(dir / "out.xdmf");
  EXPECT_TRUE(balanced_tags(xml));
  EXPECT_EQ(xml.find("out_00000020.h5"), std::string::npos);
  EXPECT_EQ(parse_index(xml).size(), 2u);

  write_step(restarted, 0.75, 15, mesh, 7);
  EXPECT_EQ(restarted.entries(), 3u);
  EXPECT_EQ(inode(dir / "out_mesh_solid_7.h5"), mesh_inode) << "same revision after restart: mesh reused";
  const std::vector<Grid> grids = parse_index(slurp(dir / "out.xdmf"));
  ASSERT_EQ(grids.size(), 3u);
  const int64_t steps[] = {0, 10, 15};
  for (int i = 0; i < 3; ++i) expect_step(dir.path(), grids[i], steps[i], mesh);

  // An output at the time of the last entry replaces it; an earlier one is refused.
  write_step(restarted, 0.75, 15, mesh, 7);
  EXPECT_EQ(restarted.entries(), 3u);
  try {
    write_step(restarted, 0.6, 12, mesh, 7);
    FAIL() << "expected rift::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("resume"), std::string::npos) << e.what();
  }

  XdmfSeries from_scratch(dir.path(), "out");
  from_scratch.resume(-1.0);  // a restart before the first output
  EXPECT_EQ(from_scratch.entries(), 0u);
  EXPECT_TRUE(balanced_tags(slurp(dir / "out.xdmf")));
}

TEST(XdmfSeries, ResumeDeletesOnlyFilesItNamedItself) {
  // The sidecar is a file anyone can edit: names in it that the series never writes (an absolute path,
  // "../x", another series' file, a step file under another step) are never deleted on restart.
  test::TempDir dir;
  const Mesh mesh;
  const auto run = dir / "run";
  {
    XdmfSeries series(run, "out");
    write_step(series, 0.0, 0, mesh, 7);
    write_step(series, 1.0, 20, mesh, 7);
  }
  const auto victim = dir / "victim.h5", outside = dir / "outside.h5";
  std::ofstream(victim) << "keep";
  std::ofstream(outside) << "keep";
  std::ofstream(run / "other_00000020.h5") << "keep";
  std::ofstream(run / "out_00000021.h5") << "keep";
  auto json = nlohmann::json::parse(slurp(run / "out.series.json"));
  auto& fields = json.at("entries").at(1).at("grids").at(0).at("fields");
  ASSERT_GE(fields.size(), 1u);
  const std::vector<std::string> foreign{victim.string(), "../outside.h5", "other_00000020.h5",
                                         "out_00000021.h5"};
  for (const std::string& name : foreign) {
    auto field = fields.at(0);
    field["name"] = "f" + std::to_string(fields.size());
    field["data"]["file"] = name;
    fields.push_back(field);
  }
  std::ofstream(run / "out.series.json") << json.dump(1);

  XdmfSeries restarted(run, "out");
  restarted.resume(0.5);
  EXPECT_EQ(restarted.entries(), 1u);
  EXPECT_FALSE(std::filesystem::exists(run / "out_00000020.h5")) << "the dropped entry's own step file";
  EXPECT_EQ(slurp(victim), "keep");
  EXPECT_EQ(slurp(outside), "keep");
  EXPECT_EQ(slurp(run / "other_00000020.h5"), "keep");
  EXPECT_EQ(slurp(run / "out_00000021.h5"), "keep");
}

TEST(XdmfSeries, ResumeWithoutEarlierOutputStartsEmpty) {
  test::TempDir dir;
  XdmfSeries series(dir.path(), "fresh");
  series.resume(3.0);
  EXPECT_EQ(series.entries(), 0u);
}

TEST(XdmfSeries, CorruptSidecarIsReported) {
  test::TempDir dir;
  std::ofstream(dir / "bad.series.json")
      << "{\"format\": \"rift-xdmf-series\", \"version\": 1, \"entries\": [{}]}";
  XdmfSeries series(dir.path(), "bad");
  try {
    series.resume(1.0);
    FAIL() << "expected rift::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.series.json"), std::string::npos) << e.what();
  }
}

TEST(XdmfSeries, InvalidGridsAreRefusedWithTheirNames) {
  test::TempDir dir;
  const Mesh mesh;
  const StepData d(0);
  XdmfSeries series(dir.path(), "out");
  auto error_of = [&](XdmfGrid g) -> std::string {
    try {
      series.write(0.0, 0, std::vector<XdmfGrid>{g});
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  XdmfGrid short_field = d.grid(mesh, 0);
  short_field.fields[3].rows = 5;  // a cell field with one row per node
  EXPECT_NE(error_of(short_field).find("field 'damage': has 5 rows, expected 2"), std::string::npos)
      << error_of(short_field);
  XdmfGrid bad_cell = d.grid(mesh, 0);
  const std::vector<int32_t> out_of_range{0, 1, 2, 3, 1, 2, 3, 5};
  bad_cell.cells = out_of_range.data();
  EXPECT_NE(error_of(bad_cell).find("refers to node 5"), std::string::npos) << error_of(bad_cell);
  XdmfGrid slash = d.grid(mesh, 0);
  slash.name = "a/b";
  EXPECT_NE(error_of(slash).find("grid 'a/b'"), std::string::npos);
  EXPECT_EQ(series.entries(), 0u);
}

TEST(XdmfSeries, NamesAreEscapedInTheIndex) {
  test::TempDir dir;
  const Mesh mesh;
  const StepData d(1);
  XdmfGrid g = d.grid(mesh, 0);
  g.fields.push_back({"σ<xx> & \"yy\"", Center::node, 1, ElementType::f64, d.pressure.data(), 5});
  XdmfSeries series(dir.path(), "esc");
  series.write(0.1, 1, std::vector<XdmfGrid>{g});
  const std::string xml = slurp(dir / "esc.xdmf");
  EXPECT_TRUE(balanced_tags(xml)) << xml;
  EXPECT_NE(xml.find("Name=\"σ&lt;xx&gt; &amp; &quot;yy&quot;\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<Time Value=\"0.1\"/>"), std::string::npos) << "shortest round-trip form of 0.1";
}

// Optional cross-check with independent readers: Python's XML parser and h5py read every DataItem
// and compare shape and type with what the index declares. Skipped when they are not installed.
TEST(XdmfSeries, PythonReadersAgreeWithTheIndex) {
  // The first interpreter in PATH, then Debian's own (where the python3-h5py package installs).
  std::string python;
  for (const char* candidate : {"python3", "/usr/bin/python3"})
    if (std::system((std::string(candidate) + " -c 'import h5py, numpy' >/dev/null 2>&1").c_str()) == 0) {
      python = candidate;
      break;
    }
  if (python.empty()) GTEST_SKIP() << "no python3 with h5py and numpy";
  test::TempDir dir;
  const Mesh mesh;
  XdmfSeries series(dir.path(), "py");
  write_step(series, 0.0, 0, mesh, 0);
  write_step(series, 1.0, 1, mesh, 0);
  std::ofstream(dir / "check.py") << R"py(
import sys, os, xml.etree.ElementTree as ET
import h5py, numpy as np
path = sys.argv[1]
root = ET.parse(path).getroot()
assert root.tag == "Xdmf" and root.get("Version") == "2.0"
kinds = {("Float", "8"): np.float64, ("Float", "4"): np.float32, ("Int", "8"): np.int64,
         ("Int", "4"): np.int32, ("UInt", "4"): np.uint32, ("UChar", "1"): np.uint8}
times = [float(g.find("Time").get("Value")) for g in root.iter("Grid") if g.get("GridType") == "Uniform"]
assert times == [0.0, 1.0], times
count = 0
for item in root.iter("DataItem"):
    name, dataset = item.text.strip().split(":", 1)
    with h5py.File(os.path.join(os.path.dirname(path), name), "r") as f:
        d = f[dataset]
        dims = tuple(int(x) for x in item.get("Dimensions").split())
        assert d.shape == dims, (item.text, d.shape, dims)
        assert d.dtype == kinds[(item.get("NumberType"), item.get("Precision"))], (item.text, d.dtype)
        count += 1
assert count == 2 * 9, count
)py";
  const std::string cmd = python + " " + (dir / "check.py").string() + " " + (dir / "py.xdmf").string();
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

}  // namespace
}  // namespace rift
