// Work spread over the machine's cores.
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "base/internal.hpp"
#include "base/stop.hpp"

namespace sweep::occt {

void parallel_for(std::size_t n, const std::function<std::function<void(std::size_t)>()>& make) {
  const std::size_t nt = std::min<std::size_t>({std::max(1u, std::thread::hardware_concurrency()), 8, n});
  if (nt <= 1) {
    const auto work = make();
    for (std::size_t i = 0; i < n; ++i) {
      check_stop();
      work(i);
    }
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  StopIndicator* const request = current_stop();
  // Each worker takes the caller's stop request, and a signal inside OCCT becomes a
  // Standard_Failure that the caller rethrows (as on its own thread).
  auto run = [&] {
    AdoptStop adopted(request);
    try {
      OCC_CATCH_SIGNALS
      const auto work = make();
      for (std::size_t i = next++; i < n; i = next++) {
        check_stop();
        work(i);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = n;
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t t = 1; t < nt; ++t) threads.emplace_back(run);
  run();
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace sweep::occt
