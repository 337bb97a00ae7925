// Coupling beyond nearest neighbours (model.coupling = range | power, model/coupling.hpp):
// the stencil's normalisation; the coupling matrix (symmetric, rows summing to zero, the
// stated diagonal; no force from a uniform translation); a released block reaching exactly
// its R neighbours on each side in one step; R = 1 giving today's golden outputs byte for
// byte; the event engine, which integrates only the blocks within R of a sliding block,
// against the straightforward whole-chain engine bit for bit; R = 3 and the power kernel
// changing the catalogue; the energy balance; a ring's invariance under a rotation of the
// block indices; and the refusals of the schemes written for nearest neighbours. Viscous
// coupling (model.viscosity, Myers & Langer 1993): eta = beta_K k_c against the Rayleigh
// form without a pulling spring; a stuck block breaking under its sliding neighbour's
// dashpot; the engine against the whole chain; the energy books with the dashpots' work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "../scene_sim.hpp"
#include "core/error.hpp"
#include "engine/contacts.hpp"
#include "engine/continuous.hpp"
#include "model/coupling.hpp"
#include "stats/stability.hpp"
#include "support/reference_events.hpp"

namespace bkq {
namespace {

using test::Settings;
using test::Sim;

ModelParams chain(int n, Coupling c, int range, Boundary b, double p_exp = 3) {
  ModelParams p;
  p.n = n;
  p.k_c = 100;
  p.coupling = c;
  p.range = range;
  p.coupling_exponent = p_exp;
  p.boundary = b;
  return p;
}

TEST(CouplingStencil, SpringsSumToKcAndRangeOneIsNearest) {
  for (Coupling c : {Coupling::Range, Coupling::Power}) {
    const CouplingStencil one = coupling_stencil(chain(20, c, 1, Boundary::Free));
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].offset, 1);
    EXPECT_EQ(one[0].k, 100.0);
    for (int R : {2, 3, 7}) {
      const CouplingStencil s = coupling_stencil(chain(20, c, R, Boundary::Free));
      ASSERT_EQ(static_cast<int>(s.size()), R);
      double sum = 0;
      for (const CouplingSpring& spring : s) sum += spring.k;
      EXPECT_NEAR(sum, 100.0, 1e-12);
      for (int r = 1; r <= R; ++r) {
        EXPECT_EQ(s[r - 1].offset, r);
        // Range: equal springs k_c/R; power: k_1 / k_r = r^p.
        if (c == Coupling::Range)
          EXPECT_NEAR(s[r - 1].k, 100.0 / R, 1e-12);
        else
          EXPECT_NEAR(s[0].k / s[r - 1].k, std::pow(r, 3.0), 1e-9);
      }
    }
  }
  EXPECT_TRUE(coupling_stencil(chain(20, Coupling::Nearest, 5, Boundary::Free)).size() == 1);
}

// K_ij = -d f_i / d w_j from the force kernel's own arithmetic (unit displacements).
std::vector<std::vector<double>> coupling_matrix(const ChainForces& f) {
  const int n = f.n();
  std::vector<std::vector<double>> K(n, std::vector<double>(n));
  std::vector<double> e(n, 0.0);
  for (int j = 0; j < n; ++j) {
    e[j] = 1.0;
    for (int i = 0; i < n; ++i) K[i][j] = -f.neighbour_force(e.data(), i);
    e[j] = 0.0;
  }
  return K;
}

