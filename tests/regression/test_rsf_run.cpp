// Rate-and-state runs from the command line: the refusals (a <= 0, D_c <= 0, V_th not
// above V_pl, event-driven runs the closed forms cannot serve), the shipped QDYN scene through
// the catalogue, histogram and summary, the event-driven chain killed and resumed, and
// `bkquake stability` reporting k_crit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "io/scene.hpp"
#include "io/settings.hpp"

namespace bkq {
namespace {

using test::expect_refused;
using test::read_file;
using test::run_bkquake;

const std::string kScene = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/rsf/qdyn-stickslip.ini";

// Runs `args(tmp/cut, {})` until its first checkpoint is written, stops it with SIGTERM,
// resumes it and expects `files` equal byte for byte to those of the run never stopped
// (tmp/whole, already run) and the checkpoint gone.
template <class Args>
void expect_resumed_equals_whole(const test::TempDir& tmp, const Args& args,
                                 std::initializer_list<const char*> files) {
  const std::string checkpoint = tmp.file("cut/checkpoint.bin");
  const auto cut = test::run_bkquake_until([&] { return std::filesystem::exists(checkpoint); },
                                           args(tmp.file("cut"), {}));
  ASSERT_EQ(cut.status, 143) << cut.err;
  const auto resumed = run_bkquake(args(tmp.file("cut"), {"--resume"}));
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  for (const char* f : files)
    EXPECT_EQ(read_file(tmp.file(std::string("cut/") + f)),
              read_file(tmp.file(std::string("whole/") + f)))
        << f;
  EXPECT_FALSE(std::filesystem::exists(checkpoint));
}

// The built-in default turned into a rate-and-state scene by --set, then `more`.
std::vector<std::string> rsf_args(const std::string& out, std::vector<std::string> more) {
  std::vector<std::string> a = {"run",
                                "--set",
                                "model.parameterisation=si",
                                "--set",
                                "friction.law=rsf",
                                "--set",
                                "model.kind=1dof",
                                "--quiet",
                                "--out",
                                out};
  for (const auto& m : more) a.insert(a.end(), {"--set", m});
  return a;
}

TEST(RsfRun, Refusals) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const std::vector<std::string> cont = {"drive.mode=continuous", "drive.speed=1e-6",
                                         "run.duration=10"};
  auto with = [&](std::vector<std::string> v, const std::string& extra) {
    v.push_back(extra);
    return v;
  };
  expect_refused(run_bkquake(rsf_args(out, with(cont, "rsf.a=0"))), {"rsf.a", "0", "(0, 10]"});
  expect_refused(run_bkquake(rsf_args(out, with(cont, "rsf.a=-0.01"))), {"rsf.a", "(0, 10]"});
  expect_refused(run_bkquake(rsf_args(out, with(cont, "rsf.dc=0"))), {"rsf.dc", "(0, 1e+06]"});
  expect_refused(run_bkquake(rsf_args(out, with(cont, "rsf.v_threshold=1e-6"))),
                 {"rsf.v_threshold = 1e-06", "drive.speed", "allowed"});
  // Event-driven: the closed form between events is the aging law's, the hand-over speed lies
  // between V_pl and V_th, and radiation damping must stay small below it.
  const std::vector<std::string> ev = {"drive.mode=events", "drive.speed=1e-6", "run.events=5"};
  expect_refused(run_bkquake(rsf_args(out, with(ev, "rsf.state_law=slip"))),
                 {"rsf.state_law = slip", "drive.mode = events", "allowed: rsf.state_law = aging"});
  // Lattices hand over at up to 3 V_pl: there the event-driven catalogue is the continuous
  // one, at the auto V_h it is not. Uniform chains run.
  const std::vector<std::string> lattice =
      with(with(with(with(ev, "model.kind=bk"), "model.rows=2"), "model.blocks=4"),
           "rsf.pattern=asperities");
  expect_refused(run_bkquake(rsf_args(out, lattice)),
                 {"rsf.handover_speed = auto", "model.rows = 2", "drive.mode = events",
                  "allowed: rsf.handover_speed up to 3 drive.speed"});
  expect_refused(run_bkquake(rsf_args(out, with(lattice, "rsf.handover_speed=4e-6"))),
                 {"rsf.handover_speed = 4e-06", "allowed: rsf.handover_speed up to 3 drive.speed"});
  // A lattice with per-block values runs at the auto V_h (the 4 x 2 lattice's asperity pattern
  // from a file).
  const std::string blocks =
      tmp.write("lattice.csv",
                "block,a,b,dc\n0,0.01,0.025,1e-5\n1,0.01,0.025,1.02e-5\n2,0.025,0.01,0.98e-5\n"
                "3,0.025,0.01,1e-5\n4,0.01,0.025,1.01e-5\n5,0.01,0.025,0.99e-5\n6,0.025,0.01,1e-5\n"
                "7,0.025,0.01,1.03e-5\n");
  {
    const auto r = run_bkquake(
        rsf_args(tmp.file("ok"),
                 with(with(with(with(ev, "model.kind=bk"), "model.rows=2"), "model.blocks=4"),
                      "rsf.blocks=" + blocks)));
    EXPECT_EQ(r.status, 0) << r.err;
    std::filesystem::remove_all(tmp.path() / "ok");
  }
  // So does an event integrated on its active blocks, on chains too.
  // (per-block values: on identical blocks it is refused, below)
  const std::vector<std::string> active = with(
      with(with(with(ev, "model.kind=bk"), "model.blocks=100"), "rsf.event_integration=active"),
      "rsf.blocks=" + std::string(BKQUAKE_SOURCE_DIR) +
          "/data/scenes/rsf/chain-events-rough-blocks.csv");
  expect_refused(
      run_bkquake(rsf_args(out, active)),
      {"rsf.handover_speed = auto", "rsf.event_integration = active",
       "allowed: rsf.handover_speed up to 3 drive.speed, or rsf.event_integration = whole"});
  for (const auto& runs :
       {with(lattice, "rsf.handover_speed=3e-6"), with(with(ev, "model.kind=bk"), "model.blocks=4"),
        with(active, "rsf.handover_speed=3e-6")}) {
    const auto r = run_bkquake(rsf_args(tmp.file("ok"), runs));
    EXPECT_EQ(r.status, 0) << r.err;
    std::filesystem::remove_all(tmp.path() / "ok");
  }
  // Blocks integrated alone: with the active-block integration only, between V_pl and V_th.
  expect_refused(run_bkquake(rsf_args(out, with(ev, "rsf.alone_speed=1e-4"))),
                 {"rsf.alone_speed = 1e-04", "rsf.event_integration = whole",
                  "allowed: rsf.event_integration = active"});
  for (const auto& [bad, shown] :
       {std::pair<std::string, std::string>{"1e-6", "1e-06"}, {"2e-3", "0.002"}})
    expect_refused(run_bkquake(rsf_args(out, with(with(active, "rsf.handover_speed=3e-6"),
                                                  "rsf.alone_speed=" + bad))),
                   {"rsf.alone_speed = " + shown, "allowed: 0 (off), auto or (1e-06, 0.001)"});
  expect_refused(run_bkquake(rsf_args(out, with(ev, "rsf.alone_speed=-1"))),
                 {"rsf.alone_speed", "-1"});
  // Their tolerance: with the active-block integration only, within integrator.tolerance's range.
  expect_refused(run_bkquake(rsf_args(out, with(ev, "rsf.alone_tolerance=1e-5"))),
                 {"rsf.alone_tolerance = 1e-05", "rsf.event_integration = whole",
                  "allowed: rsf.event_integration = active or groups"});
  expect_refused(run_bkquake(rsf_args(out, with(ev, "rsf.alone_tolerance=0.5"))),
                 {"rsf.alone_tolerance", "0.5"});
  {
    // 0 turns it off (summary.json says so), and whole-grid runs take auto and 0.
    for (const auto& runs : {with(with(active, "rsf.handover_speed=3e-6"), "rsf.alone_speed=0"),
                             with(with(ev, "model.kind=bk"), "rsf.alone_speed=0")}) {
      const auto r = run_bkquake(rsf_args(tmp.file("ok"), runs));
      EXPECT_EQ(r.status, 0) << r.err;
      std::filesystem::remove_all(tmp.path() / "ok");
    }
  }
  expect_refused(run_bkquake(rsf_args(out, with(ev, "rsf.handover_speed=2e-3"))),
                 {"rsf.handover_speed = 0.002", "allowed: auto or (1e-06, 0.001)"});
  // The creep quantum is a positive length up to a metre, and only for drive.mode = events.
  for (const char* bad : {"0", "-1e-6", "2", "none"})
    expect_refused(run_bkquake(rsf_args(out, with(ev, std::string("rsf.creep_quantum=") + bad))),
                   {"rsf.creep_quantum", bad, "(0, 1] or auto"});
  expect_refused(run_bkquake(rsf_args(out, with(cont, "rsf.creep_quantum=1e-6"))),
                 {"rsf.creep_quantum", "drive.mode = events"});
  const auto damped = [&](const std::string& c_s) {
    std::vector<std::string> v = with(with(ev, "model.shear_modulus=2e10"), c_s);
    return v;
  };
  expect_refused(run_bkquake(rsf_args(
                     out, with(damped("model.shear_wave_speed=30"), "rsf.handover_speed=5e-4"))),
                 {"rsf.handover_speed = 5e-04", "radiation damping", "allowed: up to 1.5e-05"});
  expect_refused(run_bkquake(rsf_args(out, damped("model.shear_wave_speed=0.01"))),
                 {"rsf.handover_speed = auto", "radiation damping", "allowed"});
  expect_refused(run_bkquake({"run", "--set", "model.parameterisation=si", "--out", out}),
                 {"model.parameterisation = si", "friction.law = clst91"});
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out" / "catalog.csv"));
}

TEST(RsfRun, QdynSceneWritesCatalogueHistogramAndSummary) {
  test::TempDir tmp;
  const auto r = run_bkquake({"run", kScene, "--quiet", "--out", tmp.file("out")});
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  std::istringstream cat(read_file(tmp.file("out/catalog.csv")));
  std::string line;
  std::getline(cat, line);
  EXPECT_EQ(line.rfind("event,load,trigger,blocks,moment,magnitude,duration,max_speed", 0), 0u);
  std::vector<double> loads, moments;
  while (std::getline(cat, line)) {
    std::vector<double> f;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(std::stod(cell));
    loads.push_back(f[1]);
    moments.push_back(f[4]);
    EXPECT_NEAR(f[5], std::log(f[4]), 1e-12);  // magnitude = ln moment
    EXPECT_GT(f[7], 1e-3);                     // peak slip rate above V_th
    EXPECT_GT(f[6], 0);                        // duration
  }
  // 1e4 s of QDYN's stick-slip at 585.48 s a cycle: 17 events after the first.
  ASSERT_EQ(loads.size(), 18u);
  // Every limit-cycle event slips the same; they recur at QDYN's period (load/V_pl is time).
  EXPECT_NEAR((loads.back() - loads[2]) / 1e-6 / (loads.size() - 3), 585.48, 0.01);
  EXPECT_NEAR(moments.back() / moments[5], 1, 1e-6);
  const std::string summary = read_file(tmp.file("out/summary.json"));
  EXPECT_NE(summary.find("\"events\": 18"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"k_crit\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"scheme\": \"dopri5\""), std::string::npos) << summary;
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "out" / "histogram.csv"));
  // The effective scene reads back to the same run.
  const auto again =
      run_bkquake({"run", tmp.file("out/scene.ini"), "--quiet", "--out", tmp.file("again")});
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(read_file(tmp.file("again/catalog.csv")), read_file(tmp.file("out/catalog.csv")));
}

