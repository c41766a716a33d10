// Checkpoints: a Store written and read back into a freshly built store is identical byte for byte;
// mismatches and damaged files are reported by name; CheckpointSet keeps the newest K.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/file_seal.hpp"
#include "engine/io/hdf5_file.hpp"
#include "tests/unit/test_checkpoint_damage.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

// The schema a run would build from its scene: a node table, an empty joint table, a large table
// (above the compression threshold) and a tet table.
void build_schema(Store& store) {
  Table& nodes = store.add_table("solid_node");
  nodes.add<double>("x", 3);
  nodes.add<double>("v", 3);
  nodes.add<float>("mass");
  nodes.add<int64_t>("id");
  nodes.add<uint8_t>("flags");
  Table& joints = store.add_table("joint");
  joints.add<uint32_t>("state");
  joints.add<double>("opening", 2);
  Table& tets = store.add_table("tet");
  tets.add<int32_t>("nodes", 4);
  tets.add<uint32_t>("material");
  Table& big = store.add_table("fluid_cell");
  big.add<double>("p");
  big.add<float>("grad", 3);
}

// Fills every column with distinct bit patterns, including the awkward ones (-0, NaN with
// payload, denormals, integer extremes) that a lossy path would change.
void fill(Store& store) {
  store.table("solid_node").resize(5);
  store.table("joint").resize(0);
  store.table("tet").resize(3);
  store.table("fluid_cell").resize(20000);  // 160 kB + 240 kB: chunked + deflate
  uint64_t state = 0x9E3779B97F4A7C15ull;
  for (const auto& table : store.tables())
    for (const auto& column : table->columns())
      for (size_t b = 0; b < column->bytes(); ++b) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;  // LCG: reproducible bytes
        column->data()[b] = static_cast<std::byte>(state >> 56);
      }
  auto x = store.table("solid_node").span<double>("x");
  x[0] = -0.0;
  x[1] = std::numeric_limits<double>::denorm_min();
  x[2] = std::bit_cast<double>(0x7FF8000000000123ull);  // NaN with payload
  x[3] = std::numeric_limits<double>::infinity();
  auto id = store.table("solid_node").span<int64_t>("id");
  id[0] = std::numeric_limits<int64_t>::min();
  id[1] = std::numeric_limits<int64_t>::max();
}

CheckpointMeta sample_meta(int64_t step) {
  CheckpointMeta meta;
  meta.step = step;
  meta.time = step * 1e-7;
  meta.dt = std::nextafter(1e-7, 1.0);
  meta.scene_hash = "sha256:0f1e2d3c";
  meta.resolved_scene = "scene:\n  name: notched block  # ünïcode\n  end_time: 1e-3\n";
  meta.rift_version = "0.1.0";
  meta.scalars = {{"energy.kinetic", 1.25e-3}, {"energy.strain", -0.0}};
  meta.integers = {{"mesh_revision.solid", 4}, {"rng.word0", std::numeric_limits<int64_t>::min()}};
  return meta;
}

void expect_same(const Store& a, const Store& b) {
  ASSERT_EQ(a.tables().size(), b.tables().size());
  for (const auto& ta : a.tables()) {
    const Table& tb = b.table(ta->name());
    EXPECT_EQ(ta->size(), tb.size()) << ta->name();
    for (const auto& ca : ta->columns()) {
      const Column& cb = tb.column(ca->name());
      ASSERT_EQ(ca->bytes(), cb.bytes()) << ca->key();
      if (ca->bytes() > 0) {
        EXPECT_EQ(std::memcmp(ca->data(), cb.data(), ca->bytes()), 0) << ca->key();
      }
    }
  }
}

using test::error_of;

