// The run's stop request: a progress indicator whose user break polls it, one per request.
#include "base/stop.hpp"

#include <Message_ProgressIndicator.hxx>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>

#include "occt_bridge/sweeper.hpp"

namespace sweep::occt {

/// Polls the request; once it has fired, keeps its reason (the request may not fire twice).
class StopIndicator : public Message_ProgressIndicator {
 public:
  explicit StopIndicator(std::function<std::string()> stop) : stop_(std::move(stop)) {}
  Standard_Boolean UserBreak() override { return !reason().empty(); }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

  std::string reason() {
    if (fired_.load(std::memory_order_acquire)) return reason_;
    std::lock_guard<std::mutex> lock(mutex_);
    if (fired_.load(std::memory_order_relaxed)) return reason_;
    std::string r = stop_ ? stop_() : std::string();
    if (r.empty()) return r;
    reason_ = std::move(r);
    fired_.store(true, std::memory_order_release);
    return reason_;
  }

 private:
  std::function<std::string()> stop_;
  std::mutex mutex_;
  std::atomic<bool> fired_{false};
  std::string reason_;
};

namespace {
thread_local StopIndicator* t_request = nullptr;
}  // namespace

StopScope::StopScope(std::function<std::string()> stop) : outer_(t_request) {
  if (!stop) return;  // no request of its own: the outer one stays in force
  Handle(StopIndicator) ind = new StopIndicator(std::move(stop));
  mine_ = ind;
  t_request = ind.get();
}

StopScope::~StopScope() { t_request = outer_; }

void check_stop() {
  if (!t_request) return;
  const std::string why = t_request->reason();
  if (!why.empty()) throw Stopped(why);
}

Message_ProgressRange stop_range() { return t_request ? t_request->Start() : Message_ProgressRange(); }

StopIndicator* current_stop() { return t_request; }

AdoptStop::AdoptStop(StopIndicator* request) : outer_(t_request) {
  if (!request) return;
  // an indicator of this thread's own that asks the shared request: OCCT's progress ranges of
  // one indicator must not be started from two threads at once
  Handle(StopIndicator) ind = new StopIndicator([request]() { return request->reason(); });
  mine_ = ind;
  t_request = ind.get();
}
AdoptStop::~AdoptStop() { t_request = outer_; }

std::function<std::string()> stop_after(double seconds, std::function<std::string()> also) {
  const auto start = std::chrono::steady_clock::now();
  return [start, seconds, also = std::move(also)]() -> std::string {
    if (also)
      if (std::string why = also(); !why.empty()) return why;
    if (seconds > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) {
      char text[80];
      std::snprintf(text, sizeof text, "the time limit of %g s was reached", seconds);
      return text;
    }
    return {};
  };
}

}  // namespace sweep::occt
