// The event engine's driver and its parts (engine/relaxation.hpp): the ledger books exactly
// what the paths report; a path and a scheme that the program does not ship, registered
// here, run without any change to the engine; and a scheme's declared traits decide what
// it is offered (a scheme that declares no located capability is refused located
// transitions). The paths against the general step: test_cluster.cpp, test_pad_paths.cpp
// (cluster kernel, fused held ranges) and test_lone_slip.cpp (the replayed start).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "../record_bits.hpp"
#include "../scene_sim.hpp"
#include "app/accuracy.hpp"
#include "core/error.hpp"
#include "engine/general_path.hpp"
#include "integrate/located.hpp"
#include "integrate/scheme_traits.hpp"

namespace bkq {
namespace {

using test::record_bits;
using test::Settings;
using test::Sim;

Settings chain(const std::string& scheme) {
  return {{"model.blocks", "40"}, {"integrator.scheme", scheme}, {"integrator.dt", "0.005"}};
}

TEST(RelaxationLedger, CountersAndEnergyBooksAreTheSumOfThePathsReports) {
  for (const char* scheme : {"rk4", "rk2"}) {
    SCOPED_TRACE(scheme);
    Sim sim(chain(scheme));
    struct Sum {
      std::int64_t calls = 0, steps = 0, block_steps = 0, sliding_block_steps = 0, releases = 0;
      double work = 0;
    };
    std::map<std::string, Sum> by_path;
    Sum all;
    sim.engine.observe_reports([&](const PathReport& r) {
      for (Sum* s : {&by_path[r.path], &all}) {
        ++s->calls;
        s->steps += r.steps;
        s->block_steps += r.block_steps;
        s->sliding_block_steps += r.sliding_block_steps;
        s->releases += static_cast<std::int64_t>(r.released.size() + r.released_inside.size());
        s->work += r.work;
      }
    });
    const int events = 2000;
    sim.run(events);
    const EngineCounters& c = sim.engine.counters();
    EXPECT_EQ(c.steps, all.steps);
    EXPECT_EQ(c.block_steps, all.block_steps);
    EXPECT_EQ(c.sliding_block_steps, all.sliding_block_steps);
    // Each event's trigger is released by the loader; every other release is a path's (the
    // pad is held, so no far block breaks while it swings).
    EXPECT_EQ(c.releases, all.releases + events);
    // The paths add to the event's book piece by piece; the reports' shares add up to it.
    EXPECT_GT(all.work, 0.0);
    EXPECT_NEAR(all.work, sim.engine.dissipated_total(), 1e-12 * sim.engine.dissipated_total());
    // Every shipped path took part, so the sums are not one path's.
    for (const char* path : {"replay", "cluster", "general"}) {
      EXPECT_GT(by_path[path].calls, 0) << path;
      EXPECT_GT(by_path[path].steps, 0) << path;
    }
  }
}

// A path the program does not ship: it takes every other step of an event with a general
// step of its own. Registered with add_path, it runs, and the events stay the same bit for
// bit.
class EveryOtherStep final : public RelaxationPath {
 public:
  const char* name() const override { return "every-other-step"; }
  bool advance(Relaxation& rx, PathReport& out) override {
    if (rx.steps % 2 == 0) return false;
    ++calls;
    return inner_.advance(rx, out);
  }
  std::int64_t calls = 0;

