#include "app/viewer/simulation_driver.h"

#include <sys/resource.h>
#include <unistd.h>

namespace dynamesh {
namespace {
constexpr int kWorkerNiceness = 10;
// A redraw costs the UI thread tens of milliseconds on a software renderer, taken from the
// loading it shows: a few per second.
constexpr std::chrono::milliseconds kProgressInterval(200);
}  // namespace

SimulationDriver::SimulationDriver(std::function<void()> on_result,
                                   std::function<void()> on_progress)
    : on_result_(std::move(on_result)),
      on_progress_(std::move(on_progress)),
      worker_([this] { run(); }) {}

void SimulationDriver::set_progress(std::string_view stage, double fraction) {
  {
    std::lock_guard lock(mutex_);
    progress_ = std::string(stage) + " " + std::to_string(static_cast<int>(100 * fraction)) + "%";
  }
  const auto now = std::chrono::steady_clock::now();
  if (on_progress_ && now - progress_told_ >= kProgressInterval) {
    progress_told_ = now;
    on_progress_();
  }
}

SimulationDriver::~SimulationDriver() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
    pending_.reset();
  }
  wake_.notify_all();
  worker_.join();
}

void SimulationDriver::request_step(const StepRequest& request) {
  {
    std::lock_guard lock(mutex_);
    // A restart must not be lost behind a later plain step: the newest request inherits it.
    const bool restart = request.restart || (pending_ && pending_->restart);
    pending_ = request;
    pending_->restart = restart;
  }
  wake_.notify_one();
}

bool SimulationDriver::busy() const {
  std::lock_guard lock(mutex_);
  return computing_ || pending_.has_value();
}

void SimulationDriver::wait_idle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return !running_step_ && !pending_; });
}

StepResult SimulationDriver::latest_result() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

std::uint64_t SimulationDriver::results_published() const {
  std::lock_guard lock(mutex_);
  return published_;
}

std::string SimulationDriver::progress() const {
  std::lock_guard lock(mutex_);
  return progress_;
}

void SimulationDriver::run() {
  // Below the UI thread: on a machine with few cores the adapter's threads (OpenMP's team
  // inherits this thread's niceness) must not take the cores that draw the window.
  ::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), kWorkerNiceness);
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
    if (stop_) return;
    const StepRequest request = *pending_;
    pending_.reset();
    running_step_ = computing_ = true;
    lock.unlock();
    StepResult result = simulation_.step(request);  // the long part, unlocked
    result.request_id = request.id;
    lock.lock();
    // A failed request keeps showing the last good mesh, with the error beside it.
    if (!result.snapshot) result.snapshot = latest_.snapshot;
    latest_ = std::move(result);
    ++published_;
    computing_ = false;
    progress_.clear();
    if (on_result_) {
      lock.unlock();
      on_result_();
      lock.lock();
    }
    running_step_ = false;  // only now: wait_idle() returns after the callback too
    if (!pending_) idle_.notify_all();
  }
}

}  // namespace dynamesh