TEST(Checkpoint, StoreRoundTripsBitForBit) {
  test::TempDir dir;
  Store original;
  build_schema(original);
  fill(original);
  const CheckpointMeta meta = sample_meta(1234);
  const auto file = dir / "c.h5";
  write_checkpoint(file, original, meta);

  Store restored;
  build_schema(restored);
  restored.table("tet").resize(11);  // the rebuilt world has other row counts; the checkpoint wins
  restored.table("joint").resize(2);
  const CheckpointMeta back = read_checkpoint(file, restored);
  expect_same(original, restored);
  EXPECT_EQ(restored.table("joint").size(), 0u);
  EXPECT_EQ(back.step, meta.step);
  EXPECT_EQ(back.time, meta.time);
  EXPECT_EQ(back.dt, meta.dt);
  EXPECT_EQ(back.scene_hash, meta.scene_hash);
  EXPECT_EQ(back.resolved_scene, meta.resolved_scene);
  EXPECT_EQ(back.rift_version, meta.rift_version);
  EXPECT_EQ(back.scalars, meta.scalars);
  EXPECT_TRUE(std::signbit(back.scalars.at("energy.strain")));
  EXPECT_EQ(back.integers, meta.integers);
  EXPECT_FALSE(std::filesystem::exists(dir / ("c.h5.tmp-" + std::to_string(::getpid()))));
}

TEST(Checkpoint, LayoutIsTheDocumentedOne) {
  test::TempDir dir;
  Store store;
  build_schema(store);
  fill(store);
  write_checkpoint(dir / "c.h5", store, sample_meta(7));
  H5File h5(dir / "c.h5", H5File::Mode::read);
  EXPECT_EQ(h5.int_attr("/", "format_version"), 3);
  EXPECT_EQ(h5.int_attr("/", "step"), 7);
  EXPECT_EQ(h5.string_attr("/", "scene_hash"), "sha256:0f1e2d3c");
  EXPECT_EQ(h5.children("/"), (std::vector<std::string>{"integers", "scalars", "scene", "tables"}));
  EXPECT_EQ(h5.children("/tables"), (std::vector<std::string>{"fluid_cell", "joint", "solid_node", "tet"}));
  EXPECT_EQ(h5.int_attr("/tables/solid_node", "rows"), 5);
  EXPECT_EQ(h5.string_attr("/tables/solid_node/x", "type"), "f64");
  EXPECT_EQ(h5.int_attr("/tables/solid_node/x", "components"), 3);
  EXPECT_EQ(h5.string_attr("/tables/solid_node/x", "fnv1a64").size(), 16u);
  EXPECT_EQ(h5.string_attr("/", "meta_fnv1a64").size(), 16u);
  const H5DatasetInfo x = h5.info("/tables/solid_node/x");
  EXPECT_EQ(x.rows, 5u);
  EXPECT_EQ(x.components, 3);
  EXPECT_EQ(h5.info("/tables/joint/opening").rows, 0u);
}

TEST(Checkpoint, MismatchesNameFileAndColumnAndLeaveTheStoreAlone) {
  test::TempDir dir;
  Store original;
  build_schema(original);
  fill(original);
  const auto file = dir / "c.h5";
  write_checkpoint(file, original, sample_meta(1));

  {  // a column whose type changed
    Store wrong;
    Table& nodes = wrong.add_table("solid_node");
    nodes.add<double>("x", 3);
    nodes.add<double>("v", 3);
    nodes.add<double>("mass");  // f32 in the checkpoint
    nodes.add<int64_t>("id");
    nodes.add<uint8_t>("flags");
    for (const char* t : {"joint", "tet", "fluid_cell"}) {
      Table& copy = wrong.add_table(t);
      for (const auto& c : original.table(t).columns())
        copy.add_column(c->name(), c->type(), c->components());
    }
    const std::string msg = error_of([&] { read_checkpoint(file, wrong); });
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("solid_node.mass"), std::string::npos) << msg;
    EXPECT_NE(msg.find("f32 x 1 in the checkpoint but f64 x 1 in this run"), std::string::npos) << msg;
    EXPECT_EQ(wrong.table("solid_node").size(), 0u) << "nothing restored after a mismatch";
  }
  {  // a component count that changed
    Store wrong;
    build_schema(wrong);
    wrong.table("joint").add<float>("extra", 2);
    const std::string msg = error_of([&] { read_checkpoint(file, wrong); });
    EXPECT_NE(msg.find("joint.extra"), std::string::npos) << msg;
  }
  {  // a table the checkpoint does not have
    Store wrong;
    build_schema(wrong);
    wrong.add_table("fracture_front");
    const std::string msg = error_of([&] { read_checkpoint(file, wrong); });
    EXPECT_NE(msg.find("fracture_front"), std::string::npos) << msg;
  }
  {  // a column the run no longer has
    Store wrong;
    Table& nodes = wrong.add_table("solid_node");
    for (const auto& c : original.table("solid_node").columns())
      if (c->name() != "flags") nodes.add_column(c->name(), c->type(), c->components());
    for (const char* t : {"joint", "tet", "fluid_cell"}) {
      Table& copy = wrong.add_table(t);
      for (const auto& c : original.table(t).columns())
        copy.add_column(c->name(), c->type(), c->components());
    }
    const std::string msg = error_of([&] { read_checkpoint(file, wrong); });
    EXPECT_NE(msg.find("column 'solid_node.flags', which this run does not define"), std::string::npos)
        << msg;
  }
}

