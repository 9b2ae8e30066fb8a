#include "worker.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace sweep::cli {
namespace {

bool g_in_worker = false;
bool g_stderr_terminal = false;  ///< the supervisor's stderr, seen from the worker
volatile std::sig_atomic_t g_first_signal = 0;
volatile std::sig_atomic_t g_signals = 0;

extern "C" void on_supervisor_signal(int sig) {
  if (g_signals == 0) g_first_signal = sig;
  g_signals = g_signals + 1;
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// `dir/.name.sweep-PID.ext` beside `path`, keeping its extension (the writers choose the format by it).
std::string temporary_beside(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = base.find_last_of('.');
  const std::string stem = dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
  const std::string ext = dot == std::string::npos || dot == 0 ? "" : base.substr(dot);
  return dir + "." + stem + ".sweep-" + std::to_string(getpid()) + ext;
}

void remove_temporary(const std::string& tmp) {
  std::remove(tmp.c_str());
  std::remove((tmp + ".partial").c_str());  // the writers' own temporary
}

std::string signal_reason(int sig) {
  if (sig == SIGINT) return "interrupted (SIGINT)";
  if (sig == SIGTERM) return "terminated (SIGTERM)";
  return "signal " + std::to_string(sig);
}

/// The test hook for a step that never polls: the worker says so on stderr (as a run's progress
/// lines do), then ignores stop signals and sleeps for the seconds that SWEEP_TEST_WORKER_STALL
/// gives before it starts the command.
void stall_if_asked() {
  const char* stall = std::getenv("SWEEP_TEST_WORKER_STALL");
  if (!stall || !*stall) return;
  std::cerr << "sweepvol: test hook: the worker stalls for " << stall << " s" << std::endl;
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_IGN);
  std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(stall)));
}

[[noreturn]] void run_worker(int out_fd, int err_fd, int argc, std::vector<std::string>& args,
                             const std::function<int(int, char**)>& command) {
  g_in_worker = true;
  // the supervisor's handlers are not the worker's; a signal the caller ignores stays ignored
  for (int sig : {SIGINT, SIGTERM})
    if (std::signal(sig, SIG_DFL) == SIG_IGN) std::signal(sig, SIG_IGN);
  if (dup2(out_fd, STDOUT_FILENO) < 0 || dup2(err_fd, STDERR_FILENO) < 0) _exit(1);
  close(out_fd);
  close(err_fd);
  stall_if_asked();
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int code = command(argc, argv.data());
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  _exit(code);  // no static destructors: the supervisor owns the process's end
}

/// Reads what is there on `fd` into `out`; false at end of file.
bool drain(int fd, std::string& out) {
  char buf[65536];
  while (true) {
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n > 0) {
      out.append(buf, static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0) return false;
    if (errno == EINTR) continue;
    return errno == EAGAIN || errno == EWOULDBLOCK;
  }
}

struct Ending {
  int status = 0;
  bool killed = false;  ///< ended by the supervisor
  std::string reason;   ///< why, when killed
};

/// One of the worker's output streams as the supervisor reads it.
struct Stream {
  int fd;
  bool open = true;
  std::string text;
};

/// `text` with every temporary output name replaced by its final name (the worker's messages
/// name the files the user gave).
std::string with_final_names(std::string text, const std::vector<Output>& outputs) {
  for (const Output& o : outputs)
    for (std::size_t at; (at = text.find(o.temporary)) != std::string::npos;) text.replace(at, o.temporary.size(), o.path);
  return text;
}

/// Passes the complete lines of the worker's stderr on (all of it once `all`).
void pass_on_stderr(Stream& err, const std::vector<Output>& outputs, bool all) {
  const std::size_t end = all ? err.text.size() : err.text.rfind('\n') + 1;  // npos + 1 == 0
  if (end == 0) return;
  std::cerr << with_final_names(err.text.substr(0, end), outputs);
  std::cerr.flush();
  err.text.erase(0, end);
}

