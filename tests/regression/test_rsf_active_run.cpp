// The event-driven rate-and-state run with rsf.event_integration = active
// (engine/rsf_active.hpp): a killed and resumed run writes the bytes of the run never stopped.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"

namespace bkq {
namespace {

using test::read_file;
using test::run_bkquake;

// The shipped event-driven chain with its rough D_c (the active-block integration needs
// per-block values), each event on its active blocks, stopped by
// SIGTERM after its first checkpoint and resumed: the catalogue and histogram of the run
// never stopped, and its count of active blocks over the steps.
TEST(RsfActiveRun, KilledAndResumedGivesTheSameBytes) {
  test::TempDir tmp;
  const std::string scenes = std::string(BKQUAKE_SOURCE_DIR) + "/data/scenes/rsf/";
  const std::string scene = scenes + "chain-events.ini",
                    rough = scenes + "chain-events-rough-blocks.csv";
  const auto args = [&](const std::string& out, std::vector<std::string> more) {
    std::vector<std::string> a = {"run",
                                  scene,
                                  "--quiet",
                                  "--set",
                                  "rsf.pattern=uniform",
                                  "--set",
                                  "rsf.blocks=" + rough,
                                  "--set",
                                  "rsf.event_integration=active",
                                  "--set",
                                  "run.events=400",
                                  "--set",
                                  "run.transient_events=20",
                                  "--set",
                                  "run.checkpoint_events=50",
                                  "--out",
                                  out};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  const auto whole = run_bkquake(args(tmp.file("whole"), {}));
  ASSERT_EQ(whole.status, 0) << whole.err;
  EXPECT_NE(read_file(tmp.file("whole/summary.json")).find("\"event_integration\": \"active\""),
            std::string::npos);
  const std::string checkpoint = tmp.file("cut/checkpoint.bin");
  const auto cut = test::run_bkquake_until([&] { return std::filesystem::exists(checkpoint); },
                                           args(tmp.file("cut"), {}));
  ASSERT_EQ(cut.status, 143) << cut.err;
  const auto resumed = run_bkquake(args(tmp.file("cut"), {"--resume"}));
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  for (const char* f : {"catalog.csv", "histogram.csv"})
    EXPECT_EQ(read_file(tmp.file(std::string("cut/") + f)),
              read_file(tmp.file(std::string("whole/") + f)))
        << f;
  EXPECT_FALSE(std::filesystem::exists(checkpoint));
  // The active blocks summed over the steps go through the checkpoint too.
  const auto counter = [&](const std::string& dir) {
    const std::string text = read_file(tmp.file(dir + "/summary.json"));
    const std::size_t at = text.find("\"active_block_steps\": ");
    return at == std::string::npos ? std::string() : text.substr(at, text.find(',', at) - at);
  };
  EXPECT_FALSE(counter("whole").empty());
  EXPECT_EQ(counter("cut"), counter("whole"));
}

}  // namespace
}  // namespace bkq