TEST(CouplingMatrix, SymmetricRowsSumToZeroDiagonalIsTheStatedStiffness) {
  for (Boundary b : {Boundary::Free, Boundary::Periodic})
    for (Coupling c : {Coupling::Range, Coupling::Power})
      for (int R : {1, 3, 5}) {
        const ModelParams p = chain(12, c, R, b);
        const ChainForces f(p);
        const CouplingStencil s = coupling_stencil(p);
        const auto K = coupling_matrix(f);
        for (int i = 0; i < p.n; ++i) {
          double row = 0, stated = 0;
          for (int j = 0; j < p.n; ++j) {
            EXPECT_NEAR(K[i][j], K[j][i], 1e-12) << i << "," << j;
            row += K[i][j];
          }
          EXPECT_NEAR(row, 0.0, 1e-12) << "row " << i;
          // The stated diagonal: each spring that reaches a block on the chain.
          for (const CouplingSpring& spring : s)
            stated += spring.k * ((b == Boundary::Periodic || i - spring.offset >= 0) +
                                  (b == Boundary::Periodic || i + spring.offset < p.n));
          EXPECT_NEAR(K[i][i], stated, 1e-12) << "block " << i;
          // Interior blocks (and every block of a ring) feel 2 k_c for every R.
          if (b == Boundary::Periodic || (i >= R && i + R < p.n)) {
            EXPECT_NEAR(K[i][i], 2.0 * p.k_c, 1e-12);
          }
          // Nothing beyond R.
          for (int j = 0; j < p.n; ++j) {
            int d = std::abs(i - j);
            if (b == Boundary::Periodic) d = std::min(d, p.n - d);
            if (d > R) {
              EXPECT_EQ(K[i][j], 0.0) << i << "," << j;
            } else if (d >= 1) {
              EXPECT_LT(K[i][j], 0.0) << i << "," << j;
            }
          }
        }
        // A uniform translation: no coupling force, exactly.
        std::vector<double> w(p.n, 3.7);
        for (int i = 0; i < p.n; ++i) EXPECT_EQ(f.neighbour_force(w.data(), i), 0.0);
      }
}

// The stability analysis's two solvers on a ring with range coupling: the modal reduction
// (k_q from the stencil) and the dense state matrix (K assembled from the stencil) agree.
TEST(CouplingStability, ModalAndDenseAgreeOnARangeCoupledRing) {
  for (Coupling c : {Coupling::Range, Coupling::Power}) {
    ModelParams p = chain(20, c, 6, Boundary::Periodic);
    p.k_c = 25;
    auto sorted = [](std::vector<Eigenmode> m) {
      std::vector<std::pair<double, double>> v;
      for (const Eigenmode& e : m) v.emplace_back(e.lambda.imag(), e.lambda.real());
      std::sort(v.begin(), v.end());
      return v;
    };
    const auto modal = sorted(modal_eigenmodes(p, -0.05));
    const auto dense = sorted(dense_eigenmodes(p, -0.05));
    ASSERT_EQ(modal.size(), dense.size());
    for (std::size_t i = 0; i < modal.size(); ++i) {
      EXPECT_NEAR(modal[i].first, dense[i].first, 1e-9);
      EXPECT_NEAR(modal[i].second, dense[i].second, 1e-9);
    }
    // Not the nearest-neighbour spectrum: the fastest mode moved.
    ModelParams nearest = p;
    nearest.coupling = Coupling::Nearest;
    auto fastest = [](const std::vector<std::pair<double, double>>& v) {
      double w = 0;
      for (const auto& e : v) w = std::max(w, e.first);
      return w;
    };
    EXPECT_GT(std::abs(fastest(sorted(modal_eigenmodes(nearest, -0.05))) - fastest(modal)), 0.1);
  }
}

// Every block sliding without friction at rest, block 20 displaced: one velocity-Verlet
// step moves the blocks its springs reach (x1 = x0 + h v0 + h^2/2 a0, a0 nonzero there
// only), R on each side, and nobody farther.
TEST(CouplingReach, AReleasedBlockMovesItsRNeighboursOnEachSideInTheFirstStep) {
  for (int R : {1, 3, 6}) {
    ModelParams p = chain(41, Coupling::Range, R, Boundary::Free);
    p.law = law_id<law::None>;
    const ChainForces f(p);
    ChainState st;
    st.resize(p.n);
    std::fill(st.mobile.begin(), st.mobile.end(), 1.0);
    st.w[20] = 0.1;
    const ChainState before = st;
    auto verlet = make_stepper("verlet", p.n);
    const Range all{0, p.n};
    verlet->step(f, Substrate::frozen(0.0), st, 0.01, Ranges(&all, 1));
    for (int j = 0; j < p.n; ++j) {
      if (std::abs(j - 20) <= R)
        EXPECT_NE(st.w[j], before.w[j]) << "R = " << R << ", block " << j;
      else
        EXPECT_EQ(st.w[j], before.w[j]) << "R = " << R << ", block " << j;
    }
  }
}

// `bkquake run` with model.coupling = range (or power) at R = 1 writes the nearest-neighbour
// golden outputs (tests/golden/bk_rk4_free: the same scene) byte for byte, provenance aside.
std::string without_comments(const std::string& bytes) {
  std::istringstream in(bytes);
  std::string out;
  for (std::string line; std::getline(in, line);)
    if (line.empty() || line[0] != '#') out += line + '\n';
  return out;
}