// A run stopped by SIGTERM after its first checkpoint and resumed writes the catalogue,
// histogram, block samples and afterslip episodes of the run that was never stopped, byte for
// byte.
TEST(RsfRun, KilledAndResumedRunGivesTheSameBytes) {
  test::TempDir tmp;
  const std::vector<std::string> scene = {kScene,  "--quiet",
                                          "--set", "run.duration=2e6",
                                          "--set", "run.checkpoint_events=200",
                                          "--set", "output.blocks=true",
                                          "--set", "output.every=1000",
                                          "--set", "rsf.slow_slip_threshold=2e-6"};
  auto args = [&](const std::string& out, std::vector<std::string> more) {
    std::vector<std::string> a = {"run"};
    a.insert(a.end(), scene.begin(), scene.end());
    a.insert(a.end(), {"--out", out});
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  const auto whole = run_bkquake(args(tmp.file("whole"), {}));
  ASSERT_EQ(whole.status, 0) << whole.err;
  expect_resumed_equals_whole(tmp, args,
                              {"catalog.csv", "histogram.csv", "rsf_blocks.csv", "slow_slip.csv"});
}

// A finished continuous run extended to a longer run.duration (--resume) writes the catalogue,
// histogram, block samples and afterslip episodes of one run of the longer duration, byte for
// byte, from its final state (the one before the step clipped at the shorter duration).
TEST(RsfRun, ExtendedRunGivesTheBytesOfOneLongerRun) {
  test::TempDir tmp;
  auto args = [&](const std::string& out, const std::string& duration, bool resume) {
    std::vector<std::string> a = {"run",
                                  resume ? tmp.file(out + "/scene.ini") : kScene,
                                  "--quiet",
                                  "--set",
                                  "run.duration=" + duration,
                                  "--set",
                                  "output.blocks=true",
                                  "--set",
                                  "output.every=1000",
                                  "--set",
                                  "rsf.slow_slip_threshold=2e-6",
                                  "--out",
                                  tmp.file(out)};
    if (resume) a.push_back("--resume");
    return a;
  };
  const auto whole = run_bkquake(args("whole", "2e6", false));
  ASSERT_EQ(whole.status, 0) << whole.err;
  const auto part = run_bkquake(args("part", "1e6", false));
  ASSERT_EQ(part.status, 0) << part.err;
  ASSERT_TRUE(std::filesystem::exists(tmp.file("part/checkpoint.final.bin")));
  const std::string shorter = read_file(tmp.file("part/catalog.csv"));
  // Not longer: refused, naming both durations, and nothing changed.
  const auto same = run_bkquake(args("part", "1e6", true));
  EXPECT_EQ(same.status, 2);
  EXPECT_NE(same.err.find("run.duration = 1e+06 would not extend it"), std::string::npos)
      << same.err;
  EXPECT_EQ(read_file(tmp.file("part/catalog.csv")), shorter);
  const auto longer = run_bkquake(args("part", "2e6", true));
  ASSERT_EQ(longer.status, 0) << longer.err;
  EXPECT_GT(read_file(tmp.file("part/catalog.csv")).size(), shorter.size());
  for (const char* f : {"catalog.csv", "histogram.csv", "rsf_blocks.csv", "slow_slip.csv"})
    EXPECT_EQ(read_file(tmp.file(std::string("part/") + f)),
              read_file(tmp.file(std::string("whole/") + f)))
        << f;
  EXPECT_NE(read_file(tmp.file("part/summary.json")).find("\"status\": \"finished\""),
            std::string::npos);
}

// The shipped event-driven chain's run arguments, 400 events (or `events`) checkpointed every
// 50, with `sets` (section.key=value) added.
auto event_run_args(std::vector<std::string> sets, int events = 400) {
  sets.insert(sets.end(), {"run.events=" + std::to_string(events), "run.transient_events=20",
                           "run.checkpoint_events=50"});
  return [sets](const std::string& out, std::vector<std::string> more) {
    std::vector<std::string> a = {
        "run", std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/rsf/chain-events.ini", "--quiet"};
    for (const auto& set : sets) a.insert(a.end(), {"--set", set});
    a.insert(a.end(), {"--out", out});
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
}

// The same chain with its rough D_c (per-block values, which the active-block integration
// needs), each event on its active blocks (in one integration, or in groups).
auto active_event_run_args(const std::string& mode = "active", int events = 400) {
  return event_run_args({"rsf.pattern=uniform",
                         "rsf.blocks=" + std::string(BKQUAKE_SOURCE_DIR) +
                             "/data/scenes/rsf/chain-events-rough-blocks.csv",
                         "rsf.event_integration=" + mode},
                        events);
}

// The shipped event-driven chain (20 blocks here), stopped by SIGTERM after its first
// checkpoint and resumed, writes the catalogue and histogram of the run never stopped.
TEST(RsfRun, EventDrivenKilledAndResumedGivesTheSameBytes) {
  test::TempDir tmp;
  const auto args = event_run_args({"model.blocks=20"});
  const auto whole = run_bkquake(args(tmp.file("whole"), {}));
  ASSERT_EQ(whole.status, 0) << whole.err;
  const std::string catalog = read_file(tmp.file("whole/catalog.csv"));
  EXPECT_EQ(std::count(catalog.begin(), catalog.end(), '\n'), 401);
  EXPECT_NE(read_file(tmp.file("whole/summary.json")).find("\"engine\": \"event-driven\""),
            std::string::npos);
  // An event-driven run says so: summary.json's mode and the printed line.
  EXPECT_NE(read_file(tmp.file("whole/summary.json")).find("\"mode\": \"events\""),
            std::string::npos);
  EXPECT_NE(whole.out.find("event-driven run to t = "), std::string::npos) << whole.out;
  expect_resumed_equals_whole(tmp, args, {"catalog.csv", "histogram.csv"});
}

// The same with each event on its active blocks (engine/rsf_active.hpp; the chain with its
// rough D_c, as that integration needs per-block values), in one integration and in groups:
// the same bytes, and the count of active blocks over the steps goes through the checkpoint
// too. 2000 events, so that the run is still going when its first checkpoint is seen.
TEST(RsfRun, ActiveBlocksKilledAndResumedGiveTheSameBytes) {
  for (const std::string mode : {"active", "groups"}) {
    SCOPED_TRACE(mode);
    test::TempDir tmp;
    const auto args = active_event_run_args(mode, 2000);
    const auto whole = run_bkquake(args(tmp.file("whole"), {}));
    ASSERT_EQ(whole.status, 0) << whole.err;
    EXPECT_NE(
        read_file(tmp.file("whole/summary.json")).find("\"event_integration\": \"" + mode + "\""),
        std::string::npos);
    expect_resumed_equals_whole(tmp, args, {"catalog.csv", "histogram.csv"});
    const auto counter = [&](const std::string& dir) {
      const std::string text = read_file(tmp.file(dir + "/summary.json"));
      const std::size_t at = text.find("\"active_block_steps\": ");
      return at == std::string::npos ? std::string() : text.substr(at, text.find(',', at) - at);
    };
    EXPECT_FALSE(counter("whole").empty());
    EXPECT_EQ(counter("cut"), counter("whole"));
    // Blocks integrated alone between events (rsf.alone_speed auto: 100 drive.speed): their
    // steps are counted, through the checkpoint too.
    const auto number = [&](const std::string& dir, const std::string& name) {
      const std::string text = read_file(tmp.file(dir + "/summary.json"));
      const std::size_t at = text.find("\"" + name + "\": ");
      return at == std::string::npos ? -1.0 : std::stod(text.substr(at + name.size() + 4));
    };
    EXPECT_NEAR(number("whole", "alone_speed"), 1e-4, 1e-15);
    EXPECT_NEAR(number("whole", "alone_tolerance"), 1e-6, 1e-20);  // auto: 1e-6 over 1e-8
    EXPECT_GT(number("whole", "alone_steps"), 0);
    EXPECT_EQ(number("cut", "alone_steps"), number("whole", "alone_steps"));
  }
}

// A finished event-driven run (active blocks, blocks alone) extended twice to more events
// (--resume with a larger run.events) writes the catalogue and histogram of one run of the
// most events, byte for byte, wherever the shorter runs ended (between the events of one
// integration too: the final state keeps the records not yet returned).
TEST(RsfRun, ExtendedEventRunGivesTheBytesOfOneLongerRun) {
  test::TempDir tmp;
  const auto args = active_event_run_args();
  const auto whole = run_bkquake(args(tmp.file("whole"), {}));
  ASSERT_EQ(whole.status, 0) << whole.err;
  for (const char* events : {"run.events=103", "run.events=205", "run.events=400"}) {
    const bool first = std::string(events) == "run.events=103";
    const auto r = run_bkquake(
        args(tmp.file("part"), first ? std::vector<std::string>{"--set", events}
                                     : std::vector<std::string>{"--resume", "--set", events}));
    ASSERT_EQ(r.status, 0) << events << ": " << r.err;
  }
  for (const char* f : {"catalog.csv", "histogram.csv"})
    EXPECT_EQ(read_file(tmp.file(std::string("part/") + f)),
              read_file(tmp.file(std::string("whole/") + f)))
        << f;
  // Fewer events than the finished run's: refused.
  const auto fewer = run_bkquake(args(tmp.file("part"), {"--resume", "--set", "run.events=300"}));
  EXPECT_EQ(fewer.status, 2);
  EXPECT_NE(fewer.err.find("would not extend it (allowed: more than 400)"), std::string::npos)
      << fewer.err;
}

// rsf.blocks: per-block a, b and D_c. Two uncoupled blocks, one with QDYN's law and one with
// another: each fails on its own period, QDYN's block on QDYN's.
TEST(RsfRun, PerBlockParametersFromAFile) {
  test::TempDir tmp;
  tmp.write("blocks.csv", "# two blocks\nblock,a,b,dc\n0,0.01,0.025,1e-5\n1,0.01,0.02,2e-5\n");
  std::string text = read_file(kScene);
  text.replace(text.find("kind = 1dof"), 11, "kind = bk\nblocks = 2");
  text.replace(text.find("v_init = 2e-5"), 13, "v_init = 2e-5\nblocks = blocks.csv");
  const std::string scene = tmp.write("s.ini", text);
  Scene s = Scene::from_file(scene);
  s.validate();
  const Settings st = settings_from_scene(s);
  ASSERT_EQ(st.rsf.chain.n(), 2);
  EXPECT_EQ(st.rsf.chain.law[0].params().b_rsf, 0.025);
  EXPECT_EQ(st.rsf.chain.law[1].params().b_rsf, 0.02);
  EXPECT_EQ(st.rsf.chain.law[1].params().dc, 2e-5);
  EXPECT_EQ(st.rsf.theta_start()[1], 2e-5 / 1e-6);  // each block's own steady state
  const auto r = run_bkquake({"run", scene, "--quiet", "--out", tmp.file("out")});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream cat(read_file(tmp.file("out/catalog.csv")));
  std::string line;
  std::getline(cat, line);
  std::vector<double> t0, t1;
  while (std::getline(cat, line)) {
    std::vector<double> f;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(std::stod(cell));
    EXPECT_EQ(f[3], 1);  // uncoupled: one block an event
    (f[2] == 0 ? t0 : t1).push_back(f[1] / 1e-6);
  }
  ASSERT_GE(t0.size(), 10u);
  ASSERT_GE(t1.size(), 3u);
  EXPECT_NEAR((t0.back() - t0[2]) / (t0.size() - 3), 585.48, 0.01);
  EXPECT_GT(std::fabs((t1.back() - t1[1]) / (t1.size() - 2) - 585.48), 10);
  // A bad row: one line naming the file, the line and the range.
  tmp.write("blocks.csv", "block,a,b,dc\n0,0.01,0.025,1e-5\n1,0,0.02,2e-5\n");
  expect_refused(run_bkquake({"run", scene, "--quiet", "--out", tmp.file("bad")}),
                 {"blocks.csv line 3", "a: expected a value in (0, 10], got 0"});
}

// The shipped chain scene (32 blocks, asperities from its rsf.blocks file) runs through the
// catalogue and `bkquake seismicity`: ruptures of one block and of several.
TEST(RsfRun, ShippedChainSceneRunsThroughTheStatistics) {
  test::TempDir tmp;
  const std::string chain =
      std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/rsf/chain-asperities.ini";
  const auto r =
      run_bkquake({"run", chain, "--quiet", "--set", "run.duration=1e4", "--out", tmp.file("out")});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream cat(read_file(tmp.file("out/catalog.csv")));
  std::string line;
  std::getline(cat, line);
  int events = 0, single = 0, largest = 0;
  while (std::getline(cat, line)) {
    std::vector<double> f;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(std::stod(cell));
    ++events;
    single += f[3] == 1;
    largest = std::max(largest, static_cast<int>(f[3]));
    EXPECT_LE(f[9], f[2]);  // first_block <= trigger <= last_block
    EXPECT_GE(f[10], f[2]);
  }
  EXPECT_GT(events, 100);
  EXPECT_GT(single, 0);
  EXPECT_GT(largest, 3);
  const auto s = run_bkquake({"seismicity", tmp.file("out")});
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "out" / "seismicity" / "seismicity.json"));
}

// output.blocks writes rsf_blocks.csv for the chosen blocks, and analysis/plot_rsf.py draws it.
TEST(RsfRun, BlockSamplesAndTheirPlot) {
  test::TempDir tmp;
  const std::string chain =
      std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/rsf/chain-asperities.ini";
  const auto r = run_bkquake({"run", chain, "--quiet", "--set", "run.duration=2000", "--set",
                              "output.blocks=true", "--set", "output.every=10", "--set",
                              "output.block_first=4", "--set", "output.block_count=3", "--out",
                              tmp.file("out")});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream in(read_file(tmp.file("out/rsf_blocks.csv")));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,block,slip_rate,theta,shear_stress,slip");
  int rows = 0;
  while (std::getline(in, line)) {
    std::vector<double> f;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(std::stod(cell));
    ASSERT_EQ(f.size(), 6u);
    EXPECT_EQ(f[0], 10.0 * (rows / 3));  // on the grid k * output.every
    EXPECT_EQ(f[1], 4 + rows % 3);
    EXPECT_GT(f[2], 0);
    ++rows;
  }
  EXPECT_EQ(rows, 3 * 201);  // t = 0, 10, ..., 2000
  if (test::run_process("/usr/bin/python3", {"-c", "import numpy, matplotlib"}).status != 0)
    GTEST_SKIP() << "no numpy/matplotlib for /usr/bin/python3";
  const auto p = test::run_process(
      "/usr/bin/python3", {std::string(BKQUAKE_SOURCE_DIR) + "/analysis/plot_rsf.py",
                           tmp.file("out"), "--blocks", "4", "6", "--out", tmp.file("rsf.png")});
  ASSERT_EQ(p.status, 0) << p.out << p.err;
  EXPECT_GT(std::filesystem::file_size(tmp.file("rsf.png")), 10000u);
}

TEST(RsfRun, StabilityReportsCriticalStiffness) {
  test::TempDir tmp;
  const auto r = run_bkquake({"stability", kScene, "--out", tmp.file("st")});
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("k_crit = sigma (b - a)/D_c = 7.5e+09 Pa/m"), std::string::npos) << r.out;
  const std::string csv = read_file(tmp.file("st/rsf_stability.csv"));
  EXPECT_EQ(csv.rfind("v_pl,k,k_c,k_crit_quasi_static,k_crit_radiation_damping,k_crit,", 0), 0u);
  // QDYN's k = 2e9 is below k_crit: its one mode grows.
  EXPECT_NE(read_file(tmp.file("st/stability.csv")).find("chain 0,0.0549930"), std::string::npos);
}

}  // namespace
}  // namespace bkq
