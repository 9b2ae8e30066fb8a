// Merging same-domain faces of a result, with a time limit.
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <string>

#include "internal.hpp"

namespace sweep::occt {
namespace {

bool solids_valid(const TopoDS_Shape& sh) {
  for (TopExp_Explorer ex(sh, TopAbs_SOLID); ex.More(); ex.Next())
    if (!BRepCheck_Analyzer(ex.Current()).IsValid()) return false;
  return BRepCheck_Analyzer(sh).IsValid();
}

}  // namespace

TopoDS_Shape unify_faces(const TopoDS_Shape& shape, double seconds) {
  // ShapeUpgrade_UnifySameDomain can change the shapes it is given and fail half-way (it works on
  // a copy), and on some arrangements of spline-bounded faces it does not return: it runs in a
  // child process that sends its result back through a pipe, and is stopped after `seconds`.
  int fds[2];
  if (pipe(fds) != 0) return {};
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return {};
  }
  if (pid == 0) {
    close(fds[0]);
    int code = 1;
    try {
      ShapeUpgrade_UnifySameDomain unify(BRepBuilderAPI_Copy(shape).Shape(), true, true, true);
      unify.Build();
      if (solids_valid(unify.Shape())) {
        std::ostringstream os;
        BRepTools::Write(unify.Shape(), os);
        const std::string text = os.str();
        std::size_t sent = 0;
        while (sent < text.size()) {
          const ssize_t n = write(fds[1], text.data() + sent, text.size() - sent);
          if (n <= 0) break;
          sent += std::size_t(n);
        }
        if (sent == text.size()) code = 0;
      }
    } catch (const Standard_Failure&) {
    }
    close(fds[1]);
    _exit(code);
  }
  close(fds[1]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::string text;
  bool eof = false;
  char buf[65536];
  while (!eof) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd pfd{fds[0], POLLIN, 0};
    const int r = poll(&pfd, 1, int(left.count()));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    eof = n == 0;
    if (n <= 0) break;
    text.append(buf, std::size_t(n));
  }
  close(fds[0]);
  if (!eof) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  TopoDS_Shape out;
  if (eof && WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    std::istringstream is(text);
    BRep_Builder b;
    BRepTools::Read(out, is, b);
  }
  return out;
}

}  // namespace sweep::occt