TEST(CouplingGolden, RangeOneReproducesTheNearestNeighbourGoldenByteForByte) {
  const std::filesystem::path golden =
      std::filesystem::path(BKQUAKE_SOURCE_DIR) / "tests" / "golden" / "bk_rk4_free";
  for (const char* kind : {"range", "power"}) {
    test::TempDir tmp;
    const auto r = test::run_bkquake(
        {"run", "--set", "model.blocks=50", "--set", "run.events=1500", "--set",
         "run.transient_events=100", "--quiet", "--set", std::string("model.coupling=") + kind,
         "--set", "model.range=1", "--out", "out"},
        tmp.path().string());
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* file : {"catalog.csv", "histogram.csv"}) {
      const std::string want = without_comments(test::read_file((golden / file).string()));
      const std::string got =
          without_comments(test::read_file(tmp.file(std::string("out/") + file)));
      ASSERT_FALSE(want.empty());
      EXPECT_TRUE(want == got) << kind << ": " << file << " differs from the golden";
    }
  }
}

// The event engine steps the blocks within R of a sliding block (and only those); the
// reference engine steps the whole chain. The same events bit for bit.
struct Case {
  const char* name;
  Settings settings;
  int min_largest;
};

class CouplingAgainstReference : public ::testing::TestWithParam<Case> {};

TEST_P(CouplingAgainstReference, SameEventsBitForBitAsTheWholeChainIntegration) {
  const Case& c = GetParam();
  Sim sim(c.settings);
  sim.run(10 * sim.p.n);
  ASSERT_LE(sim.engine.worst_stuck_excess(), 0.0);
  auto stepper = make_stepper(std::string(sim.stepper->name()), sim.p.n);
  ReferenceEventEngine ref(sim.forces, *stepper, sim.checked_dt(test::make_scene(c.settings)),
                           sim.engine.state());
  const EngineCounters before = sim.engine.counters();
  int largest = 0;
  for (int i = 0; i < 1000; ++i) {
    const EventRecord a = sim.engine.next_event(), b = ref.next_event();
    ASSERT_EQ(a.trigger, b.trigger) << "event " << i + 1;
    ASSERT_EQ(a.load, b.load) << "event " << i + 1;
    ASSERT_EQ(a.blocks, b.blocks) << "event " << i + 1;
    ASSERT_EQ(a.duration, b.duration) << "event " << i + 1;
    ASSERT_EQ(a.max_speed, b.max_speed) << "event " << i + 1;
    ASSERT_NEAR(a.moment, b.moment, 1e-12 * b.moment) << "event " << i + 1;
    largest = std::max(largest, a.blocks);
  }
  EXPECT_EQ(sim.engine.state().w, ref.state().w);
  EXPECT_EQ(sim.engine.counters().sliding_block_steps - before.sliding_block_steps,
            ref.sliding_block_steps);
  EXPECT_LT(sim.engine.counters().block_steps - before.block_steps, ref.block_steps);
  EXPECT_GE(largest, c.min_largest);
}

const Case kCases[] = {
    {"viscous_nearest_rk4", {{"model.blocks", "60"}, {"model.viscosity", "2"}}, 15},
    // Ranges of 64 blocks and more (the reference's whole chain, the engine's largest events):
    // the stepper's fused pass, which reads only j +- 1, must not take them.
    {"range3_long_chain_rk4",
     {{"model.blocks", "100"},
      {"model.coupling", "range"},
      {"model.range", "3"},
      {"friction.alpha", "1"}},
     64},
    {"viscous_range3_periodic_rk4",
     {{"model.blocks", "60"},
      {"model.viscosity", "2"},
      {"model.coupling", "range"},
      {"model.range", "3"},
      {"model.boundary", "periodic"}},
     15},
    {"range3_free_rk4",
     {{"model.blocks", "60"}, {"model.coupling", "range"}, {"model.range", "3"}},
     15},
    {"power5_periodic_rk2",
     {{"model.blocks", "60"},
      {"model.coupling", "power"},
      {"model.range", "5"},
      {"model.boundary", "periodic"},
      {"integrator.scheme", "rk2"},
      {"integrator.dt", "0.005"}},
     15},
    {"range4_thesis_backslip_verlet",
     {{"model.blocks", "60"},
      {"model.coupling", "range"},
      {"model.range", "4"},
      {"friction.law", "thesis"},
      {"integrator.scheme", "verlet"},
      {"integrator.dt", "0.005"}},
     15},
};

