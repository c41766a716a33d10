#include "engine/io/run_summary.hpp"

#include <string>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"

namespace rift {

void RunSummary::set(std::string_view dotted_path, nlohmann::json value) {
  nlohmann::json* node = &root_;
  size_t start = 0;
  while (true) {
    const size_t dot = dotted_path.find('.', start);
    const std::string key(
        dotted_path.substr(start, dot == std::string_view::npos ? dotted_path.npos : dot - start));
    if (key.empty()) throw Error("run summary key '" + std::string(dotted_path) + "' has an empty segment");
    if (!node->is_object())
      throw Error(
          "run summary key '" + std::string(dotted_path) + "': " +
          (start == 0 ? std::string("the root") : "'" + std::string(dotted_path.substr(0, start - 1)) + "'") +
          " holds a " + node->type_name() + ", not an object");
    if (dot == std::string_view::npos) {
      (*node)[key] = std::move(value);
      return;
    }
    nlohmann::json& child = (*node)[key];
    if (child.is_null()) child = nlohmann::json::object();
    node = &child;
    start = dot + 1;
  }
}

void RunSummary::write(const std::filesystem::path& file) const {
  write_text_atomic(file, root_.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace rift
