// The CLI end to end: exit codes, and a run stopped by SIGTERM that continues with --restart latest to
// the same final state (summary.json state_hash) as an uninterrupted run.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string scene = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";

// Runs rift with args (stdout/stderr to a log file); returns the exit status, or 128 + signal.
int run_rift(const std::vector<std::string>& args, const fs::path& log, double kill_after = -1.0) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(RIFT_EXECUTABLE)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(RIFT_EXECUTABLE, argv.data());
    _exit(127);
  }
  if (kill_after >= 0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(kill_after));
    kill(pid, SIGTERM);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

fs::path temp(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("rift_cli_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  return d;
}

}  // namespace

TEST(Cli, ExitCodesAndMessages) {
  const fs::path log = temp("log");
  EXPECT_EQ(run_rift({"check", std::string(RIFT_SOURCE_DIR) + "/scenes/bad/three_errors.yaml"}, log), 2);
  EXPECT_NE(read(log).find("3 error(s)"), std::string::npos) << read(log);
  EXPECT_EQ(run_rift({"info"}, log), 0);
  EXPECT_NE(read(log).find("HDF5"), std::string::npos);
  EXPECT_NE(read(log).find("CGAL"), std::string::npos);
  EXPECT_EQ(run_rift({"graph", scene}, log), 0);
  EXPECT_NE(read(log).find("tet_forces"), std::string::npos);
  EXPECT_EQ(run_rift({"check", scene, "--set", "time.end=-1"}, log), 2);
  EXPECT_NE(read(log).find("--set time.end=-1"), std::string::npos) << read(log);
  EXPECT_EQ(run_rift({"run", scene, "--restart", "latest", "--out", temp("none").string()}, log), 2);
  fs::remove(log);
}

TEST(Cli, SigtermThenRestartGivesTheStraightRunsState) {
  const std::vector<std::string> common{
      "--set", "time.end=4.0e-4", "--set", "output.interval=1.0e-4", "--threads", "2"};
  const fs::path straight = temp("straight"), stopped = temp("stopped"), log = temp("log2");
  std::vector<std::string> a{"run", scene, "--out", straight.string()};
  a.insert(a.end(), common.begin(), common.end());
  ASSERT_EQ(run_rift(a, log), 0) << read(log);
  const auto reference = nlohmann::json::parse(read(straight / "summary.json"));

  std::vector<std::string> b{"run", scene, "--out", stopped.string()};
  b.insert(b.end(), common.begin(), common.end());
  const int code = run_rift(b, log, 1.0);
  if (code == 0) GTEST_SKIP() << "the run finished within 1 s; nothing was interrupted";
  ASSERT_EQ(code, 130) << read(log);
  EXPECT_NE(read(log).find("--restart latest"), std::string::npos);
  const auto partial = nlohmann::json::parse(read(stopped / "summary.json"));
  EXPECT_EQ(partial["status"], "signal");
  EXPECT_LT(partial["steps"].get<int64_t>(), reference["steps"].get<int64_t>());

  b.push_back("--restart");
  b.push_back("latest");
  ASSERT_EQ(run_rift(b, log), 0) << read(log);
  const auto resumed = nlohmann::json::parse(read(stopped / "summary.json"));
  EXPECT_EQ(resumed["status"], "completed");
  EXPECT_EQ(resumed["state_hash"], reference["state_hash"]);
  EXPECT_EQ(read(stopped / "timeseries.csv"), read(straight / "timeseries.csv"));
  fs::remove_all(straight);
  fs::remove_all(stopped);
  fs::remove(log);
}
