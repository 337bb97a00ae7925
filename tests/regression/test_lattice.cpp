// The BK lattice (model.rows > 1; Carlson 1991): its stencil in the plane, its forces, and
// its events under the symmetries of the lattice. A column is the chain (line_as_chain) byte
// for byte; a transposed lattice gives the transposed events; a periodic lattice shifted
// gives the shifted events; the engine steps the events' sites and their rim, not the plane.
// The event engine against the whole-lattice integration is in test_reference_events.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "../scene_sim.hpp"
#include "core/error.hpp"
#include "model/coupling.hpp"

namespace bkq {
namespace {

using test::Settings;
using test::Sim;

ModelParams lattice_params(int nx, int ny, Coupling c, int range) {
  ModelParams p;
  p.n = nx * ny;
  p.rows = ny;
  p.k_c = 100;
  p.k_c_y = 49;
  p.coupling = c;
  p.range = range;
  return p;
}

TEST(LatticeStencil, ProjectionsSumToTheSpringsAlongAndAcrossAndRangeOneIsNearest) {
  const LatticeStencil nearest = lattice_stencil(lattice_params(10, 10, Coupling::Nearest, 1));
  ASSERT_EQ(nearest.size(), 2u);
  EXPECT_EQ(nearest[0].dx, 1);
  EXPECT_EQ(nearest[0].dy, 0);
  EXPECT_EQ(nearest[0].k, 100);
  EXPECT_EQ(nearest[1].dx, 0);
  EXPECT_EQ(nearest[1].dy, 1);
  EXPECT_EQ(nearest[1].k, 49);
  for (Coupling c : {Coupling::Range, Coupling::Power}) {
    const LatticeStencil one = lattice_stencil(lattice_params(10, 10, c, 1));
    ASSERT_EQ(one.size(), 2u);
    EXPECT_EQ(one[0].k, 100);
    EXPECT_EQ(one[1].k, 49);
    const LatticeStencil s = lattice_stencil(lattice_params(10, 10, c, 4));
    double total = 0;
    int count = 0;
    for (const LatticeSpring& e : s) {
      const double r2 = e.dx * e.dx + e.dy * e.dy;
      ASSERT_GT(r2, 0);
      ASSERT_LE(r2, 16);
      ASSERT_TRUE(e.dx > 0 || (e.dx == 0 && e.dy > 0)) << e.dx << ", " << e.dy;
      total += e.k;
      ++count;
    }
    // Half of the 48 sites of the disc of radius 4 (lattice points 0 < r <= 4).
    EXPECT_EQ(count, 24);
    // An interior site feels 2 (k_c + k_c_y), as with nearest neighbours.
    EXPECT_NEAR(total, 149, 1e-12);
    // Isotropic springs (k_c = k_c_y): the projections along and across are k_c each.
    ModelParams iso = lattice_params(10, 10, c, 4);
    iso.k_c_y = iso.k_c;
    double along = 0, across = 0;
    for (const LatticeSpring& e : lattice_stencil(iso)) {
      const double r2 = e.dx * e.dx + e.dy * e.dy;
      along += e.k * e.dx * e.dx / r2;
      across += e.k * e.dy * e.dy / r2;
    }
    EXPECT_NEAR(along, 100, 1e-12);
    EXPECT_NEAR(across, 100, 1e-12);
  }
}

// Every site's force against its neighbours listed by hand, on free and periodic edges.
TEST(LatticeForces, NeighbourSumsAreTheLatticeLaplacianWithTheEdges) {
  const int nx = 5, ny = 4;
  for (Boundary bx : {Boundary::Free, Boundary::Periodic})
    for (Boundary by : {Boundary::Free, Boundary::Periodic}) {
      ModelParams p = lattice_params(nx, ny, Coupling::Nearest, 1);
      p.boundary = bx;
      p.boundary_y = by;
      const ChainForces f(p);
      ASSERT_TRUE(f.lattice());
      std::vector<double> w(nx * ny);
      for (int j = 0; j < nx * ny; ++j) w[j] = std::sin(1.7 * j) + 0.1 * j;
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
          const int j = y * nx + x;
          double want = 0;
          auto add = [&](int xx, int yy, double k) {
            if (xx < 0 || xx >= nx) {
              if (bx == Boundary::Free) return;
              xx = (xx + nx) % nx;
            }
            if (yy < 0 || yy >= ny) {
              if (by == Boundary::Free) return;
              yy = (yy + ny) % ny;
            }
            want += k * (w[yy * nx + xx] - w[j]);
          };
          add(x - 1, y, 100);
          add(x + 1, y, 100);
          add(x, y - 1, 49);
          add(x, y + 1, 49);
          EXPECT_NEAR(f.neighbour_force(w.data(), j), want, 1e-12) << x << ", " << y;
        }
      // Free edges: the neighbour springs' forces cancel in the sum over the lattice.
      if (bx == Boundary::Free && by == Boundary::Free) {
        double total = 0;
        for (int j = 0; j < nx * ny; ++j) total += f.neighbour_force(w.data(), j);
        EXPECT_NEAR(total, 0, 1e-11);
      }
    }
  // The checkerboard is the fastest mode: the stability limit uses 4 (k_c + k_c_y).
  ModelParams p = lattice_params(nx, ny, Coupling::Nearest, 1);
  EXPECT_DOUBLE_EQ(p.max_angular_frequency(), std::sqrt(4.0 * (100 + 49) + 1));
}

// Sites whose partners all lie inside the lattice sum them at fixed offsets, without edge
// tests (ChainForces::lattice_sum, for_each_partner): the force and the partners are those of
// the stencil applied site by site with the edges tested, bit for bit, on every site of
// lattices with sites far from every edge, near them and on them.
TEST(LatticeForces, InteriorSitesSumTheirStencilAsTheEdgeTestedSumDoes) {
  const int nx = 11, ny = 9;
  for (Coupling c : {Coupling::Nearest, Coupling::Range, Coupling::Power})
    for (Boundary bx : {Boundary::Free, Boundary::Periodic})
      for (Boundary by : {Boundary::Free, Boundary::Periodic}) {
        ModelParams p = lattice_params(nx, ny, c, c == Coupling::Nearest ? 1 : 3);
        p.boundary = bx;
        p.boundary_y = by;
        const ChainForces f(p);
        std::vector<double> w(nx * ny);
        for (int j = 0; j < nx * ny; ++j) w[j] = std::sin(1.3 * j) + 0.01 * j;
        auto site = [&](int x, int y) {
          if (x < 0 || x >= nx) {
            if (bx == Boundary::Free) return -1;
            x = (x + nx) % nx;
          }
          if (y < 0 || y >= ny) {
            if (by == Boundary::Free) return -1;
            y = (y + ny) % ny;
          }
          return y * nx + x;
        };
        for (int y = 0; y < ny; ++y)
          for (int x = 0; x < nx; ++x) {
            const int j = y * nx + x;
            double want = 0;
            std::vector<int> partners;
            for (const LatticeSpring& sp : f.lattice_stencil()) {
              double d = 0;
              for (int i : {site(x - sp.dx, y - sp.dy), site(x + sp.dx, y + sp.dy)})
                if (i >= 0) {
                  d += w[i] - w[j];
                  partners.push_back(i);
                }
              want += sp.k * d;
            }
            EXPECT_EQ(f.neighbour_force(w.data(), j), want) << x << ", " << y;
            std::vector<int> seen;
            f.for_each_partner(j, [&](int i) { seen.push_back(i); });
            EXPECT_EQ(seen, partners) << x << ", " << y;
          }
      }
}

// The state of an nx x ny lattice as the ny x nx lattice with the axes swapped.
ChainState transposed(const ChainState& a, int nx, int ny) {
  ChainState b = a;
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) b.w[x * ny + y] = a.w[y * nx + x];
  return b;
}

