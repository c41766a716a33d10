// Atomic file replacement and the run summary JSON.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/hdf5_file.hpp"
#include "engine/io/run_summary.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

using test::slurp;

size_t file_count(const std::filesystem::path& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WriteReplacesContentAndLeavesNoTemp) {
  test::TempDir dir;
  const auto file = dir / "a.txt";
  write_text_atomic(file, "first");
  write_text_atomic(file, std::string("second\0with nul", 15));
  EXPECT_EQ(slurp(file), std::string("second\0with nul", 15));
  EXPECT_EQ(file_count(dir.path()), 1u);
}

TEST(AtomicFile, UncommittedWriteKeepsPreviousFileAndRemovesTemp) {
  test::TempDir dir;
  const auto file = dir / "state.txt";
  write_text_atomic(file, "good");
  {
    AtomicPath atomic(file);
    EXPECT_TRUE(AtomicPath::is_temp_name(atomic.temp()));
    std::ofstream(atomic.temp()) << "half-writ";  // the run "dies" before commit()
    EXPECT_EQ(slurp(file), "good");
  }
  EXPECT_EQ(slurp(file), "good");
  EXPECT_EQ(file_count(dir.path()), 1u);
}

TEST(AtomicFile, ErrorsNameThePathAndReason) {
  test::TempDir dir;
  const auto file = dir / "missing-dir" / "x.txt";
  try {
    write_text_atomic(file, "x");
    FAIL() << "expected rift::Error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find((dir / "missing-dir").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
  }
}

TEST(AtomicFile, ALinkAtTheTempNameIsNeverWrittenThrough) {
  // `<target>.tmp-<pid>` is predictable: a link planted there must not make the writer truncate or fill
  // the link's target, whether the link is there before the write starts or appears during it.
  test::TempDir dir;
  const auto victim = dir / "victim.txt";
  std::ofstream(victim) << "precious";
  const auto file = dir / "scene.yaml";
  std::filesystem::create_symlink(victim, AtomicPath::temp_for(file, ::getpid()));
  write_text_atomic(file, "new");
  EXPECT_EQ(slurp(file), "new");
  EXPECT_EQ(slurp(victim), "precious");
  EXPECT_FALSE(std::filesystem::is_symlink(file));
  EXPECT_EQ(file_count(dir.path()), 2u);

  {
    AtomicPath atomic(dir / "late.txt");
    std::filesystem::create_symlink(victim, atomic.temp());  // planted after the leftover check
    const std::string msg = test::error_of([&] { atomic.create_temp(); });
    EXPECT_NE(msg.find("cannot create '" + atomic.temp().string() + "': File exists"), std::string::npos)
        << msg;
  }
  EXPECT_EQ(slurp(victim), "precious");
}

TEST(AtomicFile, ALinkAtAnHdf5TempNameIsNeverWrittenThrough) {
  test::TempDir dir;
  const auto victim = dir / "victim.h5";
  std::ofstream(victim) << "precious";
  const auto file = dir / "out_00000001.h5";
  std::filesystem::create_symlink(victim, AtomicPath::temp_for(file, ::getpid()));
  {
    AtomicPath atomic(file);
    H5File h5(atomic.temp(), H5File::Mode::create);
    h5.set_int_attr("/", "step", 1);
    h5.close();
    atomic.commit();
  }
  EXPECT_EQ(H5File(file, H5File::Mode::read).int_attr("/", "step"), 1);
  EXPECT_EQ(slurp(victim), "precious");

  AtomicPath atomic(dir / "late.h5");
  for (const auto& target : {victim, dir / "dangling"}) {
    std::filesystem::create_symlink(target, atomic.temp());
    const std::string msg = test::error_of([&] { H5File(atomic.temp(), H5File::Mode::create); });
    EXPECT_NE(msg.find("cannot create (something is at that path already)"), std::string::npos) << msg;
    std::filesystem::remove(atomic.temp());
  }
  EXPECT_EQ(slurp(victim), "precious");
  EXPECT_FALSE(std::filesystem::exists(dir / "dangling"));
}

