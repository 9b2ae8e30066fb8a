#pragma once
// A command run in a worker process that the command-line process supervises. The worker does the
// geometry; the supervisor holds the time limit and the stop signals, so a step that never polls
// the stop request (an OCCT algorithm without a user break) still ends the run on time.
#include <functional>
#include <string>
#include <vector>

namespace sweep::cli {

/// An output file of a command: the option that names it, the path the user gave, and the
/// temporary path beside it that the worker writes instead.
struct Output {
  std::string option, path, temporary;
};

/// How the supervisor runs one command.
struct WorkerPlan {
  /// Options whose value is an output file ("-o", "--report", ...). The worker writes each to a
  /// temporary file beside it (same extension); the supervisor renames them into place only when
  /// the worker ended by itself, and removes them otherwise, so no half-written file is left.
  std::vector<std::string> output_options;
  /// Seconds; 0: none. The worker stops itself at the limit; the supervisor ends it when it has
  /// not ended `grace` seconds later.
  double time_limit = 0;
  double grace = 0.5;
  /// Writes what the command prints when the worker had to be ended (the reason: "stopped: ..."
  /// or how the worker died), to stdout and to the outputs' final paths. Returns the exit code.
  std::function<int(const std::string& reason, const std::vector<Output>& outputs)> on_ended;
};

/// Runs `command(argc, argv)` in a forked worker (argv with output paths replaced by temporary
/// ones) and returns its exit code. The worker's stderr is passed on line by line and its stdout
/// once it has ended by itself, both with the temporary names replaced by the final ones.
/// A first SIGINT or SIGTERM is passed on to the worker, which stops at its next poll; a second
/// one, or the grace period running out, ends it with SIGKILL.
int run_in_worker(int argc, char** argv, const WorkerPlan& plan, const std::function<int(int, char**)>& command);

/// True inside a worker (its stop request keeps the first signal and never ends the process: the
/// supervisor does that).
bool in_worker();

/// Whether the command's stderr is a terminal (progress lines go there): in a worker, the
/// supervisor's stderr, which the worker's is passed on to.
bool stderr_is_terminal();

}  // namespace sweep::cli
