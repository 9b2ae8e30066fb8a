#pragma once
/// @file error.hpp
/// The two error channels of the project: typed exceptions for user input and for computations
/// that fail or do not validate, and an assertion macro (file:line) for internal invariants.
#include <stdexcept>
#include <string>

namespace sweep {

/// Invalid user input. `pointer` is the JSON pointer of the offending field ("" for the document),
/// `line`/`column` its 1-based position in the spec text when known (0 otherwise).
/// The CLI maps it to exit code 2.
class InputError : public std::runtime_error {
 public:
  InputError(std::string pointer, const std::string& message, int line = 0, int column = 0)
      : std::runtime_error(message), pointer_(std::move(pointer)), line_(line), column_(column) {}
  const std::string& pointer() const { return pointer_; }
  int line() const { return line_; }
  int column() const { return column_; }
  void set_position(int line, int column) { line_ = line; column_ = column; }
  /// "spec.json:3:14: /entity/radius: must be positive (got -1)"
  std::string describe(const std::string& source = "") const;

 private:
  std::string pointer_;
  int line_, column_;
};

/// The computation failed, or its result failed validation. The CLI maps it to exit code 3.
class ComputeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Internal invariant violated (a bug). The CLI maps it to exit code 1.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

[[noreturn]] void assert_fail(const char* cond, const char* file, int line, const std::string& msg);

}  // namespace sweep

#define SWEEP_ASSERT(cond, msg)                                            \
  do {                                                                     \
    if (!(cond)) ::sweep::assert_fail(#cond, __FILE__, __LINE__, (msg));   \
  } while (0)
