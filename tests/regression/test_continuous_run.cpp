// Continuous runs: their slip episodes are events, so a continuous run writes the same
// magnitude histogram (histogram.csv) and Gutenberg-Richter fit in summary.json as an
// event run, through the same observers, and the two modes compare directly. Like event
// runs they lose nothing when stopped: SIGTERM leaves whole rows and a checkpoint, and
// --resume continues bit for bit, for an explicit scheme (also with the energy diagnostics
// and Rayleigh damping), the theta-method, the adaptive
// scheme and a steps schedule with block trajectories; SIGKILL resumes from the periodic
// checkpoint. The signals are sent once timeseries.csv has grown to a given size.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "io/checkpoint.hpp"
#include "io/histogram_csv.hpp"
#include "io/run_folder.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_args;
using test::run_bkquake;

// A 30-block Carlson-Langer chain pulled at speed 0.05: a few hundred slip episodes in
// well under a second.
const std::vector<std::string> kContinuous = {
    "--set",  "drive.mode=continuous", "--set", "model.blocks=30",
    "--set",  "run.duration=1500",     "--set", "drive.speed=0.05",
    "--set",  "integrator.scheme=rk4", "--set", "output.every=5",
    "--quiet"};

// The values of the column `name` of a CSV file without comment lines.
std::vector<double> column_of(const std::string& path, const std::string& name) {
  std::istringstream in(read_file(path));
  std::string line;
  int column = -1;
  std::vector<double> values;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (column < 0) {
      const auto it = std::find(cells.begin(), cells.end(), name);
      if (it == cells.end()) return values;
      column = static_cast<int>(it - cells.begin());
      continue;
    }
    values.push_back(std::strtod(cells.at(static_cast<std::size_t>(column)).c_str(), nullptr));
  }
  return values;
}

TEST(ContinuousRun, WritesTheHistogramAndTheFitOfItsEpisodes) {
  test::TempDir tmp;
  const std::string out = tmp.file("out");
  // A given window: 530 episodes hold no window that passes the goodness-of-fit test, so
  // the automatic one gives no b (docs/explanation/b-fit.md); a given one is fitted.
  const auto r = run_bkquake(run_args(
      kContinuous, {"--out", out, "--set", "stats.mu_min=-7.8", "--set", "stats.mu_max=-1.8"}));
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(out + "/histogram.csv"));

  // Every episode with a positive moment is in the histogram, each in its bin.
  const std::vector<double> moments = column_of(out + "/catalog.csv", "moment");
  ASSERT_GT(moments.size(), 50u);
  const MagnitudeHistogram h = read_histogram_csv(out + "/histogram.csv", 1.0, 30);
  MagnitudeHistogram from_catalog(h.bin_width());
  for (double m : moments)
    if (m > 0) from_catalog.add(std::log(m));
  EXPECT_EQ(h.events(), from_catalog.events());
  EXPECT_EQ(h.state().counts, from_catalog.state().counts);

  const std::string summary = read_file(out + "/summary.json");
  for (const char* field : {"\"b_mle\"", "\"b_mle_err\"", "\"fit_window\"", "\"bin_width\"",
                            "\"nonpositive_moments\"", "\"moment_sum\""})
    EXPECT_NE(summary.find(field), std::string::npos) << field << " missing in\n" << summary;
  EXPECT_NE(r.out.find("b = "), std::string::npos) << r.out;
}

// ---- stop and resume ----

struct ResumeCase {
  std::string name;
  std::vector<std::string> scene;
};

