// libFuzzer target: spec text of any form either parses or throws InputError, never anything else.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "sweep/error.hpp"
#include "sweep/spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // file names resolve against a directory that does not exist: no file is read
    (void)sweep::parse_spec(text, "/nonexistent-fuzz-dir");
  } catch (const sweep::InputError&) {
  }
  return 0;
}
