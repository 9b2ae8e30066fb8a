#pragma once
// Shared by the subcommands' argument parsers.
#include <string>

#include "sweep/error.hpp"

namespace sweep::cli {

/// The value after option `name` at argv[i] (i moves onto it). @throws InputError when none follows.
inline std::string option_value(int argc, char** argv, int& i, const char* name) {
  if (i + 1 >= argc) throw sweep::InputError(name, std::string("option ") + name + " needs a value");
  return argv[++i];
}

}  // namespace sweep::cli
