#include "sweep/error.hpp"

namespace sweep {

std::string InputError::describe(const std::string& source) const {
  std::string s;
  if (!source.empty()) s += source + ":";
  if (line_ > 0) s += std::to_string(line_) + ":" + std::to_string(column_) + ":";
  if (!s.empty()) s += " ";
  s += (pointer_.empty() ? std::string("/") : pointer_) + ": " + what();
  return s;
}

void assert_fail(const char* cond, const char* file, int line, const std::string& msg) {
  throw InternalError(std::string(file) + ":" + std::to_string(line) + ": assertion `" + cond +
                      "` failed: " + msg);
}

}  // namespace sweep