TEST(Checkpoint, UnknownFormatVersionIsRefused) {
  test::TempDir dir;
  const auto file = dir / "future.h5";
  {
    H5File h5(file, H5File::Mode::truncate, kSealBytes);
    h5.set_int_attr("/", "format_version", 99);
  }
  seal_file(file);  // an intact file of another format
  Store store;
  const std::string msg = error_of([&] { read_checkpoint(file, store); });
  EXPECT_NE(msg.find("format_version 99"), std::string::npos) << msg;
  EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;

  std::ofstream(dir / "text.h5") << "not a checkpoint";
  EXPECT_NE(error_of([&] { read_checkpoint(dir / "text.h5", store); }).find("text.h5"), std::string::npos);
}

TEST(Checkpoint, EveryChangedByteOfAColumnIsReported) {
  // A flipped byte in a column's values would restore a different state without a word. The file's seal
  // finds it before HDF5 reads anything; resealed (the file written wrong rather than damaged later),
  // the column's checksum makes both verify_checkpoint and read_checkpoint name the file and the column.
  test::TempDir dir;
  Store store;
  build_schema(store);
  fill(store);
  const auto file = dir / "c.h5";
  write_checkpoint(file, store, sample_meta(3));
  const auto original = test::slurp(file);
  for (const std::string column : {"solid_node.x", "solid_node.flags", "tet.nodes"}) {
    const std::string dataset =
        "/tables/" + column.substr(0, column.find('.')) + "/" + column.substr(column.find('.') + 1);
    const uint64_t size = test::dataset_bytes(file, dataset).second;
    ASSERT_GT(size, 0u);
    for (uint64_t byte = 0; byte < size; ++byte) {
      std::ofstream(file, std::ios::binary) << original;
      test::flip_dataset_byte(file, dataset, byte);
      const std::string unsealed = error_of([&] { verify_checkpoint(file); });
      EXPECT_NE(unsealed.find("checkpoint " + file.string() + " is damaged: its bytes do not match its seal"),
                std::string::npos)
          << "byte " << byte << ": " << unsealed;
      seal_file(file);
      const std::string verified = error_of([&] { verify_checkpoint(file); });
      EXPECT_NE(verified.find("checkpoint " + file.string() + " is damaged: the data of column '" + column +
                              "' does not match its checksum"),
                std::string::npos)
          << "byte " << byte << ": " << verified;
      Store restored;
      build_schema(restored);
      const std::string read = error_of([&] { read_checkpoint(file, restored); });
      EXPECT_NE(read.find("column '" + column + "' does not match its checksum"), std::string::npos) << read;
    }
  }
  std::ofstream(file, std::ios::binary) << original;
  Store restored;
  build_schema(restored);
  EXPECT_EQ(verify_checkpoint(file).step, 3);
  EXPECT_EQ(read_checkpoint(file, restored).step, 3);
  expect_same(store, restored);
}