std::vector<std::string> continuous(std::vector<std::string> more) {
  std::vector<std::string> a = {"--set", "drive.mode=continuous", "--quiet"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// Each runs about half a second, long enough to be stopped midway.
std::vector<ResumeCase> resume_cases() {
  const std::vector<std::string> thesis = {"--set", "model.parameterisation=thesis", "--set",
                                           "friction.law=thesis"};
  std::vector<ResumeCase> cases;
  cases.push_back({"rk4", continuous({"--set", "model.blocks=30", "--set", "run.duration=10000",
                                      "--set", "drive.speed=0.05", "--set", "output.every=2",
                                      "--set", "run.checkpoint_events=1000"})});
  // The energy diagnostics' windows and files resume too; with Rayleigh block damping.
  cases.push_back({"rk4_energy_rayleigh",
                   continuous({"--set", "model.blocks=30", "--set", "run.duration=10000", "--set",
                               "drive.speed=0.05", "--set", "output.every=2", "--set",
                               "output.energy=true", "--set", "output.energy_window=300", "--set",
                               "output.status=true", "--set", "model.rayleigh_alpha=0.05"})});
  cases.push_back({"theta", continuous({"--set", "model.blocks=30", "--set", "run.duration=2500",
                                        "--set", "drive.speed=0.05", "--set",
                                        "integrator.scheme=theta", "--set", "output.every=0.5"})});
  std::vector<std::string> adaptive = {
      "--set", "model.kind=1dof",     "--set", "integrator.scheme=adaptive",
      "--set", "run.duration=100000", "--set", "drive.speed=0.1",
      "--set", "integrator.dt=0.2",   "--set", "output.every=2"};
  adaptive.insert(adaptive.end(), thesis.begin(), thesis.end());
  cases.push_back({"adaptive", continuous(adaptive)});
  cases.push_back(
      {"steps_rk2_blocks",
       {"{src}/data/scenes/thesis.ini", "--set", "drive.step_interval=1000", "--set",
        "model.blocks=20", "--set", "output.blocks=true", "--set", "output.every=0.2", "--quiet"}});
  return cases;
}

std::vector<std::string> with_src(std::vector<std::string> args) {
  for (auto& a : args)
    if (a.rfind("{src}", 0) == 0) a = BKQUAKE_SOURCE_DIR + a.substr(5);
  return args;
}

std::uintmax_t size_of(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t n = fs::file_size(path, ec);
  return ec ? 0 : n;
}

// The file without its provenance: comment lines of CSV and INI files, and the summary's
// fields that may differ between a resumed run and a straight one (timing, `resumes`).
std::string without_provenance(const std::string& name, const std::string& bytes) {
  if (name == "summary.json") return test::summary_without_timing(bytes);
  std::istringstream in(bytes);
  std::string out;
  for (std::string line; std::getline(in, line);)
    if (line.empty() || line[0] != '#') out += line + "\n";
  return out;
}

std::map<std::string, std::string> outputs_of(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "checkpoint.final.bin") continue;  // the final state: it holds its clocks
    files[name] = without_provenance(name, read_file(e.path().string()));
  }
  return files;
}