TEST(LatticeSymmetry, TransposingTheLatticeTransposesTheEvents) {
  const int nx = 11, ny = 7;
  const Settings sa = {{"model.blocks", std::to_string(nx)},
                       {"model.rows", std::to_string(ny)},
                       {"model.l", "10"},
                       {"model.l_y", "7"}};
  const Settings sb = {{"model.blocks", std::to_string(ny)},
                       {"model.rows", std::to_string(nx)},
                       {"model.l", "7"},
                       {"model.l_y", "10"}};
  Sim a(sa);
  a.run(400);
  EngineSnapshot t = a.engine.snapshot();
  t.state = transposed(a.engine.state(), nx, ny);
  Sim b(sb);
  EventEngine engine(b.forces, *b.stepper, b.checked_dt(test::make_scene(sb)), t);
  int spread = 0;
  for (int i = 0; i < 1500; ++i) {
    const EventRecord x = a.engine.next_event(), y = engine.next_event();
    ASSERT_EQ(x.trigger, y.trigger_row) << "event " << i + 1;
    ASSERT_EQ(x.trigger_row, y.trigger) << "event " << i + 1;
    ASSERT_EQ(x.first_block, y.first_row) << "event " << i + 1;
    ASSERT_EQ(x.last_block, y.last_row) << "event " << i + 1;
    ASSERT_EQ(x.first_row, y.first_block) << "event " << i + 1;
    ASSERT_EQ(x.last_row, y.last_block) << "event " << i + 1;
    ASSERT_EQ(x.load, y.load) << "event " << i + 1;
    ASSERT_EQ(x.blocks, y.blocks) << "event " << i + 1;
    ASSERT_EQ(x.duration, y.duration) << "event " << i + 1;
    ASSERT_NEAR(x.moment, y.moment, 1e-12 * x.moment) << "event " << i + 1;
    spread += x.first_row != x.last_row && x.first_block != x.last_block;
  }
  EXPECT_EQ(engine.state().w, transposed(a.engine.state(), nx, ny).w);
  // Events that spread in both directions occurred.
  EXPECT_GT(spread, 20);
}

