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
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::string scene = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";

// Runs rift with args (stdout/stderr to a log file); returns the exit status, or 128 + signal. When
// kill_when is given, SIGTERM is sent as soon as it returns true (polled every 5 ms).
int run_rift(const std::vector<std::string>& args, const fs::path& log,
             const std::function<bool()>& kill_when = {}) {
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
  int status = 0;
  bool reaped = false;
  if (kill_when) {
    const auto t0 = std::chrono::steady_clock::now();
    while (!(reaped = waitpid(pid, &status, WNOHANG) == pid)) {
      if (kill_when() || std::chrono::steady_clock::now() - t0 > std::chrono::seconds(120)) {
        kill(pid, SIGTERM);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  if (!reaped) waitpid(pid, &status, 0);
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
  // 1e-3 s is ~12,700 steps and 10 field outputs; the signal is sent once the second output exists, so it
  // arrives from inside the step loop with most of the run still ahead.
  const std::vector<std::string> common{
      "--set", "time.end=1.0e-3", "--set", "output.interval=1.0e-4", "--threads", "2"};
  const fs::path straight = temp("straight"), stopped = temp("stopped"), log = temp("log2");
  std::vector<std::string> a{"run", scene, "--out", straight.string()};
  a.insert(a.end(), common.begin(), common.end());
  ASSERT_EQ(run_rift(a, log), 0) << read(log);
  const auto reference = nlohmann::json::parse(read(straight / "summary.json"));

  std::vector<std::string> b{"run", scene, "--out", stopped.string()};
  b.insert(b.end(), common.begin(), common.end());
  auto field_outputs = [&] {
    size_t n = 0;
    if (fs::exists(stopped))
      for (const auto& e : fs::directory_iterator(stopped)) {
        const std::string name = e.path().filename().string();
        n += name.rfind("rift_0", 0) == 0 && name.size() == 16 && name.ends_with(".h5") ? 1 : 0;
      }
    return n;
  };
  const int code = run_rift(b, log, [&] { return field_outputs() >= 2; });
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