 private:
  GeneralStepPath inner_;
};

TEST(RelaxationPaths, ATestOnlyPathRunsWithoutTouchingTheEngine) {
  Sim plain(chain("rk4")), extended(chain("rk4"));
  auto path = std::make_unique<EveryOtherStep>();
  const EveryOtherStep& added = *path;
  extended.engine.add_path(std::move(path));
  std::int64_t reported = 0;
  extended.engine.observe_reports([&](const PathReport& r) {
    if (std::string(r.path) == "every-other-step") ++reported;
  });
  for (int i = 0; i < 1000; ++i)
    ASSERT_EQ(record_bits(plain.engine.next_event()), record_bits(extended.engine.next_event()))
        << "event " << i + 1;
  EXPECT_GT(added.calls, 100);
  EXPECT_EQ(reported, added.calls);
  EXPECT_EQ(plain.engine.counters().steps, extended.engine.counters().steps);
  EXPECT_EQ(plain.engine.state().w, extended.engine.state().w);
}

// A scheme the program does not ship: the midpoint rule of rk2 behind a stepper of its own
// that declares transitions at the step on every kernel, no fast kernels, and (unless told)
// no located transitions (a registration may declare other traits and another name).
class TestMidpoint final : public Stepper {
 public:
  static constexpr SchemeTraits kTraits{.stick_rule = StickRule::Crossing, .general_kernels = true};
  explicit TestMidpoint(int n, std::string name = "test-midpoint",
                        const SchemeTraits& traits = kTraits)
      : inner_(make_stepper("rk2", n)), name_(std::move(name)), traits_(traits) {}
  std::string_view name() const override { return name_; }
  std::unique_ptr<Stepper> fresh(int n) const override {
    return std::make_unique<TestMidpoint>(n, name_, traits_);
  }
  const SchemeTraits& traits() const override { return traits_; }
  int order() const override { return inner_->order(); }
  double stability_constant() const override { return inner_->stability_constant(); }
  void step(const ChainForces& f, const Substrate& sub, ChainState& st, double dt,
            Ranges ranges) override {
    inner_->step(f, sub, st, dt, ranges);
  }

