// Long event runs lose nothing: a run stopped by SIGTERM, SIGINT or SIGKILL and continued
// with --resume writes exactly the catalog.csv and histogram.csv of a run that never
// stopped; refused resumes (another scene, a damaged checkpoint, no checkpoint, a finished
// run) change no file; and the checkpoint format round-trips every value exactly and
// detects truncation and any changed byte. The program runs as a subprocess; the signals
// are sent once catalog.csv has grown to a given size, so they land mid-run without timing.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "../cli_helpers.hpp"
#include "../refusal.hpp"
#include "bkquake_version.hpp"
#include "core/error.hpp"
#include "io/catalog.hpp"
#include "io/checkpoint.hpp"
#include "io/histogram_csv.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"
#include "stats/histogram.hpp"

namespace bkq {
namespace {
using test::expect_refused;

namespace fs = std::filesystem;
using test::read_file;
using test::run_args;
using test::run_bkquake;

// 2e5 events of a 50-block Carlson-Langer chain: about a second; a checkpoint every 2e4.
const std::vector<std::string> kScene = {
    "--set",  "model.blocks=50",          "--set", "run.events=200000",
    "--set",  "run.transient_events=100", "--set", "run.checkpoint_events=20000",
    "--quiet"};

std::uintmax_t size_of(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t n = fs::file_size(path, ec);
  return ec ? 0 : n;
}

std::int64_t lines_of(const std::string& path) {
  const std::string s = read_file(path);
  return static_cast<std::int64_t>(std::count(s.begin(), s.end(), '\n'));
}

// Every file of a folder with its bytes: "nothing changed" is equality of two of these.
std::map<std::string, std::string> folder_bytes(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    files[entry.path().filename().string()] = read_file(entry.path().string());
  return files;
}

struct Stopped {
  int status = -1;  // exit status, 128 + signal when killed by one
  std::string err;  // stderr
};

// Starts bkquake with `bkquake_args`, waits until `watch` has at least `min_bytes`, sends `sig`
// and waits for the exit; stdout and stderr go to `log`.
Stopped run_and_signal(const std::vector<std::string>& bkquake_args, const std::string& watch,
                       std::uintmax_t min_bytes, int sig, const std::string& log) {
  Stopped r;
  r.status = test::run_and_signal_when(
      bkquake_args, [&] { return size_of(watch) >= min_bytes; }, sig, log);
  r.err = read_file(log);
  return r;
}

class Resume : public ::testing::Test {
 protected:
  // The straight run every interrupted one is compared with.
  static void SetUpTestSuite() {
    straight_ = new test::TempDir;
    const auto r = run_bkquake(run_args(kScene, {"--out", straight_->file("out")}));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  static void TearDownTestSuite() {
    delete straight_;
    straight_ = nullptr;
  }
  static std::string straight(const std::string& name) { return straight_->file("out/" + name); }

  // A run of kScene stopped by `sig` once catalog.csv holds `fraction` of its final size.
  Stopped interrupt(const std::string& out, int sig, double fraction) {
    const auto min_bytes = static_cast<std::uintmax_t>(
        fraction * static_cast<double>(size_of(straight("catalog.csv"))));
    return run_and_signal(run_args(kScene, {"--out", out}), out + "/catalog.csv", min_bytes, sig,
                          tmp_.file("log.txt"));
  }

  void expect_same_results(const std::string& out) {
    EXPECT_TRUE(read_file(out + "/catalog.csv") == read_file(straight("catalog.csv")));
    EXPECT_EQ(read_file(out + "/histogram.csv"), read_file(straight("histogram.csv")));
    EXPECT_EQ(run_status(out), RunStatus::Finished);
    // The summary of the resumed run is the straight run's but for timing and `resumes`.
    EXPECT_EQ(test::summary_without_timing(read_file(out + "/summary.json")),
              test::summary_without_timing(read_file(straight("summary.json"))));
    EXPECT_FALSE(CheckpointFiles(out).exist()) << "a finished run keeps no checkpoint";
    for (const auto& e : fs::directory_iterator(out))
      EXPECT_FALSE(is_write_temporary(e.path().filename().string())) << e.path();
  }

  // The summary an interrupted run leaves: marked interrupted, with the figures of its
  // checkpoint, no fit, and what continues it.
  static void expect_interrupted_summary(const std::string& out, const char* signal) {
    ASSERT_EQ(run_status(out), RunStatus::Interrupted);
    const std::string summary = read_file(out + "/summary.json");
    const Checkpoint c = CheckpointFiles(out).read();
    for (const std::string& want :
         {std::string("\"status\": \"interrupted\""), std::string("\"signal\": \"") + signal + "\"",
          std::string("\"checkpoint\": \"checkpoint.bin\""),
          "\"resume\": \"bkquake run " + out + "/scene.ini --out " + out + " --resume\"",
          std::string("\"events_planned\": 200000"),
          "\"events\": " + std::to_string(c.progress.events_done) + ",",
          "\"transient_events\": " + std::to_string(c.progress.transient_done) + ",",
          std::string("\"b_mle\": null"), std::string("\"fit_error\": \"no fit: interrupted"),
          std::string("\"accuracy\": {"), std::string("\"energy_residual_max\": ")})
      EXPECT_NE(summary.find(want), std::string::npos) << want << " missing in\n" << summary;
    EXPECT_EQ(read_json_number(out + "/summary.json", "moment_sum"), c.progress.moment_sum);
  }

  static test::TempDir* straight_;
  test::TempDir tmp_;
};

test::TempDir* Resume::straight_ = nullptr;

TEST_F(Resume, SigtermMidRunThenResumeIsByteIdentical) {
  const std::string out = tmp_.file("out");
  const Stopped s = interrupt(out, SIGTERM, 0.4);
  ASSERT_EQ(s.status, 143) << s.err;
  EXPECT_NE(s.err.find("stopped by SIGTERM"), std::string::npos) << s.err;
  EXPECT_NE(s.err.find(out + "/checkpoint.bin"), std::string::npos) << s.err;
  EXPECT_NE(s.err.find("--resume"), std::string::npos) << s.err;
  expect_interrupted_summary(out, "SIGTERM");
  // The current event was finished and the catalog flushed: it ends at the checkpoint.
  const Checkpoint c = CheckpointFiles(out).read();
  EXPECT_GT(c.progress.events_done, 0);
  EXPECT_LT(c.progress.events_done, 200000);
  EXPECT_EQ(lines_of(out + "/catalog.csv"), c.progress.events_done + 1);
  EXPECT_EQ(size_of(out + "/catalog.csv"), c.progress.catalog_bytes);

  const auto r = run_bkquake(run_args(kScene, {"--out", out, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("resuming"), std::string::npos) << r.out;
  expect_same_results(out);
  EXPECT_NE(read_file(out + "/summary.json").find("\"resumes\": 1"), std::string::npos);
}

TEST_F(Resume, SigintStopsWith130AndTheRunsOwnSceneIniResumesIt) {
  const std::string out = tmp_.file("out");
  const Stopped s = interrupt(out, SIGINT, 0.2);
  ASSERT_EQ(s.status, 130) << s.err;
  EXPECT_NE(s.err.find("stopped by SIGINT"), std::string::npos) << s.err;
  expect_interrupted_summary(out, "SIGINT");
  const Checkpoint c = CheckpointFiles(out).read();
  EXPECT_EQ(lines_of(out + "/catalog.csv"), c.progress.events_done + 1);
  // The stop message tells to resume with the folder's scene.ini: that is the same scene.
  const auto r = run_bkquake({"run", out + "/scene.ini", "--out", out, "--resume", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_results(out);
}

TEST_F(Resume, SigkillResumesFromThePeriodicCheckpointAndDropsLaterRows) {
  const std::string out = tmp_.file("out");
  const Stopped s = interrupt(out, SIGKILL, 0.6);
  ASSERT_EQ(s.status, 128 + SIGKILL) << s.err;
  const CheckpointFiles files(out);
  ASSERT_TRUE(fs::exists(files.current()));
  ASSERT_TRUE(fs::exists(files.previous())) << "the checkpoint before the newest is kept";
  const Checkpoint c = files.read();
  const Checkpoint prev = decode_checkpoint(read_file(files.previous()), files.previous());
  EXPECT_EQ(c.progress.events_done - prev.progress.events_done, 20000);
  EXPECT_EQ((c.progress.events_done + 100) % 20000, 0) << "checkpoints every 20000 engine events";
  EXPECT_GT(size_of(out + "/catalog.csv"), c.progress.catalog_bytes) << "rows after the checkpoint";

  const auto r = run_bkquake(run_args(kScene, {"--out", out, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_results(out);
}

// A second SIGTERM while the run stops exits at once, wherever the run is: in the event,
// writing the checkpoint, or writing the interrupted summary. Each file is written to a
// temporary and renamed, so whatever is there is whole: the newest checkpoint (or the
// periodic one before it) and, if there is a summary, a whole interrupted one.
TEST_F(Resume, SecondSigtermWhileStoppingLeavesWholeFilesAndResumes) {
  const std::string out = tmp_.file("out");
  const auto min_bytes =
      static_cast<std::uintmax_t>(0.3 * static_cast<double>(size_of(straight("catalog.csv"))));
  const int status = test::run_and_signal_when(
      run_args(kScene, {"--out", out}),
      [&] {
        return fs::exists(out + "/checkpoint.bin") && size_of(out + "/catalog.csv") >= min_bytes;
      },
      SIGTERM, tmp_.file("log.txt"), "", 2);
  ASSERT_EQ(status, 143) << read_file(tmp_.file("log.txt"));
  EXPECT_NO_THROW(CheckpointFiles(out).read());
  if (fs::exists(out + "/summary.json")) {
    EXPECT_EQ(run_status(out), RunStatus::Interrupted);
    EXPECT_EQ(read_file(out + "/summary.json").back(), '\n') << "a whole summary";
  }
  const auto r = run_bkquake(run_args(kScene, {"--out", out, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_results(out);
}

TEST_F(Resume, CrashBetweenTheTwoRenamesResumesFromThePreviousCheckpoint) {
  const std::string out = tmp_.file("out");
  ASSERT_EQ(interrupt(out, SIGKILL, 0.6).status, 128 + SIGKILL);
  const CheckpointFiles files(out);
  fs::remove(files.current());
  ASSERT_TRUE(fs::exists(files.previous()));
  const auto r = run_bkquake(run_args(kScene, {"--out", out, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("checkpoint.prev.bin"), std::string::npos) << r.out;
  expect_same_results(out);
}

TEST_F(Resume, StoppedDuringTheTransient) {
  const std::vector<std::string> scene = {"--set",  "model.blocks=50",
                                          "--set",  "run.events=2000",
                                          "--set",  "run.transient_events=80000",
                                          "--set",  "run.checkpoint_events=5000",
                                          "--quiet"};
  const std::string a = tmp_.file("a"), b = tmp_.file("b");
  ASSERT_EQ(run_bkquake(run_args(scene, {"--out", a})).status, 0);
  // SIGTERM pending from the start: the run stops at its first event, inside the transient,
  // whatever the speed of the machine.
  const int status =
      test::run_with_pending_signal(run_args(scene, {"--out", b}), SIGTERM, tmp_.file("log.txt"));
  ASSERT_EQ(status, 143) << read_file(tmp_.file("log.txt"));
  const Checkpoint c = CheckpointFiles(b).read();
  EXPECT_LT(c.progress.transient_done, 80000) << "the signal should land in the transient";
  EXPECT_EQ(c.progress.events_done, 0);
  // Stopped before recording began: no events, no load, no work yet.
  EXPECT_EQ(run_status(b), RunStatus::Interrupted);
  EXPECT_EQ(read_json_number(b + "/summary.json", "transient_events"),
            static_cast<double>(c.progress.transient_done));
  EXPECT_EQ(read_json_number(b + "/summary.json", "events"), 0.0);
  EXPECT_EQ(read_json_number(b + "/summary.json", "total_load"), 0.0);
  const auto r = run_bkquake(run_args(scene, {"--out", b, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(read_file(b + "/catalog.csv") == read_file(a + "/catalog.csv"));
  EXPECT_EQ(read_file(b + "/histogram.csv"), read_file(a + "/histogram.csv"));
  EXPECT_EQ(test::summary_without_timing(read_file(b + "/summary.json")),
            test::summary_without_timing(read_file(a + "/summary.json")));
}

TEST_F(Resume, AnotherSceneIsRefusedAndNothingChanges) {
  const std::string out = tmp_.file("out");
  ASSERT_EQ(interrupt(out, SIGTERM, 0.05).status, 143);
  const auto before = folder_bytes(out);
  expect_refused(
      run_bkquake(run_args(kScene, {"--out", out, "--resume", "--set", "friction.alpha=2"})),
      {"another scene", "friction.alpha = 2.5 in the checkpoint, 2 now"});
  EXPECT_TRUE(folder_bytes(out) == before);
}

TEST_F(Resume, DamagedOrTruncatedCheckpointIsRefusedAndNothingChanges) {
  const std::string out = tmp_.file("out");
  ASSERT_EQ(interrupt(out, SIGTERM, 0.05).status, 143);
  const std::string ckpt = out + "/checkpoint.bin";
  const std::string good = read_file(ckpt);

  std::string flipped = good;
  flipped[flipped.size() / 2] ^= 0x01;
  tmp_.write("out/checkpoint.bin", flipped);
  auto before = folder_bytes(out);
  expect_refused(run_bkquake(run_args(kScene, {"--out", out, "--resume"})),
                 {ckpt, "damaged", "checksum"});
  EXPECT_TRUE(folder_bytes(out) == before);

  tmp_.write("out/checkpoint.bin", good.substr(0, good.size() - 100));
  before = folder_bytes(out);
  expect_refused(run_bkquake(run_args(kScene, {"--out", out, "--resume"})), {ckpt, "truncated"});
  EXPECT_TRUE(folder_bytes(out) == before);
}

TEST_F(Resume, CatalogShorterThanItsCheckpointIsRefused) {
  const std::string out = tmp_.file("out");
  ASSERT_EQ(interrupt(out, SIGTERM, 0.05).status, 143);
  const std::string catalog = read_file(out + "/catalog.csv");
  tmp_.write("out/catalog.csv", catalog.substr(0, catalog.size() - 10));
  const auto before = folder_bytes(out);
  expect_refused(run_bkquake(run_args(kScene, {"--out", out, "--resume"})),
                 {"catalog.csv", "changed after the checkpoint"});
  EXPECT_TRUE(folder_bytes(out) == before);
}

TEST_F(Resume, WithoutACheckpointIsRefused) {
  const std::string out = tmp_.file("out");
  fs::create_directories(out);
  tmp_.write("out/catalog.csv", catalog_header() + "\n");
  const auto before = folder_bytes(out);
  expect_refused(run_bkquake(run_args(kScene, {"--out", out, "--resume"})),
                 {"--resume", "no checkpoint", out});
  EXPECT_TRUE(folder_bytes(out) == before);
}

TEST_F(Resume, FinishedAndInterruptedRunsAreNotOverwrittenWithoutForce) {
  const std::string done = straight_->file("out");
  const auto finished = folder_bytes(done);
  expect_refused(run_bkquake(run_args(kScene, {"--out", done})), {"finished run", "--force"});
  expect_refused(run_bkquake(run_args(kScene, {"--out", done, "--resume"})),
                 {"--resume", "finished run", "nothing to continue"});
  EXPECT_TRUE(folder_bytes(done) == finished);

  const std::string out = tmp_.file("out");
  ASSERT_EQ(interrupt(out, SIGTERM, 0.05).status, 143);
  const auto interrupted = folder_bytes(out);
  expect_refused(run_bkquake(run_args(kScene, {"--out", out})),
                 {"interrupted run", "--resume", "--force"});
  EXPECT_TRUE(folder_bytes(out) == interrupted);

  // --force starts over: the old checkpoints go with the old run.
  const auto r =
      run_bkquake(run_args(kScene, {"--out", out, "--force", "--set", "run.events=1000"}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(CheckpointFiles(out).exist());
  EXPECT_EQ(lines_of(out + "/catalog.csv"), 1001);
}

// Continuous runs resume too (test_continuous_run.cpp); without a checkpoint they refuse.
TEST_F(Resume, ContinuousRunWithoutACheckpointIsRefused) {
  const std::string out = tmp_.file("out");
  std::filesystem::create_directory(out);  // a missing folder is refused before that
  expect_refused(run_bkquake({"run", "--set", "drive.mode=continuous", "--out", out, "--resume"}),
                 {"--resume", "no checkpoint"});
}

// ---- the checkpoint format ----

Checkpoint sample_checkpoint() {
  Checkpoint c;
  c.version = kVersion;
  c.git_revision = "abc123";
  const Scene scene;
  c.scene_hash = scene.hash();
  c.scene_ini = scene.to_ini();
  c.seed = 20261121;
  c.progress.transient_done = 1000;
  c.progress.events_done = 123456;
  c.progress.catalog_bytes = 9876543210ull;
  c.progress.load0 = 1.0 / 3.0;
  c.progress.counters0 = {1000, 2, 3, 4, 5};
  c.progress.moment_sum = 1e300;
  c.progress.nonpositive = 7;
  c.progress.wall_events = 12.5;
  c.progress.wall_total = 13.25;
  c.progress.resumes = 2;
  ChainState& st = c.engine.state;
  st.resize(5);
  st.w = {0.1, -0.0, std::numeric_limits<double>::denorm_min(), -1e-300, 7.0 / 9.0};
  st.dir = {1, -1, 1, 1, -1};
  st.x = std::nextafter(1.0, 2.0);
  st.xd = 0;
  st.s = 123.456;
  st.t = 1e9;
  st.sum_w = -2.5;
  c.engine.counters = {124456, 99, 98, 97, 96};
  MagnitudeHistogram h(0.2);
  for (double mu : {-3.1, -2.05, 0.0, 0.3, 4.99, 0.31}) h.add(mu);
  h.set_loading(3.5, 5);
  c.histogram = h.state();
  return c;
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

void expect_equal(const Checkpoint& a, const Checkpoint& b) {
  EXPECT_EQ(a.version, b.version);
  EXPECT_EQ(a.git_revision, b.git_revision);
  EXPECT_EQ(a.scene_hash, b.scene_hash);
  EXPECT_EQ(a.scene_ini, b.scene_ini);
  EXPECT_EQ(a.seed, b.seed);
  const RunProgress &p = a.progress, &q = b.progress;
  EXPECT_EQ(p.transient_done, q.transient_done);
  EXPECT_EQ(p.events_done, q.events_done);
  EXPECT_EQ(p.catalog_bytes, q.catalog_bytes);
  EXPECT_TRUE(same_bits(p.load0, q.load0));
  EXPECT_EQ(p.counters0.events, q.counters0.events);
  EXPECT_EQ(p.counters0.releases, q.counters0.releases);
  EXPECT_TRUE(same_bits(p.moment_sum, q.moment_sum));
  EXPECT_EQ(p.nonpositive, q.nonpositive);
  EXPECT_TRUE(same_bits(p.wall_events, q.wall_events));
  EXPECT_TRUE(same_bits(p.wall_total, q.wall_total));
  EXPECT_EQ(p.resumes, q.resumes);
  const ChainState &s = a.engine.state, &t = b.engine.state;
  ASSERT_EQ(s.n(), t.n());
  for (int j = 0; j < s.n(); ++j) {
    EXPECT_TRUE(same_bits(s.w[j], t.w[j])) << j;
    EXPECT_TRUE(same_bits(s.wd[j], t.wd[j])) << j;
    EXPECT_TRUE(same_bits(s.mobile[j], t.mobile[j])) << j;
    EXPECT_TRUE(same_bits(s.dir[j], t.dir[j])) << j;
  }
  for (auto [u, v] :
       {std::pair{s.x, t.x}, {s.xd, t.xd}, {s.s, t.s}, {s.t, t.t}, {s.sum_w, t.sum_w}})
    EXPECT_TRUE(same_bits(u, v));
  EXPECT_EQ(a.engine.counters.events, b.engine.counters.events);
  EXPECT_EQ(a.engine.counters.steps, b.engine.counters.steps);
  EXPECT_EQ(a.engine.counters.block_steps, b.engine.counters.block_steps);
  EXPECT_EQ(a.engine.counters.sliding_block_steps, b.engine.counters.sliding_block_steps);
  EXPECT_EQ(a.engine.counters.releases, b.engine.counters.releases);
  EXPECT_TRUE(MagnitudeHistogram::from_state(a.histogram) ==
              MagnitudeHistogram::from_state(b.histogram));
}

TEST(Checkpoint, RoundTripIsExact) {
  const Checkpoint c = sample_checkpoint();
  const std::string bytes = encode_checkpoint(c);
  expect_equal(decode_checkpoint(bytes, "mem"), c);
  EXPECT_EQ(encode_checkpoint(decode_checkpoint(bytes, "mem")), bytes);
}

TEST(Checkpoint, HistogramStateRoundTripsAndIsChecked) {
  MagnitudeHistogram h(0.25);
  for (double mu : {-1.0, 2.2, 2.3, 7.9}) h.add(mu);
  h.set_loading(2.0, 10);
  EXPECT_TRUE(MagnitudeHistogram::from_state(h.state()) == h);
  EXPECT_EQ(histogram_csv(MagnitudeHistogram::from_state(h.state())), histogram_csv(h));
  MagnitudeHistogram::State bad = h.state();
  bad.events += 1;
  EXPECT_THROW(MagnitudeHistogram::from_state(bad), Error);
}

TEST(Checkpoint, EveryTruncationAndEveryChangedByteIsDetected) {
  const std::string bytes = encode_checkpoint(sample_checkpoint());
  for (std::size_t n = 0; n < bytes.size(); n += 7)
    EXPECT_THROW(decode_checkpoint(bytes.substr(0, n), "cut"), Error) << n;
  EXPECT_THROW(decode_checkpoint(bytes + "x", "long"), Error);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::string changed = bytes;
    changed[i] ^= 0x10;
    EXPECT_THROW(decode_checkpoint(changed, "flip"), Error) << "byte " << i;
  }
}

TEST(Checkpoint, OtherVersionOrSceneIsRefusedNamingTheDifference) {
  Checkpoint c = sample_checkpoint();
  const Scene scene;
  EXPECT_NO_THROW(check_checkpoint_matches(c, scene, "ck"));
  Scene other;
  other.set("friction.sigma", "0.02");
  other.set("model.blocks", "64");
  try {
    check_checkpoint_matches(c, other, "ck");
    ADD_FAILURE() << "another scene was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("friction.sigma = 0.01 in the checkpoint, 0.02 now"), std::string::npos) << m;
    EXPECT_NE(m.find("model.blocks = 100 in the checkpoint, 64 now"), std::string::npos) << m;
  }
  c.version = "0.0.1";
  try {
    check_checkpoint_matches(c, scene, "ck");
    ADD_FAILURE() << "another version was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bkquake 0.0.1"), std::string::npos) << m;
    EXPECT_NE(m.find(std::string("this is bkquake ") + kVersion), std::string::npos) << m;
  }
}

TEST(Checkpoint, FilesRotateAndTheOldOneSurvives) {
  test::TempDir tmp;
  const CheckpointFiles files(tmp.path().string());
  EXPECT_FALSE(files.exist());
  EXPECT_THROW(files.read(), Error);
  Checkpoint c = sample_checkpoint();
  files.write(c);
  EXPECT_FALSE(fs::exists(files.previous()));
  c.progress.events_done += 1;
  files.write(c);
  std::string from;
  EXPECT_EQ(files.read(&from).progress.events_done, 123457);
  EXPECT_EQ(from, files.current());
  EXPECT_EQ(decode_checkpoint(read_file(files.previous()), "prev").progress.events_done, 123456);
  // Only the two checkpoints are left: no temporary files.
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 2);
  tmp.write(std::string("checkpoint.bin") + kTempMarker + "abc123", "left by a write cut short");
  tmp.write("checkpoint.bin.tmp-abc123", "left by an earlier version's write cut short");
  files.remove();
  EXPECT_FALSE(files.exist());
  EXPECT_TRUE(fs::is_empty(tmp.path()));
}

TEST(Checkpoint, CsvPrefixMustHoldExactlyTheRows) {
  test::TempDir tmp;
  const std::string csv = tmp.write("c.csv", "a,b\n1,2\n3,4\n5,");
  EXPECT_NO_THROW(check_csv_prefix(csv, "a,b", 2, 12));
  EXPECT_NO_THROW(check_csv_prefix(csv, "a,b", 1, 8));
  EXPECT_THROW(check_csv_prefix(csv, "a,b", 2, 8), Error);   // one row, not two
  EXPECT_THROW(check_csv_prefix(csv, "a,b", 1, 10), Error);  // ends mid-row
  EXPECT_THROW(check_csv_prefix(csv, "a,b", 3, 20), Error);  // file too short
  EXPECT_THROW(check_csv_prefix(csv, "x,y", 2, 12), Error);  // other header
  EXPECT_THROW(check_csv_prefix(tmp.file("missing.csv"), "a,b", 0, 4), Error);
}

// The catalogue's checksum is line_hash line by line; check_csv_prefix reads the file in
// blocks of 1 MiB and finds the same value when lines of every length straddle a block's
// end, and another value when one byte differs.
TEST(Checkpoint, CsvPrefixChecksumIsTheLineHashAcrossReadBlocks) {
  test::TempDir tmp;
  std::string text = "a,b\n";
  std::uint64_t sum = line_hash(text, kLineHashSeed);
  std::int64_t rows = 0;
  for (std::size_t len = 1; text.size() < (std::size_t{5} << 19); len = len % 41 + 1, ++rows) {
    std::string line(len, static_cast<char>('0' + rows % 10));
    line += '\n';
    sum = line_hash(line, sum);
    text += line;
  }
  const std::string csv = tmp.write("c.csv", text);
  EXPECT_NO_THROW(check_csv_prefix(csv, "a,b", rows, text.size(), sum));
  EXPECT_THROW(check_csv_prefix(csv, "a,b", rows, text.size(), sum + 1), Error);
  text[(std::size_t{1} << 20) + 3] ^= 1;  // a digit just past the first block, changed
  const std::string edited = tmp.write("d.csv", text);
  EXPECT_THROW(check_csv_prefix(edited, "a,b", rows, text.size(), sum), Error);
}

}  // namespace
}  // namespace bkq

namespace bkq {
namespace {

// A runaway event (here forced by a tiny run.max_steps_per_event) stops the run with a
// message naming the event and saves the state before it: resuming from that checkpoint
// replays the same event, which fails the same way, and the catalog keeps every row
// before it.
TEST(ResumeFailure, FailedEventSavesTheStateBeforeIt) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  const std::vector<std::string> scene = {"--set",  "model.blocks=50",
                                          "--set",  "run.transient_events=0",
                                          "--set",  "run.max_steps_per_event=200",
                                          "--quiet"};
  const auto first = run_bkquake(run_args(scene, {"--out", out}));
  ASSERT_EQ(first.status, 2) << first.err;
  const auto at = first.err.find("event ");
  ASSERT_NE(at, std::string::npos) << first.err;
  const std::string failed_event = first.err.substr(at, first.err.find(' ', at + 6) - at);
  EXPECT_NE(first.err.find("run.max_steps_per_event"), std::string::npos) << first.err;
  EXPECT_NE(first.err.find(out + "/checkpoint.bin"), std::string::npos) << first.err;
  const Checkpoint c = CheckpointFiles(out).read();
  EXPECT_EQ("event " + std::to_string(c.progress.events_done + 1), failed_event);
  EXPECT_EQ(lines_of(out + "/catalog.csv"), c.progress.events_done + 1);

  const auto again = run_bkquake(run_args(scene, {"--out", out, "--resume"}));
  EXPECT_EQ(again.status, 2) << again.err;
  EXPECT_NE(again.err.find(failed_event + " did not end"), std::string::npos) << again.err;
}

}  // namespace
}  // namespace bkq
