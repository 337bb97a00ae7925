// Test helper: runs two event engines side by side and expects the same events bit for bit,
// the same step counters and the same final positions and slips. The path tests compare each
// fast path with the general path this way. Header-only.
#pragma once

#include <gtest/gtest.h>

#include "engine/event_engine.hpp"
#include "record_bits.hpp"

namespace bkq::test {

// Wrap the call in ASSERT_NO_FATAL_FAILURE: the first differing event stops it.
inline void expect_same_events(EventEngine& a, EventEngine& b, int events) {
  for (int i = 0; i < events; ++i) {
    const EventRecord x = a.next_event(), y = b.next_event();
    ASSERT_EQ(record_bits(x), record_bits(y)) << "event " << i + 1;
  }
  const EngineCounters& ca = a.counters();
  const EngineCounters& cb = b.counters();
  EXPECT_EQ(ca.steps, cb.steps);
  EXPECT_EQ(ca.block_steps, cb.block_steps);
  EXPECT_EQ(ca.sliding_block_steps, cb.sliding_block_steps);
  EXPECT_EQ(ca.releases, cb.releases);
  EXPECT_EQ(a.state().w, b.state().w);
  EXPECT_EQ(a.state().s, b.state().s);
}

}  // namespace bkq::test