 private:
  std::unique_ptr<Stepper> inner_;
  std::string name_;
  SchemeTraits traits_;
};

// Registers the test scheme for the lifetime of the guard.
struct Registered {
  Registered() {
    register_scheme("test-midpoint", TestMidpoint::kTraits,
                    [](int n, double) -> std::unique_ptr<Stepper> {
                      return std::make_unique<TestMidpoint>(n);
                    });
  }
  ~Registered() { unregister_scheme("test-midpoint"); }
};

TEST(RelaxationPaths, ATestOnlySchemeRunsWithoutTouchingTheEngine) {
  const Registered guard;
  ASSERT_NE(scheme_traits("test-midpoint"), nullptr);
  EXPECT_EQ(*scheme_traits("test-midpoint"), TestMidpoint::kTraits);
  Sim rk2(chain("rk2"));
  // The engine of the registered scheme, on the same model and state: it declares no
  // cluster kernel, so the general step takes what rk2's kernel takes; the replayed start
  // is built from the registry's stepper of its name.
  const auto stepper = make_stepper("test-midpoint", rk2.p.n);
  EXPECT_EQ(stepper->traits(), TestMidpoint::kTraits);
  EventEngine engine(rk2.forces, *stepper, 0.005, rk2.engine.state());
  for (int i = 0; i < 1000; ++i)
    ASSERT_EQ(record_bits(rk2.engine.next_event()), record_bits(engine.next_event()))
        << "event " << i + 1;
  EXPECT_EQ(engine.cluster_steps().all, 0);
  EXPECT_GT(rk2.engine.cluster_steps().all, 0);
  EXPECT_GT(engine.lone_slip_starts().replayed, 0);
  EXPECT_EQ(rk2.engine.counters().steps, engine.counters().steps);
}

TEST(RelaxationPaths, TheReplayedStartCopiesAnUnregisteredScheme) {
  // The lone-slip record is integrated by a copy of the engine's own stepper (Stepper::
  // fresh), not by the registry's stepper of its name: a scheme nobody registered gets its
  // replayed starts, and the events stay rk2's bit for bit.
  Sim rk2(chain("rk2"));
  TestMidpoint unlisted(rk2.p.n, "test-unlisted");
  ASSERT_EQ(scheme_traits("test-unlisted"), nullptr);
  EventEngine engine(rk2.forces, unlisted, 0.005, rk2.engine.state());
  for (int i = 0; i < 1000; ++i)
    ASSERT_EQ(record_bits(rk2.engine.next_event()), record_bits(engine.next_event()))
        << "event " << i + 1;
  EXPECT_GT(engine.lone_slip_starts().replayed, 0);
  EXPECT_EQ(rk2.engine.lone_slip_starts().replayed, engine.lone_slip_starts().replayed);
  EXPECT_EQ(rk2.engine.counters().steps, engine.counters().steps);
}

TEST(SchemeTraits, ASchemeWithoutTheLocatedCapabilityIsRefusedLocatedTransitions) {
  const Registered guard;
  try {
    with_located_transitions(make_stepper("test-midpoint", 10), 10);
    FAIL() << "located transitions were accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "integrator.transitions = located: the scheme test-midpoint resolves its "
              "transitions itself; located applies to rk2, rk4 and verlet (use "
              "integrator.transitions = step)");
  }
  // The shipped schemes as each declares itself.
  for (const char* s : {"theta", "adaptive"})
    EXPECT_THROW(with_located_transitions(make_stepper(s, 10), 10), Error) << s;
  for (const char* s : {"rk2", "rk4", "verlet"}) {
    const auto located = with_located_transitions(make_stepper(s, 10), 10);
    EXPECT_TRUE(located->traits().located_on_fixed_steps) << s;
    EXPECT_EQ(located->stick_rule(), StickRule::Located) << s;
  }
}

TEST(SchemeTraits, AccuracyOffersARegisteredSchemeByItsTraits) {
  EXPECT_EQ(AccuracyOptions().schemes, stepper_keywords());
  EXPECT_EQ(accuracy_reference_scheme(), "adaptive");
  const Registered guard;
  AccuracyOptions opt;
  // The default list is the registry's, the registered scheme last.
  ASSERT_FALSE(opt.schemes.empty());
  EXPECT_EQ(opt.schemes.back(), "test-midpoint");
  opt.schemes = {"rk2", "test-midpoint"};
  opt.dts = {0.02, 0.005};
  opt.tolerances = {1e-8};
  opt.samples = 4;
  opt.sample_spacing = 5;
  opt.long_events = kMinLongEvents;
  const Scene scene = test::make_scene({{"model.blocks", "30"}, {"run.transient_events", "100"}});
  const AccuracyStudy study = run_accuracy(scene, opt);
  // Not locatable: its transitions at the step only, where its errors are rk2's.
  std::map<std::string, std::map<double, double>> moment;
  for (const AccuracyPoint& pt : study.points) {
    if (pt.scheme != "test-midpoint") continue;
    EXPECT_EQ(pt.transitions, "step");
    EXPECT_EQ(pt.tolerance, 0.0);
    moment[pt.scheme][pt.dt] = pt.moment_error_median;
  }
  for (const AccuracyPoint& pt : study.points)
    if (pt.scheme == "rk2" && pt.transitions == "step")
      moment["rk2"][pt.dt] = pt.moment_error_median;
  EXPECT_EQ(moment["test-midpoint"].size(), 2u);
  EXPECT_EQ(moment["test-midpoint"], moment["rk2"]);
  // rk2 (locatable) is offered located transitions too.
  int rk2_located = 0;
  for (const AccuracyPoint& pt : study.points)
    rk2_located += pt.scheme == "rk2" && pt.transitions == "located";
  EXPECT_EQ(rk2_located, 2);
}

TEST(SchemeTraits, EachShippedStepperDeclaresTheRegistrysTraits) {
  for (const std::string& s : stepper_keywords()) {
    SCOPED_TRACE(s);
    ASSERT_NE(scheme_traits(s), nullptr);
    EXPECT_EQ(make_stepper(s, 4)->traits(), *scheme_traits(s));
  }
  EXPECT_EQ(scheme_traits("no-such-scheme"), nullptr);
  EXPECT_TRUE(scheme_traits("rk4")->fused_kernels);
  EXPECT_FALSE(scheme_traits("rk2")->fused_kernels);
  EXPECT_TRUE(scheme_traits("adaptive")->error_control);
  EXPECT_FALSE(scheme_traits("theta")->general_kernels);
  EXPECT_THROW(register_scheme("rk4", *scheme_traits("rk4"), nullptr), Error);
}

}  // namespace
}  // namespace bkq