TEST(LatticeSymmetry, ShiftingAPeriodicLatticeShiftsTheEvents) {
  const int nx = 10, ny = 8, sx = 3, sy = 5;
  const Settings s = {{"model.blocks", std::to_string(nx)},
                      {"model.rows", std::to_string(ny)},
                      {"model.boundary", "periodic"},
                      {"model.boundary_y", "periodic"},
                      {"model.l_y", "6"}};
  Sim a(s);
  a.run(400);
  auto shifted = [&](const ChainState& st) {
    ChainState out = st;
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) out.w[((y + sy) % ny) * nx + (x + sx) % nx] = st.w[y * nx + x];
    return out;
  };
  EngineSnapshot t = a.engine.snapshot();
  t.state = shifted(a.engine.state());
  Sim b(s);
  EventEngine engine(b.forces, *b.stepper, b.checked_dt(test::make_scene(s)), t);
  int multi = 0;
  for (int i = 0; i < 1500; ++i) {
    const EventRecord x = a.engine.next_event(), y = engine.next_event();
    ASSERT_EQ((x.trigger + sx) % nx, y.trigger) << "event " << i + 1;
    ASSERT_EQ((x.trigger_row + sy) % ny, y.trigger_row) << "event " << i + 1;
    ASSERT_EQ(x.load, y.load) << "event " << i + 1;
    ASSERT_EQ(x.blocks, y.blocks) << "event " << i + 1;
    ASSERT_EQ(x.duration, y.duration) << "event " << i + 1;
    ASSERT_NEAR(x.moment, y.moment, 1e-12 * x.moment) << "event " << i + 1;
    multi += x.blocks > 1;
  }
  EXPECT_EQ(engine.state().w, shifted(a.engine.state()).w);
  EXPECT_GT(multi, 100);
}

// The relaxation steps the sliding sites and their rim: on a 32 x 32 lattice the blocks
// advanced per step are a small share of the plane, and the energy balance closes.
TEST(LatticeEngine, StepsTheEventNotThePlaneAndTheEnergyBalanceCloses) {
  Sim sim(Settings{{"model.blocks", "32"}, {"model.rows", "32"}, {"integrator.dt", "0.005"}});
  sim.run(20000);
  const EngineCounters before = sim.engine.counters();
  double worst = 0;
  int largest = 0;
  for (int i = 0; i < 3000; ++i) {
    const EventRecord e = sim.engine.next_event();
    worst = std::max(worst, std::abs(e.energy_residual));
    largest = std::max(largest, e.blocks);
  }
  const EngineCounters& after = sim.engine.counters();
  const double per_step =
      double(after.block_steps - before.block_steps) / double(after.steps - before.steps);
  std::printf("32 x 32: %.1f blocks per step, largest event %d blocks, worst residual %.3g\n",
              per_step, largest, worst);
  EXPECT_LT(per_step, 0.05 * 32 * 32);
  EXPECT_GT(largest, 10);
  EXPECT_LT(worst, 0.05);
}