class ContinuousResume : public ::testing::TestWithParam<ResumeCase> {
 protected:
  void SetUp() override {
    scene_ = with_src(GetParam().scene);
    const auto r = run_bkquake(run_args(scene_, {"--out", straight()}));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  std::string straight() const { return tmp_.file("straight"); }

  // Runs the scene into `out`, sending `sig` once timeseries.csv holds `fraction` of its
  // final size (and, with `after_checkpoint`, a checkpoint exists).
  int interrupt(const std::string& out, int sig, double fraction, bool after_checkpoint) {
    const auto min_bytes = static_cast<std::uintmax_t>(
        fraction * static_cast<double>(size_of(straight() + "/timeseries.csv")));
    return test::run_and_signal_when(
        run_args(scene_, {"--out", out}),
        [&] {
          return size_of(out + "/timeseries.csv") >= min_bytes &&
                 (!after_checkpoint || fs::exists(out + "/checkpoint.bin"));
        },
        sig, tmp_.file("log.txt"));
  }

  void resume_and_compare(const std::string& out) {
    const auto r = run_bkquake(run_args(scene_, {"--out", out, "--resume"}));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(CheckpointFiles(out).exist()) << "a finished run keeps no checkpoint";
    const auto want = outputs_of(straight());
    const auto got = outputs_of(out);
    ASSERT_EQ(want.size(), got.size());
    for (const auto& [name, bytes] : want) {
      const auto it = got.find(name);
      ASSERT_NE(it, got.end()) << name;
      EXPECT_TRUE(it->second == bytes) << name << " differs from the straight run's";
    }
    EXPECT_NE(read_file(out + "/summary.json").find("\"resumes\": 1"), std::string::npos);
  }

  std::vector<std::string> scene_;
  test::TempDir tmp_;
};

TEST_P(ContinuousResume, SigtermLeavesWholeRowsAndResumeIsByteIdentical) {
  const std::string out = tmp_.file("out");
  const int status = interrupt(out, SIGTERM, 0.4, false);
  const std::string err = read_file(tmp_.file("log.txt"));
  ASSERT_EQ(status, 143) << err;
  EXPECT_NE(err.find("stopped by SIGTERM"), std::string::npos) << err;
  EXPECT_NE(err.find(out + "/checkpoint.bin"), std::string::npos) << err;
  EXPECT_NE(err.find("--resume"), std::string::npos) << err;
  // The summary is marked interrupted and holds the figures of the checkpoint, no fit.
  ASSERT_EQ(run_status(out), RunStatus::Interrupted);
  const Checkpoint c = CheckpointFiles(out).read();
  const std::string summary = read_file(out + "/summary.json");
  for (const std::string& want :
       {std::string("\"mode\": \"continuous\""), std::string("\"signal\": \"SIGTERM\""),
        std::string("\"checkpoint\": \"checkpoint.bin\""), std::string("\"duration_planned\": "),
        "\"steps\": " + std::to_string(c.engine.counters.steps) + ",",
        "\"events\": " + std::to_string(c.engine.counters.events) + ",",
        std::string("\"b_mle\": null"), std::string("no fit: interrupted"),
        std::string("\"energy_residual\": ")})
    EXPECT_NE(summary.find(want), std::string::npos) << want << " missing in\n" << summary;
  EXPECT_EQ(read_json_number(out + "/summary.json", "duration"), c.engine.state.t);
  for (const char* f : {"/timeseries.csv", "/catalog.csv"}) {
    const std::string text = read_file(out + f);
    ASSERT_FALSE(text.empty()) << f;
    EXPECT_EQ(text.back(), '\n') << f << " ends in a torn row";
  }
  EXPECT_LT(size_of(out + "/timeseries.csv"), size_of(straight() + "/timeseries.csv"));
  resume_and_compare(out);
}

INSTANTIATE_TEST_SUITE_P(Schemes, ContinuousResume, ::testing::ValuesIn(resume_cases()),
                         [](const ::testing::TestParamInfo<ResumeCase>& info) {
                           return info.param.name;
                         });

// SIGKILL gives no chance to save: the run resumes from its last periodic checkpoint and
// computes the rows after it again.
TEST(ContinuousResumeKill, SigkillResumesFromThePeriodicCheckpoint) {
  const ResumeCase c = resume_cases().front();
  test::TempDir tmp;
  const auto scene = with_src(c.scene);
  ASSERT_EQ(run_bkquake(run_args(scene, {"--out", tmp.file("straight")})).status, 0);
  const std::string out = tmp.file("out");
  const auto min_bytes = static_cast<std::uintmax_t>(
      0.6 * static_cast<double>(size_of(tmp.file("straight/timeseries.csv"))));
  const int status = test::run_and_signal_when(
      run_args(scene, {"--out", out}),
      [&] {
        return size_of(out + "/timeseries.csv") >= min_bytes && fs::exists(out + "/checkpoint.bin");
      },
      SIGKILL);
  ASSERT_EQ(status, 128 + SIGKILL);
  const auto r = run_bkquake(run_args(scene, {"--out", out, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto want = outputs_of(tmp.file("straight"));
  const auto got = outputs_of(out);
  ASSERT_EQ(want.size(), got.size());
  for (const auto& [name, bytes] : want) EXPECT_TRUE(got.at(name) == bytes) << name;
}

// A sampled file changed after the checkpoint is refused, and nothing is changed.
TEST(ContinuousResumeKill, TimeSeriesShorterThanItsCheckpointIsRefused) {
  const ResumeCase c = resume_cases().front();
  test::TempDir tmp;
  const auto scene = with_src(c.scene);
  const std::string out = tmp.file("out");
  ASSERT_EQ(test::run_and_signal_when(
                run_args(scene, {"--out", out}),
                [&] { return size_of(out + "/timeseries.csv") > 100000; }, SIGTERM),
            143);
  const std::string ts = out + "/timeseries.csv";
  fs::resize_file(ts, size_of(ts) / 2);
  const std::string catalog = read_file(out + "/catalog.csv");
  const auto r = run_bkquake(run_args(scene, {"--out", out, "--resume"}));
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("timeseries.csv"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(out + "/catalog.csv"), catalog) << "a refused resume changed the catalog";
  EXPECT_TRUE(CheckpointFiles(out).exist());
}

}  // namespace
}  // namespace bkq
