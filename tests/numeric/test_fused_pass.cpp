// The general step's fused pass (integrate/layouts.hpp: one long range in pieces, the
// updates one block behind the accelerations) against its two-pass form (accelerations of
// every block first, then the updates), which the same chain split into two adjacent
// ranges takes: the states must agree bit for bit, for every explicit scheme, with the
// pad moving or held, free or periodic ends, with blocks stuck among sliding ones.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/initial_state.hpp"
#include "integrate/stepper.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"
#include "model/chain.hpp"
#include "model/substrate.hpp"

namespace bkq {
namespace {

ModelParams chain(const std::string& kind, const std::string& boundary, int n) {
  Scene scene;
  scene.set("model.kind", kind);
  scene.set("model.boundary", boundary);
  scene.set("friction.law", "thesis");
  scene.set("model.blocks", std::to_string(n));
  if (kind == "bkp") scene.set("model.parameterisation", "thesis");
  scene.validate();
  return model_from_scene(scene);
}

// A loaded chain with every third block stuck and the others sliding at various speeds.
ChainState mixed_state(const ChainForces& forces) {
  ChainState st = initial_state(forces, 7, 0.75, false);
  for (int j = 0; j < st.n(); ++j) {
    const bool slides = j % 3 != 0;
    st.mobile[j] = slides ? 1.0 : 0.0;
    st.wd[j] = slides ? 0.05 * ((j * 37) % 11 - 3) : 0.0;
    st.dir[j] = st.wd[j] < 0 ? -1.0 : 1.0;
  }
  st.xd = 0.01;
  st.recompute_sum_w();
  return st;
}

TEST(FusedPass, OneLongRangeIsTheTwoPassFormBitForBit) {
  const int n = 300;  // four full pieces of 64 blocks and a short one
  for (const char* kind : {"bkp", "bk"})
    for (const char* boundary : {"free", "periodic"}) {
      const ModelParams p = chain(kind, boundary, n);
      const ChainForces forces(p);
      const Substrate substrate = Substrate::constant(0.1);
      for (const char* scheme : {"rk2", "rk4", "verlet"}) {
        SCOPED_TRACE(std::string(kind) + " " + boundary + " " + scheme);
        auto fused = make_stepper(scheme, n);
        auto two_pass = make_stepper(scheme, n);
        ChainState a = mixed_state(forces), b = a;
        const std::vector<Range> whole{{0, n}}, split{{0, 150}, {150, n}};
        for (int i = 0; i < 40; ++i) {
          fused->step(forces, substrate, a, 0.005, whole);
          two_pass->step(forces, substrate, b, 0.005, split);
        }
        ASSERT_NE(a.w, mixed_state(forces).w) << "the chain moved";
        for (int j = 0; j < n; ++j) {
          ASSERT_EQ(a.w[j], b.w[j]) << "block " << j;
          ASSERT_EQ(a.wd[j], b.wd[j]) << "block " << j;
        }
        EXPECT_EQ(a.x, b.x);
        EXPECT_EQ(a.xd, b.xd);
        EXPECT_EQ(a.sum_w, b.sum_w);
      }
    }
}

}  // namespace
}  // namespace bkq
