#include "stop_request.hpp"

#include <cmath>
#include <csignal>
#include <cstdlib>

#include "occt_bridge/sweeper.hpp"
#include "sweep/error.hpp"
#include "worker.hpp"

namespace sweep::cli {
namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop_signal(int sig) {
  if (!g_signal) g_signal = sig;
}

extern "C" void on_stop_signal_once(int sig) {
  g_signal = sig;
  std::signal(sig, SIG_DFL);  // a second one ends the process
}

}  // namespace

double parse_time_limit(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v <= 0)
    throw InputError("--time-limit", "--time-limit needs a positive number of seconds (got '" + text + "')");
  return v;
}

std::function<std::string()> stop_request(double time_limit) {
  // a signal the parent ignores (SIGINT in a shell's background job) stays ignored
  for (int sig : {SIGINT, SIGTERM})
    // in a worker the supervisor ends the process at a second signal
    if (std::signal(sig, in_worker() ? on_stop_signal : on_stop_signal_once) == SIG_IGN) std::signal(sig, SIG_IGN);
  return sweep::occt::stop_after(time_limit, []() -> std::string {
    if (const int sig = g_signal) return sig == SIGINT ? "interrupted (SIGINT)" : "terminated (SIGTERM)";
    return {};
  });
}

}  // namespace sweep::cli