TEST(AtomicFile, TempNamesAreRecognised) {
  EXPECT_TRUE(AtomicPath::is_temp_name("dir/ckpt_0000000010.h5.tmp-1234"));
  EXPECT_FALSE(AtomicPath::is_temp_name("dir/ckpt_0000000010.h5"));
  EXPECT_FALSE(AtomicPath::is_temp_name("x.tmp-"));
  EXPECT_FALSE(AtomicPath::is_temp_name("x.tmp-12a"));
}

TEST(AtomicFile, TempNamesParseOnlyAsTheWriterMakesThem) {
  const auto ok = AtomicPath::parse_temp_name("timeseries.csv.tmp-4242");
  ASSERT_TRUE(ok.has_value());
  EXPECT_EQ(ok->target, "timeseries.csv");
  EXPECT_EQ(ok->pid, 4242);
  for (const char* bad : {"timeseries.csv", "x.tmp-", "x.tmp-+1", "x.tmp-012", "x.tmp-0", "x.tmp--3",
                          ".tmp-12", "x.tmp-99999999999999999999", "x.tmp-12a"})
    EXPECT_FALSE(AtomicPath::parse_temp_name(bad).has_value()) << bad;
  EXPECT_FALSE(AtomicPath::writer_is_gone(::getpid()));
}

TEST(RunSummary, DottedPathsBuildNestedObjects) {
  RunSummary summary;
  summary.set("scene.name", "notched_block");
  summary.set("timing.solid.seconds", 1.5);
  summary.set("timing.solid.calls", 20);
  summary.set("timing.fluid", nlohmann::json::array({1, 2}));
  summary.root()["warnings"] = nlohmann::json::array();
  EXPECT_EQ(summary.root()["timing"]["solid"]["seconds"], 1.5);
  EXPECT_EQ(summary.root()["timing"]["solid"]["calls"], 20);
  EXPECT_EQ(summary.root()["scene"]["name"], "notched_block");

  EXPECT_THROW(summary.set("timing.solid.seconds.max", 2.0), Error);  // seconds is a number
  EXPECT_THROW(summary.set("a..b", 1), Error);
  EXPECT_THROW(summary.set("", 1), Error);
}

TEST(RunSummary, WritesPrettyJsonThatParsesBack) {
  test::TempDir dir;
  RunSummary summary;
  summary.set("final.step", 1200);
  summary.set("final.time", 0.1);
  summary.set("note", std::string("bad utf8 \xff here"));
  const auto file = dir / "run_summary.json";
  summary.write(file);
  const std::string text = slurp(file);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  EXPECT_NE(text.find("\n  \"final\": {"), std::string::npos) << text;  // 2-space indentation
  const auto parsed = nlohmann::json::parse(text);
  EXPECT_EQ(parsed["final"]["step"], 1200);
  EXPECT_EQ(parsed["final"]["time"].get<double>(), 0.1);  // nlohmann prints doubles round-trip exact
  EXPECT_EQ(file_count(dir.path()), 1u);
}

// JSON has no infinity or NaN: they are written as strings, never as null, at any depth.
TEST(RunSummary, NonFiniteNumbersAreWrittenAsStrings) {
  test::TempDir dir;
  RunSummary summary;
  summary.set("solid.joint_stable_dt", std::numeric_limits<double>::infinity());
  summary.set("solid.energy.kinetic", -std::numeric_limits<double>::infinity());
  summary.root()["list"] = {1.5, std::nan("")};
  const auto file = dir / "run_summary.json";
  summary.write(file);
  const std::string text = slurp(file);
  EXPECT_EQ(text.find("null"), std::string::npos) << text;
  const auto parsed = nlohmann::json::parse(text);
  EXPECT_EQ(parsed["solid"]["joint_stable_dt"], "inf");
  EXPECT_EQ(parsed["solid"]["energy"]["kinetic"], "-inf");
  EXPECT_EQ(parsed["list"][0].get<double>(), 1.5);
  EXPECT_EQ(parsed["list"][1], "nan");
}

}  // namespace
}  // namespace rift