INSTANTIATE_TEST_SUITE_P(Scenes, CouplingAgainstReference, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return std::string(info.param.name);
                         });

std::vector<EventRecord> events_of(const Settings& settings, int count) {
  Sim sim(settings);
  std::vector<EventRecord> out;
  for (int i = 0; i < count; ++i) out.push_back(sim.engine.next_event());
  return out;
}

TEST(CouplingCatalogue, RangeThreeAndThePowerKernelChangeTheEvents) {
  const Settings base = {{"model.blocks", "60"}};
  auto with = [&](Settings more) {
    Settings s = base;
    s.insert(s.end(), more.begin(), more.end());
    return s;
  };
  const auto nearest = events_of(base, 400);
  const auto range3 = events_of(with({{"model.coupling", "range"}, {"model.range", "3"}}), 400);
  const auto power = events_of(with({{"model.coupling", "power"}, {"model.range", "3"}}), 400);
  auto differs = [&](const std::vector<EventRecord>& a) {
    int n = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      n += a[i].blocks != nearest[i].blocks || a[i].moment != nearest[i].moment;
    return n;
  };
  EXPECT_GT(differs(range3), 100);
  EXPECT_GT(differs(power), 100);
  int apart = 0;
  for (std::size_t i = 0; i < power.size(); ++i) apart += power[i].moment != range3[i].moment;
  EXPECT_GT(apart, 100);
}

// The energy books with the stencil's springs: the residual stays below the limit a run
// warns at (run.accuracy, 0.05) as with nearest neighbours, and it is the integration's
// error, not the books': it halves with the step (first order across transitions).
TEST(CouplingEnergy, BalanceClosesAsWellAsWithNearestNeighbours) {
  auto worst = [](Settings s, const char* dt) {
    s.emplace_back("integrator.dt", dt);
    Sim sim(s);
    sim.run(300);
    double w = 0;
    for (int i = 0; i < 1500; ++i)
      w = std::max(w, std::abs(sim.engine.next_event().energy_residual));
    return w;
  };
  const double nearest = worst({{"model.blocks", "80"}}, "0.01");
  EXPECT_LT(nearest, 0.05);
  for (const char* kind : {"range", "power"})
    for (const char* boundary : {"free", "periodic"}) {
      const Settings s = {{"model.blocks", "80"},
                          {"model.coupling", kind},
                          {"model.range", "5"},
                          {"model.boundary", boundary}};
      const double coarse = worst(s, "0.01"), fine = worst(s, "0.005");
      std::printf("energy residual: nearest %.3g; %s %s R = 5: %.3g, at dt/2 %.3g\n", nearest, kind,
                  boundary, coarse, fine);
      EXPECT_LT(coarse, 0.05) << kind << " " << boundary;
      if (coarse > 2 * nearest) {
        EXPECT_LT(fine, 0.65 * coarse) << kind << " " << boundary;
      }
    }
}

// A ring has no first block: rotating the initial state by k blocks rotates every event.
TEST(CouplingRing, EventsAreInvariantUnderARotationOfTheBlockIndices) {
  const Settings s = {{"model.blocks", "40"},
                      {"model.boundary", "periodic"},
                      {"model.coupling", "range"},
                      {"model.range", "4"}};
  Sim a(s);
  a.run(400);
  const int k = 13, n = a.p.n;
  EngineSnapshot rotated = a.engine.snapshot();
  for (int j = 0; j < n; ++j) rotated.state.w[(j + k) % n] = a.engine.state().w[j];
  Sim b(s);
  EventEngine engine(b.forces, *b.stepper, b.checked_dt(test::make_scene(s)), rotated);
  int multi = 0;
  for (int i = 0; i < 1000; ++i) {
    const EventRecord x = a.engine.next_event(), y = engine.next_event();
    ASSERT_EQ((x.trigger + k) % n, y.trigger) << "event " << i + 1;
    ASSERT_EQ(x.load, y.load) << "event " << i + 1;
    ASSERT_EQ(x.blocks, y.blocks) << "event " << i + 1;
    ASSERT_EQ(x.duration, y.duration) << "event " << i + 1;
    ASSERT_NEAR(x.moment, y.moment, 1e-12 * x.moment) << "event " << i + 1;
    multi += x.blocks > 1;
  }
  for (int j = 0; j < n; ++j) EXPECT_EQ(engine.state().w[(j + k) % n], a.engine.state().w[j]);
  EXPECT_GT(multi, 50);
}

