#pragma once
// The stop request of a command-line run (RunOptions::stop).
#include <functional>
#include <string>

namespace sweep::cli {

/// The time limit of a run that gives no --time-limit (seconds).
constexpr double kDefaultTimeLimit = 600;

/// `--time-limit SECONDS`: a positive number of seconds. @throws InputError naming the option.
double parse_time_limit(const std::string& text);

/// Installs handlers for SIGINT and SIGTERM (unless the process ignores them) and returns the
/// request a run polls: the first such signal stops the run (a second one ends the process), and
/// with time_limit > 0 so does the wall-clock time passing it, counted from this call.
std::function<std::string()> stop_request(double time_limit);

}  // namespace sweep::cli
