#pragma once
// The run's stop request (RunOptions::stop), seen by every step of a run: OCCT's long algorithms
// get a progress range whose user break polls it, and our own loops call check_stop().
#include <Message_ProgressRange.hxx>
#include <Standard_Handle.hxx>
#include <Standard_Transient.hxx>
#include <functional>
#include <string>

#include "sweep/error.hpp"

namespace sweep::occt {

/// Thrown when the run's stop request fires; the run reports `failed` with its message.
class Stopped : public ComputeError {
 public:
  explicit Stopped(const std::string& reason) : ComputeError("stopped: " + reason) {}
};

/// A stop request as OCCT's progress indicator (stop.cpp).
class StopIndicator;

/// While alive, makes `stop` the stop request of this thread and of the workers parallel_for
/// starts from it (nested scopes restore the outer request).
class StopScope {
 public:
  explicit StopScope(std::function<std::string()> stop);
  ~StopScope();
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;

 private:
  Handle(Standard_Transient) mine_;
  StopIndicator* outer_;
};

/// Throws Stopped when this thread's stop request fires (cheap: call it once per piece of work).
void check_stop();
/// A progress range for one OCCT algorithm on this thread (its user break polls the request;
/// an empty range when there is none). Use it for one call, then call check_stop().
Message_ProgressRange stop_range();

/// The request in force on this thread, to hand to another thread (parallel_for does this).
StopIndicator* current_stop();
/// Makes `request` (from current_stop()) this thread's request while alive, through an indicator
/// of this thread's own, so that stop_range() may be called on any thread.
class AdoptStop {
 public:
  explicit AdoptStop(StopIndicator* request);
  ~AdoptStop();
  AdoptStop(const AdoptStop&) = delete;
  AdoptStop& operator=(const AdoptStop&) = delete;

 private:
  Handle(Standard_Transient) mine_;
  StopIndicator* outer_;
};

}  // namespace sweep::occt
