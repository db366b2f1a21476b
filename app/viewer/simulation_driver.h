// SimulationDriver: runs the Simulation on a worker thread so the window stays responsive
// while a step computes. The UI thread calls request_step() (never blocks; a request made
// while a step runs replaces any older pending one: the newest wish wins) and polls
// latest_result() each frame; finished snapshots are handed over as shared_ptr to const, so
// the renderer reads them while the worker builds the next.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>

#include "app/viewer/simulation.h"

namespace dynamesh {

class SimulationDriver {
 public:
  // `on_result` (optional) is called on the worker thread after each result is published,
  // e.g. to wake a UI thread that sleeps waiting for events.
  // `on_progress` (optional, worker thread) hears that the loading progress moved, at most
  // every kProgressInterval, e.g. to wake the UI thread so the panel shows it.
  explicit SimulationDriver(std::function<void()> on_result = {},
                            std::function<void()> on_progress = {});
  ~SimulationDriver();  // finishes the running step, drops pending ones, joins
  SimulationDriver(const SimulationDriver&) = delete;
  SimulationDriver& operator=(const SimulationDriver&) = delete;

  void request_step(const StepRequest& request);
  // True while a step runs or waits to run.
  bool busy() const;
  // Blocks until no step runs or waits (scripted runs use this to be deterministic).
  void wait_idle();
  // The most recent finished request and a counter that grows with each one (so the caller
  // can tell a new result from the one it already has). A failed request's result carries
  // the error with the last good snapshot.
  StepResult latest_result() const;
  std::uint64_t results_published() const;
  // The stage of loading a scene from a file, e.g. "distance transform 40%"; empty when none
  // is loading.
  std::string progress() const;

 private:
  void run();

  void set_progress(std::string_view stage, double fraction);

  Simulation simulation_{
      [this](std::string_view stage, double fraction) { set_progress(stage, fraction); }};
  std::function<void()> on_result_, on_progress_;
  std::chrono::steady_clock::time_point progress_told_;  // worker thread only
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::optional<StepRequest> pending_;
  bool running_step_ = false;  // until the result's callback returned (wait_idle)
  // Until the result is published: busy() must be false when the callback's wake-up draws a
  // frame, or that frame shows "(computing)" and a playing viewer waits for the next event.
  bool computing_ = false;
  bool stop_ = false;
  StepResult latest_;
  std::uint64_t published_ = 0;
  std::string progress_;
  std::thread worker_;  // last: starts after everything above exists
};

}  // namespace dynamesh
