#include "core/adapt/measurement_rotation.h"

#include <algorithm>

#include "core/parallel.h"

namespace dynamesh {

std::size_t MeasurementRotation::turn_block(std::size_t faces) {
  return std::clamp<std::size_t>(faces / (kRotation * kBlocksPerTurn), 1, kMaxBlock);
}

void MeasurementRotation::grow(std::size_t capacity) {
  for (std::size_t f = turn_of_.size(); f < capacity; ++f)
    turn_of_.push_back(static_cast<std::uint8_t>(f % kRotation));
  if (next_.size() < capacity) next_.resize(capacity, kNone);
}

void MeasurementRotation::reset() {
  turn_of_.clear();
  next_.clear();
  pending_ = 0;
}

void MeasurementRotation::set_step(std::uint64_t step) {
  const auto turn = static_cast<std::uint8_t>(step % kRotation);
  // The same step again (sub-steps, a repair's sampling) serves the same turn.
  if (pending_ > 0 && turn != turn_) take_pending(turn_);
  turn_ = turn;
}

void MeasurementRotation::take_pending(std::uint8_t served) {
  const auto n = static_cast<std::int64_t>(next_.size());
  std::size_t taken = 0;
#pragma omp parallel for schedule(static) reduction(+ : taken) if (n > kParallelMin)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (next_[k] == kNone || (served != kEveryTurn && turn_of_[k] != served)) continue;
    turn_of_[k] = static_cast<std::uint8_t>(next_[k] - 1);
    next_[k] = kNone;
    ++taken;
  }
  pending_ -= taken;
}

std::uint32_t MeasurementRotation::steps_until(std::uint8_t turn) const {
  return (turn + kRotation - turn_ - 1) % kRotation + 1;
}

void MeasurementRotation::renumber(const Renumbering& r) {
  renumber_elements(turn_of_, r.face, r.n_faces);
  renumber_elements(next_, r.face, r.n_faces);
  pending_ = static_cast<std::size_t>(
      std::count_if(next_.begin(), next_.end(), [](std::uint8_t t) { return t != kNone; }));
}

void MeasurementRotation::group_in_order() {
  const std::size_t n = turn_of_.size();
  const std::size_t block = turn_block(n);
  pending_ = 0;
  for (std::size_t f = 0; f < n; ++f) {
    const auto turn = static_cast<std::uint8_t>(f / block % kRotation);
    // Last on turn at most kRotation - steps_until(old) steps ago: the new turn may come no
    // later than the old one would (the current turn has been served). All faces were just
    // measured where every face is on turn.
    if (turn_ == kEveryTurn || steps_until(turn) <= steps_until(turn_of_[f])) {
      turn_of_[f] = turn;
      next_[f] = kNone;
    } else {
      next_[f] = static_cast<std::uint8_t>(turn + 1);
      ++pending_;
    }
  }
}

}  // namespace dynamesh