// One pad under every block of the lattice (model.kind = bkp): it moves in every event and
// the energy balance, which books its motion, closes.
TEST(LatticeEngine, APadUnderTheLatticeMovesAndTheEnergyBalanceCloses) {
  Sim sim(Settings{{"model.kind", "bkp"},
                   {"model.blocks", "12"},
                   {"model.rows", "12"},
                   {"integrator.dt", "0.005"}});
  sim.run(3000);
  double worst = 0;
  int moved = 0, largest = 0;
  for (int i = 0; i < 3000; ++i) {
    const EventRecord e = sim.engine.next_event();
    worst = std::max(worst, std::abs(e.energy_residual));
    moved += e.pad_displacement != 0;
    largest = std::max(largest, e.blocks);
  }
  EXPECT_EQ(moved, 3000);
  EXPECT_GT(largest, 20);
  EXPECT_LT(worst, 0.05);
}

std::vector<std::vector<std::string>> catalog_rows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::istringstream cs(line);
    for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

int column_of(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  ADD_FAILURE() << "no column " << name;
  return 0;
}

// A lattice of one column (model.blocks = 1, model.rows = N, its springs across strike those
// of the chain) is the chain of N blocks: the same catalogue, the chain's blocks read as rows.
TEST(LatticeColumn, IsTheChainByteForByte) {
  for (const char* boundary : {"free", "periodic"}) {
    test::TempDir tmp;
    const std::vector<std::string> common = {"--quiet", "--set", "run.events=1500", "--set",
                                             "run.transient_events=200"};
    auto run = [&](const std::vector<std::string>& sets, const char* out) {
      std::vector<std::string> args = {"run"};
      args.insert(args.end(), common.begin(), common.end());
      for (const auto& s : sets) args.insert(args.end(), {"--set", s});
      args.insert(args.end(), {"--out", out});
      const auto r = test::run_bkquake(args, tmp.path().string());
      EXPECT_EQ(r.status, 0) << r.err;
    };
    run({"model.blocks=40", "model.l=10", std::string("model.boundary=") + boundary}, "chain");
    // The spring along strike has nothing to couple in one column: l = 3 changes nothing.
    run({"model.blocks=1", "model.rows=40", "model.l=3", "model.l_y=10",
         std::string("model.boundary_y=") + boundary},
        "column");
    const auto chain = catalog_rows(tmp.file("chain/catalog.csv"));
    const auto column = catalog_rows(tmp.file("column/catalog.csv"));
    ASSERT_EQ(chain.size(), 1501u);
    ASSERT_EQ(column.size(), chain.size());
    const auto& hc = chain[0];
    const auto& hl = column[0];
    ASSERT_EQ(hl.size(), hc.size() + 3);
    std::size_t multi = 0;
    for (std::size_t i = 1; i < chain.size(); ++i) {
      for (std::size_t c = 0; c < hc.size(); ++c) {
        const std::string& name = hc[c];
        const std::string& got = column[i][column_of(hl, name)];
        if (name == "trigger" || name == "first_block" || name == "last_block") {
          const std::string row = name == "trigger"       ? "trigger_row"
                                  : name == "first_block" ? "first_row"
                                                          : "last_row";
          ASSERT_EQ(column[i][column_of(hl, row)], chain[i][c]) << boundary << " event " << i;
          ASSERT_EQ(got, "0");
        } else {
          ASSERT_EQ(got, chain[i][c]) << boundary << " event " << i << " column " << name;
        }
      }
      multi += chain[i][column_of(hc, "blocks")] != "1";
    }
    EXPECT_GT(multi, 100u);
    EXPECT_EQ(catalog_rows(tmp.file("chain/histogram.csv")),
              catalog_rows(tmp.file("column/histogram.csv")));
  }
}

TEST(LatticeRun, EventAndContinuousRunsWriteTheRowColumns) {
  test::TempDir tmp;
  auto r = test::run_bkquake({"run", "--quiet", "--set", "model.blocks=12", "--set",
                              "model.rows=10", "--set", "run.events=400", "--out", "ev"},
                             tmp.path().string());
  ASSERT_EQ(r.status, 0) << r.err;
  auto rows = catalog_rows(tmp.file("ev/catalog.csv"));
  ASSERT_EQ(rows.size(), 401u);
  const int tr = column_of(rows[0], "trigger_row"), fr = column_of(rows[0], "first_row"),
            lr = column_of(rows[0], "last_row"), t = column_of(rows[0], "trigger");
  int off_first_row = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const int y = std::stoi(rows[i][tr]);
    EXPECT_LE(std::stoi(rows[i][fr]), y);
    EXPECT_GE(std::stoi(rows[i][lr]), y);
    EXPECT_LT(std::stoi(rows[i][lr]), 10);
    EXPECT_LT(std::stoi(rows[i][t]), 12);
    off_first_row += y > 0;
  }
  EXPECT_GT(off_first_row, 200);
  r = test::run_bkquake({"run", "--quiet", "--set", "model.blocks=8", "--set", "model.rows=6",
                         "--set", "drive.mode=continuous", "--set", "drive.speed=0.01", "--set",
                         "run.duration=300", "--out", "co"},
                        tmp.path().string());
  ASSERT_EQ(r.status, 0) << r.err;
  rows = catalog_rows(tmp.file("co/catalog.csv"));
  ASSERT_GT(rows.size(), 5u);
  EXPECT_GE(column_of(rows[0], "last_row"), 0);
}

