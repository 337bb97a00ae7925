// The general step: one step of every covered range with the stepper's step() (its fused
// step_held() where every range ends in blocks that hold and the scheme fuses), then the
// dissipated work and the contact pass (engine/contacts.hpp). It applies to every state,
// and is the path the others are held equal to.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/relaxation.hpp"
#include "integrate/block_window.hpp"

namespace bkq {

class GeneralStepPath final : public RelaxationPath {
 public:
  const char* name() const override { return "general"; }
  bool advance(Relaxation& rx, PathReport& out) override;
  // Steps taken with the pad moving on the fused held-range step (a study count).
  std::int64_t pad_held_steps() const { return pad_held_steps_; }

 private:
  static bool held_ranges(const Relaxation& rx);
  // The blocks a stepper that resolves transitions itself released in its step: its own
  // list, then every block whose flag went from stuck to sliding. Covers them.
  void collect_released_inside(Relaxation& rx);

  // Velocities, stick flags and positions at the start of a step (the last two for
  // steppers that resolve transitions themselves), over the blocks of the step's ranges.
  enum { kWdOld, kMobileOld, kWOld };
  RangeArrays old_{3};
  std::vector<int> released_;
  std::vector<Stepper::Release> inside_;
  std::int64_t pad_held_steps_ = 0;
};

}  // namespace bkq
