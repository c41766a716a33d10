#include "engine/core/log.hpp"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/dist_sink.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "engine/core/error.hpp"

namespace rift {

namespace {
std::shared_ptr<spdlog::sinks::dist_sink_mt> sinks;
std::shared_ptr<spdlog::sinks::sink> file_sink;
std::shared_ptr<spdlog::sinks::ringbuffer_sink_mt> early;
constexpr const char* file_pattern = "[%Y-%m-%d %H:%M:%S.%e] [%l] %v";
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
  if (early) {
    std::ofstream out(file, std::ios::app);
    if (!out) throw Error(cannot + std::strerror(errno));
    for (const auto& line : early->last_formatted()) out << line;
  }
  std::shared_ptr<spdlog::sinks::sink> sink;
  try {
    sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(file.string(), false);
  } catch (const spdlog::spdlog_ex& e) {  // its message names the file and the OS reason
    throw Error(cannot + e.what());
  }
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