// Slip maps of a lattice (output.event_slip): each event's sites as (block, row) inside the
// lattice and its bounding box, their slips adding up to the catalogue's moment.
TEST(LatticeRun, SlipMapsAddUpToTheMomentInsideTheBoundingBox) {
  test::TempDir tmp;
  const auto r = test::run_bkquake(
      {"run", "--quiet", "--set", "model.blocks=10", "--set", "model.rows=8", "--set",
       "run.events=1000", "--set", "output.event_slip=-6", "--out", "ev"},
      tmp.path().string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto cat = catalog_rows(tmp.file("ev/catalog.csv"));
  const auto slip = catalog_rows(tmp.file("ev/event_slip.csv"));
  ASSERT_GT(slip.size(), 1u);
  const auto& h = slip[0];
  ASSERT_EQ(h, (std::vector<std::string>{"event", "block", "row", "slip"}));
  std::vector<double> sum(cat.size(), 0.0);
  std::vector<int> sites(cat.size(), 0);
  const auto& hc = cat[0];
  for (std::size_t i = 1; i < slip.size(); ++i) {
    const auto e = static_cast<std::size_t>(std::stoll(slip[i][0]));
    ASSERT_LT(e, cat.size());
    const int x = std::stoi(slip[i][1]), y = std::stoi(slip[i][2]);
    EXPECT_GE(x, std::stoi(cat[e][column_of(hc, "first_block")]));
    EXPECT_LE(x, std::stoi(cat[e][column_of(hc, "last_block")]));
    EXPECT_GE(y, std::stoi(cat[e][column_of(hc, "first_row")]));
    EXPECT_LE(y, std::stoi(cat[e][column_of(hc, "last_row")]));
    sum[e] += std::stod(slip[i][3]);
    ++sites[e];
  }
  int mapped = 0;
  for (std::size_t e = 1; e < cat.size(); ++e) {
    if (sites[e] == 0) continue;
    ++mapped;
    EXPECT_EQ(sites[e], std::stoi(cat[e][column_of(hc, "blocks")])) << "event " << e;
    const double m = std::stod(cat[e][column_of(hc, "moment")]);
    EXPECT_NEAR(sum[e], m, 1e-9 * m) << "event " << e;
  }
  EXPECT_GT(mapped, 20);
}

// A lattice run killed (SIGKILL) after a checkpoint and resumed writes the files of a run
// that never stopped, byte for byte: catalogue with the row columns, slip maps, histogram.
TEST(LatticeRun, ResumeAfterSigkillWritesTheStraightRunsFiles) {
  test::TempDir tmp;
  const std::vector<std::string> scene = {"--quiet",
                                          "--set",
                                          "model.blocks=16",
                                          "--set",
                                          "model.rows=12",
                                          "--set",
                                          "run.events=20000",
                                          "--set",
                                          "run.checkpoint_events=500",
                                          "--set",
                                          "output.event_slip=-5"};
  auto args = [&](const std::string& out) {
    std::vector<std::string> a = {"run"};
    a.insert(a.end(), scene.begin(), scene.end());
    a.insert(a.end(), {"--out", out});
    return a;
  };
  const std::string straight = tmp.file("straight"), out = tmp.file("out");
  ASSERT_EQ(test::run_bkquake(args(straight)).status, 0);
  const int status = test::run_and_signal_when(
      args(out), [&] { return std::filesystem::exists(out + "/checkpoint.prev.bin"); }, SIGKILL);
  ASSERT_EQ(status, 128 + SIGKILL);
  ASSERT_FALSE(std::filesystem::exists(out + "/summary.json") &&
               test::read_file(out + "/summary.json").find("finished") != std::string::npos);
  const auto r =
      test::run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* file : {"catalog.csv", "event_slip.csv", "histogram.csv"})
    EXPECT_TRUE(test::read_file(out + "/" + file) == test::read_file(straight + "/" + file))
        << file;
  EXPECT_NE(test::read_file(out + "/catalog.csv").find(",trigger_row,first_row,last_row"),
            std::string::npos);
}

