// The measurement rotation (issue 17): every face has a turn, one step in kRotation, on which
// both sampling modes measure it, so that no face goes unmeasured for more than kRotation steps
// (predictive sampling's guard against what its bound does not model, ErrorPredictor).
//
// A new face slot takes the turn id % kRotation, and a renumbering moves each face's turn
// with it. After the adapter renumbers its mesh along a space-filling curve
// (Adapter::renumber_if_scattered), group_in_order() gives the faces their turns in blocks of
// consecutive ids (turn_block), so that the faces measured on one turn are patches of
// neighbours instead of every sixteenth face: an edge between two measured faces has its
// peaks read once for both (SampleStore::shared_edge_peaks), and the pass walks memory in order.
// At 10^6 triangles (capsule-bend, two threads) the sampling phase fell from ~185-225 ms to
// ~140-175 ms, though measuring's instructions fell by only 4.5%: mostly cache misses saved.
//
// A face takes its new turn only where that does not make it wait longer than kRotation steps
// since it was last on turn; otherwise once its old turn has come (pending). set_step()
// assumes the caller measured every face on the previous step's turn (the adapter does, in
// both modes).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/handles.h"
#include "core/mesh/renumbering.h"

namespace dynamesh {

class MeasurementRotation {
 public:
  static constexpr std::uint32_t kRotation = 16;
  // Turn blocks: at most kMaxBlock faces, and at least kBlocksPerTurn blocks per turn, so that
  // every turn holds nearly the same number of faces also on small meshes.
  static constexpr std::size_t kMaxBlock = 1024;
  static constexpr std::size_t kBlocksPerTurn = 16;
  static std::size_t turn_block(std::size_t faces);

  // Slots up to `capacity`, each new one with the turn id % kRotation.
  void grow(std::size_t capacity);
  void reset();  // no slots (the current turn stays)
  // The step whose turn it is; the previous step's turn counts as served (its faces measured),
  // and faces pending a new turn there take it.
  void set_step(std::uint64_t step);
  void set_every_turn() { turn_ = kEveryTurn; }
  bool on_turn(Face f) const { return turn_ == kEveryTurn || turn_of_[f.idx] == turn_; }
  std::uint8_t turn(Face f) const { return turn_of_[f.idx]; }
  std::size_t pending() const { return pending_; }
  // Follows a renumbering: the turns (and pending turns) move with their faces.
  void renumber(const Renumbering& r);
  // Each face's turn becomes its block's in the order of the ids (now, or once its old turn
  // has come). Between steps: the current turn has been served.
  void group_in_order();

 private:
  static constexpr std::uint8_t kEveryTurn = 0xff;
  static constexpr std::uint8_t kNone = 0;  // no pending turn (a slot a renumbering fills anew)
  // Steps from the current turn to the next step on `turn` (1 .. kRotation).
  std::uint32_t steps_until(std::uint8_t turn) const;
  void take_pending(std::uint8_t served);

  std::uint8_t turn_ = kEveryTurn;
  std::vector<std::uint8_t> turn_of_;  // each face slot's turn
  std::vector<std::uint8_t> next_;     // 1 + a turn it takes once its own is served, or kNone
  std::size_t pending_ = 0;            // slots with a next_ turn
};

}  // namespace dynamesh