TEST(Checkpoint, AChangedByteOfTheSceneIsReported) {
  // The scene text, the clock, scalars and integers are covered by the metadata checksum.
  test::TempDir dir;
  Store store;
  build_schema(store);
  fill(store);
  const auto file = dir / "c.h5";
  write_checkpoint(file, store, sample_meta(3));
  test::flip_dataset_byte(file, "/scene", 10);
  EXPECT_NE(error_of([&] { verify_checkpoint(file); }).find("do not match its seal"), std::string::npos);
  seal_file(file);  // the metadata checksum still finds it
  const std::string msg = error_of([&] { verify_checkpoint(file); });
  EXPECT_NE(msg.find("checkpoint " + file.string() + " is damaged: its metadata"), std::string::npos) << msg;
  Store restored;
  build_schema(restored);
  fill(restored);
  const std::string read = error_of([&] { read_checkpoint(file, restored); });
  EXPECT_NE(read.find("is damaged: its metadata"), std::string::npos) << read;
  expect_same(store, restored);  // refused before any column was touched
}

pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;  // reaped: no such process until the kernel reuses the number
}

TEST(CheckpointSet, KeepsTheNewestAndFindsTheLatestReadable) {
  test::TempDir dir;
  Store store;
  build_schema(store);
  fill(store);
  CheckpointSet set(dir.path(), 2);
  EXPECT_EQ(set.latest(), std::nullopt);  // no directory yet

  // A leftover from a killed run (its process is gone) and one of ours in progress.
  std::filesystem::create_directories(set.dir());
  const auto orphan = set.dir() / ("ckpt_0000000005.h5.tmp-" + std::to_string(dead_pid()));
  const auto ours = set.dir() / ("ckpt_0000000006.h5.tmp-" + std::to_string(::getpid()));
  std::ofstream(orphan) << "partial";
  std::ofstream(ours) << "partial";

  for (int64_t step : {10, 20, 30, 40}) {
    const auto path = set.write(store, sample_meta(step));
    EXPECT_EQ(path, set.path_for(step));
    EXPECT_EQ(path.filename().string().size(), std::string("ckpt_0000000010.h5").size());
  }
  const auto kept = set.list();
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].first, 30);
  EXPECT_EQ(kept[1].first, 40);
  EXPECT_FALSE(std::filesystem::exists(orphan));
  EXPECT_TRUE(std::filesystem::exists(ours));
  EXPECT_EQ(set.latest(), set.path_for(40));

  // Newer but damaged: a truncated copy, garbage and a temp leftover must all be passed over.
  const auto good = set.path_for(40);
  const auto size = std::filesystem::file_size(good);
  std::filesystem::copy_file(good, set.path_for(45));
  std::filesystem::resize_file(set.path_for(45), size / 2);
  std::ofstream(set.path_for(50)) << "garbage, not HDF5";
  std::filesystem::copy_file(good, set.dir() / "ckpt_0000000060.h5.tmp-1");
  std::filesystem::copy_file(good, set.path_for(55));
  test::flip_dataset_byte(set.path_for(55), "/tables/tet/nodes", 5);
  std::vector<CheckpointProblem> skipped;
  EXPECT_EQ(set.latest(&skipped), good);
  ASSERT_EQ(skipped.size(), 3u);
  EXPECT_EQ(skipped[0].file, set.path_for(55));
  EXPECT_NE(skipped[0].reason.find("its bytes do not match its seal"), std::string::npos)
      << skipped[0].reason;
  EXPECT_EQ(skipped[1].file, set.path_for(50));
  EXPECT_EQ(skipped[2].file, set.path_for(45));

  Store restored;
  build_schema(restored);
  EXPECT_EQ(read_checkpoint(*set.latest(), restored).step, 40);
  expect_same(store, restored);
}

