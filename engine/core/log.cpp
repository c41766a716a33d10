#include "engine/core/log.hpp"

#include <fcntl.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/dist_sink.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "engine/core/error.hpp"

namespace rift {

namespace {
std::shared_ptr<spdlog::sinks::dist_sink_mt> sinks;
std::shared_ptr<spdlog::sinks::sink> file_sink;
std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> early;
constexpr const char* file_pattern = "[%Y-%m-%d %H:%M:%S.%e] [%l] %v";

// Appends to a file Rift opened itself: spdlog's file sinks open by name and would follow a symbolic
// link planted where the log goes.
class AppendFileSink final : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit AppendFileSink(std::FILE* file) : file_(file) {}
  ~AppendFileSink() override { std::fclose(file_); }

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    spdlog::memory_buf_t formatted;
    formatter_->format(msg, formatted);
    std::fwrite(formatted.data(), 1, formatted.size(), file_);
  }
  void flush_() override { std::fflush(file_); }

 private:
  std::FILE* file_;
};

// O_NOFOLLOW: a link at the log's path is refused, never written through. O_NONBLOCK keeps a FIFO there
// from blocking the open; anything but a regular file is refused after it.
std::FILE* open_for_append(const std::filesystem::path& file, const std::string& cannot) {
  const int fd =
      ::open(file.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    if (err == ELOOP)
      throw Error(cannot + "it is a symbolic link, which Rift does not write through; remove it");
    throw Error(cannot + std::strerror(err));
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw Error(cannot + "not a regular file");
  }
  std::FILE* out = ::fdopen(fd, "a");
  if (!out) {
    const int err = errno;
    ::close(fd);
    throw Error(cannot + std::strerror(err));
  }
  return out;
}

}  // namespace

void init_logging(bool verbose, bool quiet) {
  if (!sinks) {
    sinks = std::make_shared<spdlog::sinks::dist_sink_mt>();
    auto console = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
    console->set_pattern("%^[%l]%$ %v");
    sinks->add_sink(console);
    auto logger = std::make_shared<spdlog::logger>("rift", sinks);
    spdlog::set_default_logger(logger);
  }
  spdlog::set_level(quiet ? spdlog::level::warn : verbose ? spdlog::level::debug : spdlog::level::info);
}

void buffer_log_messages() {
  if (!sinks) init_logging(false, false);
  if (early) sinks->remove_sink(early);
  early = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(4096);
  early->set_pattern(file_pattern);
  sinks->add_sink(early);
}

void open_log_file(const std::filesystem::path& file) {
  if (!sinks) init_logging(false, false);
  close_log_file();
  const std::string cannot = "cannot open the log file '" + file.string() + "': ";
  std::FILE* out = open_for_append(file, cannot);
  if (early)
    for (const auto& line : early->last_formatted()) std::fwrite(line.data(), 1, line.size(), out);
  auto sink = std::make_shared<AppendFileSink>(out);
  if (early) {
    sinks->remove_sink(early);
    early.reset();
  }
  file_sink = std::move(sink);
  file_sink->set_pattern(file_pattern);
  file_sink->set_level(spdlog::level::debug);
  sinks->add_sink(file_sink);
}

void close_log_file() {
  if (sinks && file_sink) {
    file_sink->flush();
    sinks->remove_sink(file_sink);
    file_sink.reset();
  }
}

}  // namespace rift
