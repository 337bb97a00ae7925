// Observers: the list notifies in attachment order and stops after a detach; a run
// notifies an attached observer of every recorded event, sample, phase and the end, and
// what it adds to the summary lands in summary.json without any edit of the run loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "app/observers/checkpoint_timer.hpp"
#include "app/observers/event_slip.hpp"
#include "app/observers/observer.hpp"
#include "app/run.hpp"
#include "core/error.hpp"
#include "io/checkpoint.hpp"
#include "io/json.hpp"
#include "io/schema.hpp"
#include "io/seismicity_csv.hpp"

namespace bkq {
namespace {

// A quiet run of the default scene with `keys` set, writing into `out`.
RunRequest quiet_run(const std::vector<std::pair<std::string, std::string>>& keys,
                     const std::string& out) {
  RunRequest req;
  for (const auto& [k, v] : keys) req.scene.set(k, v);
  req.scene.validate();
  req.out_dir = out;
  req.quiet = true;
  return req;
}

struct Recorder : RunObserver {
  void on_start() override { ++starts; }
  void on_phase(const Phase& p) override { phases.push_back(p.what); }
  void on_event(const EventRecord& e) override { events.push_back(e.event); }
  void on_sample(const Sample& s) override { sample_times.push_back(s.values.t); }
  void on_advance(const Advance&) override { ++advances; }
  void on_end(const RunEnd& e) override {
    ++ends;
    end = e;
  }
  void add_to_summary(Json& summary) const override {
    summary.set("recorded_by_test", static_cast<std::int64_t>(events.size()));
  }
  int starts = 0, ends = 0;
  std::int64_t advances = 0;
  std::vector<std::string> phases;
  std::vector<std::int64_t> events;
  std::vector<double> sample_times;
  RunEnd end;
};

TEST(Observers, NotifyInOrderAndStopAfterDetach) {
  std::vector<int> order;
  struct Tagged : RunObserver {
    Tagged(std::vector<int>& o, int t) : order(o), tag(t) {}
    void on_event(const EventRecord&) override { order.push_back(tag); }
    std::vector<int>& order;
    int tag;
  };
  Observers obs;
  Tagged& first = obs.attach<Tagged>(order, 1);
  Tagged second(order, 2);
  obs.attach_ref(second);
  obs.event(EventRecord{});
  EXPECT_EQ(order, (std::vector<int>{1, 2}));
  obs.detach(first);
  obs.event(EventRecord{});
  EXPECT_EQ(order, (std::vector<int>{1, 2, 2}));
  EXPECT_EQ(obs.size(), 1u);
}

TEST(Observers, CheckpointTimerAsksEveryNEvents) {
  int written = 0;
  CheckpointTimer timer([&] { ++written; }, 3, 0.0);
  timer.on_start();
  for (std::int64_t e = 1; e <= 10; ++e) timer.on_advance({static_cast<double>(e), e});
  EXPECT_EQ(written, 3);
}

// Checkpoints by time: the first kFirstCheckpointSeconds after the start (a SIGKILL early
// in a long run loses no more than that), then every period; a shorter period applies
// from the start. A fake clock advances one second per kClockStride advances.
std::vector<double> checkpoint_times(double period, int seconds) {
  double t = 1000;
  std::vector<double> written_at;
  CheckpointTimer* self = nullptr;
  CheckpointTimer timer(
      [&] {
        written_at.push_back(t - 1000);
        Checkpoint c;
        self->on_checkpoint(c);  // as the run's save() notifies every observer
      },
      0, period, [&] { return t; });
  self = &timer;
  timer.on_start();
  for (int s = 0; s < seconds; ++s) {
    t += 1;
    for (std::int64_t k = 0; k < CheckpointTimer::kClockStride; ++k) timer.on_advance({0.0, 0});
  }
  return written_at;
}

TEST(Observers, FirstCheckpointComesEarlyThenAtThePeriod) {
  ASSERT_EQ(kFirstCheckpointSeconds, 30.0);
  EXPECT_EQ(checkpoint_times(600, 1300), (std::vector<double>{30, 630, 1230}));
  EXPECT_EQ(checkpoint_times(10, 35), (std::vector<double>{10, 20, 30}));
}

TEST(Observers, EventRunNotifiesAnAttachedObserver) {
  test::TempDir dir;
  Recorder rec;
  RunRequest req =
      quiet_run({{"model.blocks", "20"}, {"run.events", "40"}, {"run.transient_events", "10"}},
                dir.file("out"));
  req.observers.push_back(&rec);
  ASSERT_EQ(run_scene(req), 0);

  EXPECT_EQ(rec.starts, 1);
  EXPECT_EQ(rec.ends, 1);
  EXPECT_EQ(rec.end.signal, 0);
  EXPECT_EQ(rec.phases, (std::vector<std::string>{"transient events", "events"}));
  ASSERT_EQ(rec.events.size(), 40u);
  for (std::size_t i = 0; i < rec.events.size(); ++i)
    EXPECT_EQ(rec.events[i], static_cast<std::int64_t>(i + 1));
  EXPECT_EQ(rec.advances, 50);
  EXPECT_TRUE(rec.sample_times.empty());
  EXPECT_NE(test::read_file(dir.file("out/summary.json")).find("\"recorded_by_test\": 40"),
            std::string::npos);
}

TEST(Observers, ContinuousRunNotifiesSamplesAndEpisodes) {
  test::TempDir dir;
  Recorder rec;
  RunRequest req = quiet_run({{"model.blocks", "10"},
                              {"drive.mode", "continuous"},
                              {"drive.speed", "0.1"},
                              {"run.duration", "20"},
                              {"output.every", "2"}},
                             dir.file("out"));
  req.observers.push_back(&rec);
  ASSERT_EQ(run_scene(req), 0);

  EXPECT_EQ(rec.phases, (std::vector<std::string>{"time"}));
  ASSERT_EQ(rec.sample_times.size(), 11u);  // t = 0, 2, ..., 20
  EXPECT_NEAR(rec.sample_times.back(), 20.0, 1e-9);
  EXPECT_EQ(rec.end.events, static_cast<std::int64_t>(rec.events.size()));
  // One catalog row per episode the observer saw, plus the header.
  const std::string catalog = test::read_file(dir.file("out/catalog.csv"));
  EXPECT_EQ(static_cast<std::size_t>(std::count(catalog.begin(), catalog.end(), '\n')),
            rec.events.size() + 1);
  EXPECT_NE(test::read_file(dir.file("out/summary.json")).find("\"pad_friction_mean\""),
            std::string::npos);
}

// An observer with state of its own keeps it in the checkpoint under its name: stopped by
// SIGTERM midway and resumed, it ends with the count of a run that never stopped.
struct Counter : RunObserver {
  void on_resume(const Checkpoint& c) override {
    if (const std::string* bytes = c.find("test.counter")) {
      StateReader r(*bytes, "test.counter");
      n = r.i64();
      restored = true;
    }
  }
  void on_event(const EventRecord&) override {
    if (++n == stop_at) std::raise(SIGTERM);
  }
  void on_checkpoint(Checkpoint& c) override {
    StateWriter w;
    w.i64(n);
    c.put("test.counter", w.bytes());
  }
  std::int64_t n = 0, stop_at = -1;
  bool restored = false;
};

TEST(Observers, OwnStateSurvivesAStopAndResume) {
  test::TempDir dir;
  RunRequest req =
      quiet_run({{"model.blocks", "20"}, {"run.events", "40"}, {"run.transient_events", "5"}},
                dir.file("out"));
  Counter first;
  first.stop_at = 15;
  req.observers = {&first};
  ASSERT_EQ(run_scene(req), 128 + SIGTERM);
  EXPECT_EQ(first.n, 15);

  Counter second;
  req.observers = {&second};
  req.resume = true;
  ASSERT_EQ(run_scene(req), 0);
  EXPECT_TRUE(second.restored);
  EXPECT_EQ(second.n, 40);
}

// The slip writer splits an engine's flat site index j = x + width * y into block (x) and,
// with more than one row, row (y): the form a lattice engine that reports (j, slip) gets
// (here a made-up 5 x 3 lattice without topplings, and one with them); a chain (one row)
// keeps event,block,slip; events below the threshold write nothing.
TEST(Observers, EventSlipWriterSplitsTheSiteIndexByTheLatticesWidth) {
  test::TempDir tmp;
  std::vector<std::pair<int, double>> slips;
  std::vector<int> topplings;
  auto write = [&](const std::string& name, SlipSource source) {
    const std::string path = tmp.file(name);
    EventSlipWriter w(path, 0.5, source);
    w.on_start();
    EventRecord e;
    slips = {{0, 0.25}, {4, 1.5}, {7, 2}, {14, 0.125}};
    topplings = {1, 2, 1, 3};
    e.event = 3;
    e.magnitude = 1.0;
    w.on_event(e);
    e.event = 4;
    e.magnitude = 0.25;  // below 0.5: not written
    w.on_event(e);
    w.on_end(RunEnd{});
    return test::read_file(path);
  };
  EXPECT_EQ(write("lattice.csv", {.slips = &slips, .width = 5, .rows = 3}),
            "event,block,row,slip\n3,0,0,0.25\n3,4,0,1.5\n3,2,1,2\n3,4,2,0.125\n");
  EXPECT_EQ(header_of(event_slip_schema({.rows = true})), "event,block,row,slip");
  EXPECT_EQ(write("ofc.csv", {.slips = &slips, .topplings = &topplings, .width = 5, .rows = 3}),
            "event,block,row,slip,topplings\n3,0,0,0.25,1\n3,4,0,1.5,2\n3,2,1,2,1\n"
            "3,4,2,0.125,3\n");
  EXPECT_EQ(write("chain.csv", {.slips = &slips, .width = 15}),
            "event,block,slip\n3,0,0.25\n3,4,1.5\n3,7,2\n3,14,0.125\n");
  EXPECT_EQ(header_of(event_slip_schema()), "event,block,slip");
}

TEST(Checkpoint, ObserverStatesRoundTrip) {
  Checkpoint c;
  c.engine.state.w = c.engine.state.wd = c.engine.state.mobile = c.engine.state.dir = {0.0};
  StateWriter w;
  w.f64(0.1);
  w.i64(-7);
  c.put("a", w.bytes());
  c.put("b", "");
  c.put("a", w.bytes() + "x");  // replaces, keeps its place
  const Checkpoint d = decode_checkpoint(encode_checkpoint(c), "mem");
  ASSERT_EQ(d.observers.size(), 2u);
  EXPECT_EQ(d.observers[0].name, "a");
  ASSERT_NE(d.find("a"), nullptr);
  StateReader r(*d.find("a"), "a");
  EXPECT_EQ(r.f64(), 0.1);
  EXPECT_EQ(r.i64(), -7);
  EXPECT_FALSE(r.done());
  EXPECT_THROW(r.u64(), Error);  // only the "x" is left
  EXPECT_EQ(d.find("missing"), nullptr);
}

// A version-1 file (before the observers' states) is still read: the same bytes without
// the trailing count, with version 1, length and checksum adjusted.
TEST(Checkpoint, FormatVersionOneIsStillRead) {
  Checkpoint c;
  c.engine.state.w = c.engine.state.wd = c.engine.state.mobile = c.engine.state.dir = {0.5};
  c.progress.events_done = 42;
  std::string v2 = encode_checkpoint(c);
  const std::size_t head = 8 + 4 + 8;
  std::string payload = v2.substr(head, v2.size() - head - 8 - 8);  // drop count and checksum
  StateWriter file;
  file.bytes().append(v2, 0, 8);
  file.u32(1);
  file.u64(payload.size());
  file.bytes() += payload;
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64, as checkpoint.cpp
  for (char ch : file.bytes()) {
    h ^= static_cast<unsigned char>(ch);
    h *= 1099511628211ull;
  }
  file.u64(h);
  const Checkpoint d = decode_checkpoint(file.bytes(), "v1");
  EXPECT_EQ(d.progress.events_done, 42);
  EXPECT_TRUE(d.observers.empty());
}

}  // namespace
}  // namespace bkq