TEST(CheckpointSet, PruningLeavesTempNamesItDidNotWriteAlone) {
  // Only "ckpt_<step:010>.h5.tmp-<pid>" with a dead pid is a leftover of ours; a pid part too large for a
  // pid, with a leading zero or a sign, or a checkpoint name we do not write, is someone else's file.
  test::TempDir dir;
  Store store;
  build_schema(store);
  fill(store);
  CheckpointSet set(dir.path(), 1);
  std::filesystem::create_directories(set.dir());
  const std::string dead = std::to_string(dead_pid());
  const auto orphan = set.dir() / ("ckpt_0000000100.h5.tmp-" + dead);
  const std::vector<std::string> foreign{
      "ckpt_000100.h5.tmp-99999999999999999999", "ckpt_0000000100.h5.tmp-99999999999999999999",
      "ckpt_0000000100.h5.tmp-2147483648",       "ckpt_0000000100.h5.tmp-0" + dead,
      "ckpt_0000000100.h5.tmp--" + dead,         "ckpt_100.h5.tmp-" + dead,
      "ckpt_00000000100.h5.tmp-" + dead,         "other.h5.tmp-" + dead};
  std::ofstream(orphan) << "partial";
  for (const auto& name : foreign) std::ofstream(set.dir() / name) << "not ours";
  const auto other_padding = set.dir() / "ckpt_00000000005.h5";  // not a name of ours: never pruned
  std::ofstream(other_padding) << "not ours";

  for (int64_t step : {10, 20}) EXPECT_EQ(set.write(store, sample_meta(step)), set.path_for(step));
  EXPECT_FALSE(std::filesystem::exists(orphan));
  for (const auto& name : foreign) EXPECT_TRUE(std::filesystem::exists(set.dir() / name)) << name;
  EXPECT_TRUE(std::filesystem::exists(other_padding));
  EXPECT_FALSE(std::filesystem::exists(set.path_for(10)));
  EXPECT_EQ(set.latest(), set.path_for(20));
}

TEST(CheckpointSet, NeverFollowsALinkedFolderOrDeletesLinks) {
  // A `checkpoints` link could lead writing and pruning out of the output folder: refused. Inside the
  // real folder, a link with a checkpoint's name is not a checkpoint of ours and is never deleted.
  test::TempDir dir;
  Store store;
  build_schema(store);
  fill(store);
  const auto elsewhere = dir / "elsewhere";
  std::filesystem::create_directories(elsewhere);
  const auto victim = elsewhere / "ckpt_0000000001.h5";
  std::ofstream(victim) << "someone else's file";
  std::filesystem::create_directories(dir / "out");
  std::filesystem::create_directory_symlink(elsewhere, dir / "out" / "checkpoints");
  const std::string msg = error_of([&] { CheckpointSet(dir / "out", 1); });
  EXPECT_NE(msg.find("'" + (dir / "out" / "checkpoints").string() + "' is a symbolic link"),
            std::string::npos)
      << msg;
  EXPECT_EQ(test::slurp(victim), "someone else's file");

  CheckpointSet set(dir / "run", 1);
  std::filesystem::create_directories(set.dir());
  std::filesystem::create_symlink(victim, set.path_for(2));
  const std::string dead = std::to_string(dead_pid());
  std::filesystem::create_symlink(victim, set.dir() / ("ckpt_0000000003.h5.tmp-" + dead));
  for (int64_t step : {10, 20}) set.write(store, sample_meta(step));
  EXPECT_TRUE(std::filesystem::is_symlink(set.path_for(2)));
  EXPECT_TRUE(std::filesystem::is_symlink(set.dir() / ("ckpt_0000000003.h5.tmp-" + dead)));
  EXPECT_EQ(test::slurp(victim), "someone else's file");
  EXPECT_EQ(set.list().size(), 1u);
  EXPECT_FALSE(std::filesystem::exists(set.path_for(10)));

  // The folder replaced by a link while the run goes on: the next write refuses.
  std::filesystem::rename(set.dir(), dir / "run" / "moved");
  std::filesystem::create_directory_symlink(elsewhere, set.dir());
  EXPECT_NE(error_of([&] { set.write(store, sample_meta(30)); }).find("is a symbolic link"),
            std::string::npos);
  EXPECT_EQ(test::slurp(victim), "someone else's file");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(elsewhere), {}), 1);
}

TEST(CheckpointSet, KeepMustBePositive) {
  test::TempDir dir;
  EXPECT_THROW(CheckpointSet(dir.path(), 0), Error);
}

}  // namespace
}  // namespace rift