// eta (w'_{j-1} - 2 w'_j + w'_{j+1}) is the neighbour dashpot that beta_K K holds: with no
// pulling spring (k_p = 0, no pad) eta = beta_K k_c gives the Rayleigh form's forces and
// modal damping, for nearest neighbours and for a range-coupled stencil.
TEST(ViscousCoupling, EtaEqualToBetaKcMatchesTheRayleighFormWithoutPullingSpring) {
  for (Coupling c : {Coupling::Nearest, Coupling::Range})
    for (Boundary b : {Boundary::Free, Boundary::Periodic}) {
      ModelParams base = chain(15, c, 3, b);
      base.k_p = 0;
      base.law = law_id<law::None>;
      const double beta = 0.07;
      ModelParams viscous = base, rayleigh = base;
      viscous.viscosity = beta * base.k_c;
      rayleigh.rayleigh_beta = beta;
      const ChainForces fv(viscous), fr(rayleigh);
      std::vector<double> w(15), wd(15), mobile(15, 1.0), dir(15, 1.0), av(15), ar(15);
      for (int j = 0; j < 15; ++j) {
        w[j] = 0.01 * std::sin(1.3 * j);
        wd[j] = 0.2 * std::cos(0.7 * j * j);
      }
      const Range all{0, 15};
      const SubstrateState sub{0.0, 0.0, 0.0};
      fv.block_accelerations(w.data(), wd.data(), mobile.data(), dir.data(), 0.3, 0.0, sub,
                             Ranges(&all, 1), av.data());
      fr.block_accelerations(w.data(), wd.data(), mobile.data(), dir.data(), 0.3, 0.0, sub,
                             Ranges(&all, 1), ar.data());
      for (int j = 0; j < 15; ++j) EXPECT_NEAR(av[j], ar[j], 1e-12) << "block " << j;
      double moved = 0;
      for (int j = 0; j < 15; ++j) moved = std::max(moved, std::abs(fv.damper_force(wd.data(), j)));
      EXPECT_GT(moved, 0.1);  // the dashpots do act
      for (int q = 0; q < 15; ++q)
        EXPECT_NEAR(chain_mode_damping(viscous, q), chain_mode_damping(rayleigh, q), 1e-12);
    }
}

// Blocks 0 and 2 stuck at 0.9 of the threshold beside block 1 sliding at 0.05: their
// neighbour's dashpot (eta 0.05 = 0.25 at eta = 5) breaks them; without it they hold.
TEST(ViscousCoupling, AStuckBlockFeelsItsSlidingNeighboursDamper) {
  for (double eta : {0.0, 5.0}) {
    ModelParams p = chain(3, Coupling::Nearest, 1, Boundary::Free);
    p.k_c = 1;
    p.viscosity = eta;
    const ChainForces f(p);
    ChainState st;
    st.resize(3);
    st.mobile[1] = 1.0;
    st.wd[1] = 0.05;
    const std::vector<double> wd_old = st.wd;
    const Range all{0, 3};
    std::vector<int> released;
    const ContactScan scan = settle_contacts(f, st, wd_old.data(), 0.9, Ranges(&all, 1), true,
                                             [&](int j) { released.push_back(j); });
    if (eta == 0) {
      EXPECT_TRUE(released.empty());
      EXPECT_EQ(scan.sliding, 1);
    } else {
      EXPECT_EQ(released, (std::vector<int>{0, 2}));
      EXPECT_EQ(scan.sliding, 3);
    }
  }
}