/// Waits for the worker, reading its stdout and passing its stderr on line by line, passing on
/// the first stop signal and ending it when the grace period or the time limit runs out, or at a
/// second signal.
Ending supervise(pid_t pid, Stream& out, Stream& err, const WorkerPlan& plan,
                 const std::vector<Output>& outputs) {
  const double start = now(), inf = std::numeric_limits<double>::infinity();
  const double deadline = plan.time_limit > 0 ? start + plan.time_limit + plan.grace : inf;
  double kill_at = inf;
  bool forwarded = false;
  Ending e;
  while (true) {
    pollfd p[2] = {{out.open ? out.fd : -1, POLLIN, 0}, {err.open ? err.fd : -1, POLLIN, 0}};
    if (out.open || err.open) {
      if (poll(p, 2, 20) > 0) {
        if (p[0].revents) out.open = drain(out.fd, out.text);
        if (p[1].revents) err.open = drain(err.fd, err.text);
        pass_on_stderr(err, outputs, false);
      }
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (waitpid(pid, &e.status, WNOHANG) == pid) {
      if (out.open) drain(out.fd, out.text);
      if (err.open) drain(err.fd, err.text);
      pass_on_stderr(err, outputs, true);
      return e;
    }
    if (e.killed) continue;
    const int signals = g_signals;
    if (signals > 0 && !forwarded) {
      kill(pid, g_first_signal);
      forwarded = true;
      kill_at = now() + plan.grace;
    }
    std::string why;
    if (signals > 1 || (forwarded && now() > kill_at)) why = signal_reason(g_first_signal);
    else if (now() > deadline) {
      char text[80];
      std::snprintf(text, sizeof text, "the time limit of %g s was reached", plan.time_limit);
      why = text;
    }
    if (!why.empty()) {
      kill(pid, SIGKILL);
      e.killed = true;
      e.reason = "stopped: " + why;
    }
  }
}

}  // namespace

bool in_worker() { return g_in_worker; }

bool stderr_is_terminal() { return g_in_worker ? g_stderr_terminal : isatty(STDERR_FILENO) != 0; }

int run_in_worker(int argc, char** argv, const WorkerPlan& plan, const std::function<int(int, char**)>& command) {
  std::vector<std::string> args(argv, argv + argc);
  std::vector<Output> outputs;
  for (int i = 1; i + 1 < argc; ++i)
    for (const std::string& opt : plan.output_options)
      if (args[i] == opt) {
        outputs.push_back({opt, args[i + 1], temporary_beside(args[i + 1])});
        args[++i] = outputs.back().temporary;
        break;
      }
  int out_fds[2], err_fds[2];
  if (pipe(out_fds) != 0) return command(argc, argv);  // no worker to be had: run here
  if (pipe(err_fds) != 0) {
    close(out_fds[0]);
    close(out_fds[1]);
    return command(argc, argv);
  }
  std::cout.flush();
  std::fflush(nullptr);
  g_stderr_terminal = isatty(STDERR_FILENO) != 0;
  for (int sig : {SIGINT, SIGTERM})
    if (std::signal(sig, on_supervisor_signal) == SIG_IGN) std::signal(sig, SIG_IGN);
  const pid_t pid = fork();
  if (pid == 0) {
    close(out_fds[0]);
    close(err_fds[0]);
    run_worker(out_fds[1], err_fds[1], argc, args, command);
  }
  close(out_fds[1]);
  close(err_fds[1]);
  if (pid < 0) {
    close(out_fds[0]);
    close(err_fds[0]);
    return command(argc, argv);
  }
  // the supervisor reads what is there and goes back to its clock: a read must never wait
  for (int fd : {out_fds[0], err_fds[0]}) fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
  Stream out{out_fds[0], true, {}}, err{err_fds[0], true, {}};
  const Ending e = supervise(pid, out, err, plan, outputs);
  close(out_fds[0]);
  close(err_fds[0]);
  if (!e.killed && WIFEXITED(e.status)) {
    for (const Output& o : outputs)
      if (access(o.temporary.c_str(), F_OK) == 0 && std::rename(o.temporary.c_str(), o.path.c_str()) != 0)
        remove_temporary(o.temporary);
    for (const Output& o : outputs) remove_temporary(o.temporary);
    std::cout << with_final_names(out.text, outputs);
    std::cout.flush();
    return WEXITSTATUS(e.status);
  }
  for (const Output& o : outputs) remove_temporary(o.temporary);
  std::string reason = e.reason;
  if (!e.killed) {
    const int sig = WIFSIGNALED(e.status) ? WTERMSIG(e.status) : 0;
    reason = "the computation ended abnormally (" + std::string(sig ? strsignal(sig) : "unknown status") + ")";
  }
  return plan.on_ended(reason, outputs);
}

}  // namespace sweep::cli
