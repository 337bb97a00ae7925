// output.event_slip: event_slip.csv holds the slip of every block of each event with
// mu >= MU, the slips of an event sum to its moment in catalog.csv, only those events are
// there, and a run killed (SIGKILL) and resumed writes the bytes of one that never stopped.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "cli_helpers.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;
using test::read_file;
using test::run_args;
using test::run_bkquake;

const std::vector<std::string> kScene = {
    "--set", "model.blocks=50",          "--set",  "run.events=100000",
    "--set", "run.transient_events=100", "--set",  "run.checkpoint_events=10000",
    "--set", "output.event_slip=0",      "--quiet"};

std::uintmax_t size_of(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t n = fs::file_size(path, ec);
  return ec ? 0 : n;
}

TEST(EventSlip, SlipsSumToTheMomentAndAKilledRunResumesTheSameBytes) {
  test::TempDir tmp;
  const std::string straight = tmp.file("straight");
  auto r = run_bkquake(run_args(kScene, {"--out", straight}));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string slips = read_file(straight + "/event_slip.csv");
  ASSERT_EQ(slips.rfind("event,block,slip\n", 0), 0u);

  // Every event with mu >= 0 is there, and its slips sum to its moment.
  std::map<long long, double> sum;
  std::istringstream in(slips.substr(slips.find('\n') + 1));
  for (std::string line; std::getline(in, line);) {
    long long event = 0;
    int block = -1;
    double slip = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lld,%d,%lf", &event, &block, &slip), 3) << line;
    EXPECT_GE(block, 0);
    EXPECT_LT(block, 50);
    sum[event] += slip;
  }
  std::istringstream cat(read_file(straight + "/catalog.csv"));
  std::string line;
  std::getline(cat, line);
  std::size_t large = 0;
  while (std::getline(cat, line)) {
    long long event = 0;
    double load = 0, moment = 0, mu = 0;
    int trigger = 0, blocks = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lld,%lf,%d,%d,%lf,%lf", &event, &load, &trigger, &blocks,
                          &moment, &mu),
              6);
    if (mu < 0) {
      EXPECT_EQ(sum.count(event), 0u) << event;
      continue;
    }
    ++large;
    ASSERT_EQ(sum.count(event), 1u) << event;
    EXPECT_NEAR(sum[event], moment, 1e-9 * moment) << event;
  }
  EXPECT_GT(large, 100u);
  EXPECT_EQ(sum.size(), large);

  // Killed after a periodic checkpoint, with rows past it on disk, then resumed.
  const std::string out = tmp.file("killed");
  const auto min_bytes = size_of(straight + "/catalog.csv") * 6 / 10;
  const int status = test::run_and_signal_when(
      run_args(kScene, {"--out", out}),
      [&] {
        return fs::exists(out + "/checkpoint.bin") && size_of(out + "/catalog.csv") >= min_bytes;
      },
      SIGKILL, tmp.file("log.txt"));
  ASSERT_EQ(status, 128 + SIGKILL) << read_file(tmp.file("log.txt"));
  ASSERT_LT(size_of(out + "/event_slip.csv"), slips.size());
  r = run_bkquake(run_args(kScene, {"--out", out, "--resume"}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(read_file(out + "/event_slip.csv") == slips) << "event_slip.csv differs";
  EXPECT_TRUE(read_file(out + "/catalog.csv") == read_file(straight + "/catalog.csv"));
}

TEST(EventSlip, IsRefusedWhereItDoesNotApplyAndOffByDefault) {
  test::TempDir tmp;
  auto r = run_bkquake({"run", "--set", "drive.mode=continuous", "--set", "output.event_slip=1",
                        "--out", tmp.file("c")});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(
      r.err.find(
          "--set output.event_slip=1 does not apply to this scene: it needs drive.mode = events"),
      std::string::npos)
      << r.err;
  r = run_bkquake({"run", "--set", "output.event_slip=off", "--out", tmp.file("d")});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("output.event_slip: expected a value in [-50, 50] or none, got 'off'"),
            std::string::npos)
      << r.err;
  r = run_bkquake({"run", "--set", "model.blocks=10", "--set", "run.events=100", "--out",
                   tmp.file("e"), "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(tmp.path() / "e" / "event_slip.csv"));
}

}  // namespace
}  // namespace bkq