// The dashpots' work enters the books: the residual stays below the limit a run warns at
// and halves with the step, as without them; and they change the events.
TEST(ViscousCoupling, EnergyBalanceClosesAndTheEventsChange) {
  auto run = [](Settings s, const char* dt, double& worst) {
    s.emplace_back("integrator.dt", dt);
    Sim sim(s);
    sim.run(300);
    worst = 0;
    std::vector<EventRecord> out;
    for (int i = 0; i < 1500; ++i) {
      out.push_back(sim.engine.next_event());
      worst = std::max(worst, std::abs(out.back().energy_residual));
    }
    return out;
  };
  double plain = 0;
  const auto without = run({{"model.blocks", "80"}}, "0.01", plain);
  for (const char* coupling : {"nearest", "range"}) {
    Settings s = {{"model.blocks", "80"}, {"model.viscosity", "3"}, {"model.coupling", coupling}};
    if (std::string(coupling) == "range") s.emplace_back("model.range", "3");
    double coarse = 0, fine = 0;
    const auto with = run(s, "0.01", coarse);
    run(s, "0.005", fine);
    std::printf("energy residual: no dashpots %.3g; eta = 3, %s: %.3g, at dt/2 %.3g\n", plain,
                coupling, coarse, fine);
    EXPECT_LT(coarse, 0.05) << coupling;
    if (coarse > 2 * plain) {
      EXPECT_LT(fine, 0.65 * coarse) << coupling;
    }
    int differ = 0;
    for (std::size_t i = 0; i < with.size(); ++i) differ += with[i].moment != without[i].moment;
    EXPECT_GT(differ, 100) << coupling;
  }
}

// A continuous run of a frictionless chain released from a random displacement: the
// dashpots (and the stencil's springs) take most of the energy, and the run's balance
// (work - dissipated) books their work.
TEST(ViscousCoupling, ContinuousEnergyBalanceBooksTheDashpotWork) {
  for (Coupling c : {Coupling::Nearest, Coupling::Power}) {
    ModelParams p = chain(20, c, 4, Boundary::Free);
    p.law = law_id<law::None>;
    p.viscosity = 3;
    const ChainForces forces(p);
    for (const char* scheme : {"rk2", "rk4", "verlet"}) {
      const auto stepper = make_stepper(scheme, p.n);
      const double dt = std::min(0.002, 0.2 * stability_limit(*stepper, p));
      ChainState st;
      st.resize(p.n);
      std::mt19937 rng(3);
      std::uniform_real_distribution<double> U(-1.0, 1.0);
      for (int j = 0; j < p.n; ++j) st.w[j] = 0.05 * U(rng);
      ContinuousDriver driver(forces, *stepper, Substrate::constant(0.0), st, dt);
      const double e0 = driver.energy();
      for (int i = 0; i < static_cast<int>(20.0 / dt); ++i) driver.step();
      const EnergyBalance& b = driver.energy_balance();
      EXPECT_GT(b.dissipated, 0.5 * e0) << scheme;
      EXPECT_LT(std::abs(b.residual(driver.energy())), 2e-3) << scheme;
    }
  }
}

TEST(CouplingRefusals, RangeTooLongAndSchemesWrittenForNearestNeighbours) {
  auto refused = [](const std::vector<std::string>& sets, const std::vector<std::string>& parts) {
    test::TempDir tmp;
    std::vector<std::string> args = {"run", "--quiet", "--set", "run.events=10"};
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    args.insert(args.end(), {"--out", "out"});
    const auto r = test::run_bkquake(args, tmp.path().string());
    test::expect_refused(r, parts);
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out" / "catalog.csv"));
  };
  refused({"model.blocks=10", "model.coupling=range", "model.range=10"},
          {"model.range = 10", "model.blocks = 10", "model.range < model.blocks"});
  refused({"model.blocks=10", "model.coupling=power", "model.range=5", "model.boundary=periodic"},
          {"model.range = 5", "2 model.range < model.blocks"});
  for (const char* scheme : {"theta", "adaptive"})
    refused(
        {"model.coupling=range", "model.range=3", std::string("integrator.scheme=") + scheme},
        {std::string("integrator.scheme = ") + scheme, "model.range = 3", "rk2, rk4 or verlet"});
  refused({"model.viscosity=1", "integrator.scheme=theta"},
          {"integrator.scheme = theta", "model.viscosity = 1"});
  refused({"model.coupling=range", "model.range=3", "integrator.transitions=located"},
          {"integrator.transitions = located", "model.coupling = range"});
  // model.range where the coupling is nearest does not apply.
  refused({"model.range=3"}, {"model.range", "model.coupling"});
}

}  // namespace
}  // namespace bkq
