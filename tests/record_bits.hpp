// Test helper: every field of an event record as bits, for comparing two engines' events
// bit for bit (a NaN magnitude equals itself). Header-only.
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include "engine/event_record.hpp"

namespace bkq::test {

inline std::vector<std::uint64_t> record_bits(const EventRecord& e) {
  auto b = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  return {static_cast<std::uint64_t>(e.event),
          b(e.load),
          static_cast<std::uint64_t>(e.trigger),
          static_cast<std::uint64_t>(e.blocks),
          b(e.moment),
          b(e.magnitude),
          b(e.duration),
          b(e.max_speed),
          b(e.pad_displacement),
          static_cast<std::uint64_t>(e.first_block),
          static_cast<std::uint64_t>(e.last_block),
          b(e.energy_residual)};
}

}  // namespace bkq::test
