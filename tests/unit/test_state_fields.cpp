// The shared checksum (core/fnv1a.hpp) against published FNV-1a 64 vectors, and an
// observer state written with put_state read back with find_state.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "core/fnv1a.hpp"
#include "io/checkpoint.hpp"

namespace bkq {
namespace {

TEST(Fnv1a, MatchesTheReferenceVectorsAndContinues) {
  EXPECT_EQ(fnv1a64(""), kFnv1a64Basis);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(fnv1a64("bar", fnv1a64("foo")), fnv1a64("foobar"));
}

TEST(ObserverState, PutStateAndFindStateRoundTripEachFieldType) {
  Checkpoint c;
  const double x = 0.1 + 0.2;
  const std::int64_t n = -7;
  const std::uint64_t u = 0xfedcba9876543210ull;
  put_state(c, "probe", x, n, u);
  double x2 = 0;
  std::int64_t n2 = 0;
  std::uint64_t u2 = 0;
  ASSERT_TRUE(find_state(c, "probe", x2, n2, u2));
  EXPECT_EQ(x2, x);
  EXPECT_EQ(n2, n);
  EXPECT_EQ(u2, u);
  // The bytes are the StateWriter encoding of the same fields in the same order.
  StateWriter w;
  w.f64(x);
  w.i64(n);
  w.u64(u);
  EXPECT_EQ(*c.find("probe"), w.bytes());
}

TEST(ObserverState, FindStateIsFalseWithoutTheStateAndThrowsOnShortBytes) {
  Checkpoint c;
  double x = 1.5;
  EXPECT_FALSE(find_state(c, "absent", x));
  EXPECT_EQ(x, 1.5);
  put_state(c, "short", 2.5);
  std::int64_t n = 0;
  EXPECT_THROW(find_state(c, "short", x, n), Error);
}

}  // namespace
}  // namespace bkq