// The run's accuracy advice names only what the lattice allows: at a coarse dt it says to
// reduce dt, not to use the adaptive scheme (which a lattice refuses).
TEST(LatticeRun, AccuracyAdviceNamesOnlyWhatTheLatticeAllows) {
  test::TempDir tmp;
  const auto r =
      test::run_bkquake({"run", "--quiet", "--set", "model.blocks=16", "--set", "model.rows=16",
                         "--set", "run.events=3000", "--set", "integrator.dt=0.05", "--out", "out"},
                        tmp.path().string());
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_NE(r.err.find("energy_residual_max"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reduce integrator.dt"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("adaptive"), std::string::npos) << r.err;
}

// The engine itself refuses a stepper that places transitions inside its step on a lattice
// (whatever the caller: the scene refuses it first for runs).
TEST(LatticeRefusals, TheEngineRefusesSteppersThatLocateTransitions) {
  Sim sim(Settings{{"model.blocks", "6"}, {"model.rows", "5"}});
  for (const char* name : {"adaptive", "theta"}) {
    auto stepper = make_stepper(name, sim.p.n);
    EXPECT_THROW(EventEngine(sim.forces, *stepper, 0.01, sim.engine.state()), Error) << name;
  }
  auto located = with_located_transitions(make_stepper("rk4", sim.p.n), sim.p.n);
  EXPECT_THROW(EventEngine(sim.forces, *located, 0.01, sim.engine.state()), Error);
}

TEST(LatticeRefusals, WhatTheLatticeIsNotWrittenFor) {
  auto refused = [](const std::vector<std::string>& sets, const std::vector<std::string>& parts) {
    test::TempDir tmp;
    std::vector<std::string> args = {"run", "--quiet", "--set", "run.events=10"};
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    args.insert(args.end(), {"--out", "out"});
    const auto r = test::run_bkquake(args, tmp.path().string());
    test::expect_refused(r, parts);
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out" / "catalog.csv"));
  };
  const std::string lattice = "model.rows=5";
  refused({lattice, "integrator.scheme=theta"},
          {"integrator.scheme = theta", "model.rows = 5", "rk2, rk4 or verlet"});
  refused({lattice, "integrator.transitions=located"},
          {"integrator.transitions = located", "model.rows = 5"});
  refused({lattice, "model.viscosity=1"}, {"model.viscosity = 1", "model.rows = 5"});
  refused({"model.kind=1dof", "model.rows=3"}, {"model.rows = 3", "1dof"});
  refused({"model.l_y=4"}, {"model.l_y", "model.rows > 1"});
  refused({"model.boundary_y=periodic"}, {"model.boundary_y", "model.rows"});
  refused({"model.rows=2", "model.boundary_y=periodic"},
          {"model.boundary_y = periodic", "model.rows >= 3"});
  refused({"model.blocks=20", "model.rows=6", "model.coupling=range", "model.range=6"},
          {"model.range = 6", "model.rows = 6", "model.range < model.rows"});
  // Springs across strike are stiffnesses: negative ones are refused by the key's range.
  refused({"model.rows=4", "model.l_y=-2"}, {"model.l_y", "-2"});
  refused({"model.rows=4", "model.parameterisation=thesis", "model.s_c_y=-0.5"},
          {"model.s_c_y", "-0.5"});
  // The linear analysis and the accuracy study are written for chains.
  auto command_refused = [](const std::vector<std::string>& args,
                            const std::vector<std::string>& parts) {
    test::TempDir tmp;
    auto a = args;
    a.insert(a.end(), {"--out", "out"});
    test::expect_refused(test::run_bkquake(a, tmp.path().string()), parts);
  };
  command_refused({"stability", "--set", "model.blocks=4", "--set", "model.rows=3", "--set",
                   "drive.speed=0.01"},
                  {"model.rows = 3", "chains"});
  command_refused({"accuracy", "--set", "model.blocks=6", "--set", "model.rows=6"},
                  {"accuracy", "model.rows = 6", "chains"});
}

}  // namespace
}  // namespace bkq
