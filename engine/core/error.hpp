#pragma once
// One exception type for everything a user can get wrong or a run can run into. The message is
// complete on its own (where, what was expected, what was found, what to change), so the CLI only
// prints it. Programming errors use assertions, not this.
#include <stdexcept>
#include <string>

namespace rift {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace rift
