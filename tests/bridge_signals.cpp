// A fault inside OCCT's signal guard becomes a Standard_Failure, which run_sweep reports as failed.
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>

#include <csignal>
#include <string>

#include <catch2/catch.hpp>
#include "base/internal.hpp"

namespace {

/// Raises `sig` inside OCC_CATCH_SIGNALS; returns the failure's message ("" when nothing was caught).
std::string caught_message(int sig) {
  try {
    OCC_CATCH_SIGNALS
    std::raise(sig);
  } catch (const Standard_Failure& f) {
    return f.GetMessageString() ? f.GetMessageString() : "(no message)";
  }
  return "";
}

}  // namespace

TEST_CASE("Signals: a segmentation fault and a floating-point signal inside OCCT's guard become failures") {
  // as the command line does (Catch's own handlers are set in this process)
  sweep::occt::install_signal_handlers(true);
  const std::string segv = caught_message(SIGSEGV);
  CAPTURE(segv);
  CHECK(!segv.empty());
  const std::string fpe = caught_message(SIGFPE);
  CAPTURE(fpe);
  CHECK(!fpe.empty());
}
