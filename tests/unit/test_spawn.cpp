// Helper programs start from an argument vector: quotes, $(), backticks, semicolons and newlines in an
// argument reach the program as text and are never run. Scene names become single, safe folder names.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/core/folder_name.hpp"
#include "engine/core/spawn.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kHostile = {
    "x'; touch owned; echo '", "$(touch owned)", "`touch owned`", "a\ntouch owned", "\"; touch owned; \"",
    "x && touch owned",        "| touch owned",  "../../owned",   "/tmp/owned",     ""};

TEST(Spawn, HostileArgumentsArriveVerbatimAndRunNothing) {
  test::TempDir dir;
  for (const auto& arg : kHostile) {
    const fs::path log = dir / "args.log";
    fs::remove(log);
    // printf prints its argument between markers; a shell would have run the touch instead.
    ASSERT_EQ(run_program({"printf", "[%s]", arg}, dir.path(), log), 0) << arg;
    EXPECT_EQ(test::slurp(log), "[" + arg + "]");
    EXPECT_FALSE(fs::exists(dir / "owned")) << arg;
    EXPECT_FALSE(fs::exists("owned")) << arg;
  }
}

TEST(Spawn, ReportsExitStatusAndAMissingProgram) {
  EXPECT_EQ(run_program({"true"}), 0);
  EXPECT_EQ(run_program({"false"}), 1);
  EXPECT_EQ(run_program({"sh", "-c", "exit 7"}), 7);
  EXPECT_EQ(run_program({"rift-no-such-program-anywhere"}), -1);
  EXPECT_EQ(run_program({}), -1);
}

TEST(Spawn, RunsInTheGivenFolderAndRefusesALogThatIsASymlink) {
  test::TempDir dir;
  ASSERT_EQ(run_program({"pwd"}, dir.path(), dir / "pwd.log"), 0);
  EXPECT_EQ(fs::path(test::slurp(dir / "pwd.log").substr(0, test::slurp(dir / "pwd.log").size() - 1)),
            fs::canonical(dir.path()));
  std::ofstream(dir / "target") << "keep";
  fs::create_symlink(dir / "target", dir / "link.log");
  EXPECT_NE(run_program({"echo", "overwrite"}, dir.path(), dir / "link.log"), 0);
  EXPECT_EQ(test::slurp(dir / "target"), "keep");
}

TEST(FolderName, ScenesNamesStayOneFolderInsideTheOutputRoot) {
  EXPECT_EQ(safe_folder_name("guo2015_wedge-dry.v2"), "guo2015_wedge-dry.v2");
  EXPECT_EQ(safe_folder_name("/abs/path"), "_abs_path");
  EXPECT_EQ(safe_folder_name("a/../../x"), "a_.._.._x");
  EXPECT_EQ(safe_folder_name(".."), "scene");
  EXPECT_EQ(safe_folder_name("."), "scene");
  EXPECT_EQ(safe_folder_name(""), "scene");
  for (const auto& name : kHostile) {
    const std::string f = safe_folder_name(name);
    EXPECT_EQ(f.find('/'), std::string::npos) << name;
    EXPECT_EQ(f.find('\n'), std::string::npos) << name;
    EXPECT_NE(f, "..");
    const fs::path p = (fs::path("rift-out") / f).lexically_normal();
    EXPECT_EQ(*p.begin(), fs::path("rift-out")) << name;
    EXPECT_EQ(std::distance(p.begin(), p.end()), 2) << name;
  }
}

}  // namespace
}  // namespace rift
