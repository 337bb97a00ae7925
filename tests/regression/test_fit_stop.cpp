// SIGTERM once an event run's last event is written: the run is then in its
// closing phase (the fit, the histogram, the summary). Either the signal lands before the last
// stop check, and the run stops as after an event: exit 143, a checkpoint with every event
// done, a summary marked interrupted without a fit, and --resume fits and finishes; or it
// lands after it and the run has finished (exit 0, a finished summary with its fit). Nothing
// else is allowed. The closing fit now takes well under a millisecond, so which of the two
// happens is the machine's timing: the test tries a few times and checks every outcome. The
// fit's own cancellation is tested directly in test_stats_fit_bounds.cpp.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "../cli_helpers.hpp"
#include "io/checkpoint.hpp"
#include "io/run_folder.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

// A finished run's fit: a b, or the reason no window passes (at bin width 0.01 the
// few-block moments leave no window that passes the goodness-of-fit test).
bool fitted(const std::string& summary) {
  return summary.find("\"b_mle\": 0.") != std::string::npos ||
         summary.find("\"fit_error\": \"no acceptable fit window: ") != std::string::npos;
}

TEST(FitStop, SigtermAfterTheLastEventStopsResumablyOrFinishes) {
  int stopped_runs = 0;
  for (int attempt = 0; attempt < 4 && stopped_runs == 0; ++attempt) {
    test::TempDir dir;
    const std::string out = dir.file("out");
    const std::vector<std::string> args = {"run",
                                           "--set",
                                           "model.blocks=50",
                                           "--set",
                                           "run.events=60000",
                                           "--set",
                                           "run.transient_events=100",
                                           "--set",
                                           "stats.bin_width=0.01",
                                           "--set",
                                           "run.checkpoint_events=0",
                                           "--set",
                                           "run.checkpoint_seconds=0",
                                           "--out",
                                           out,
                                           "--quiet"};
    // The catalog is flushed at the end of the events, before the fit, so 60000 lines are
    // there only once every event is.
    std::uintmax_t seen = 0;
    bool complete = false;
    const auto all_events_written = [&] {
      std::error_code ec;
      const std::uintmax_t size = fs::file_size(out + "/catalog.csv", ec);
      if (ec || size == seen) return complete;
      seen = size;
      const std::string text = test::read_file(out + "/catalog.csv");
      complete = std::count(text.begin(), text.end(), '\n') >= 60000;
      return complete;
    };
    const int status =
        test::run_and_signal_when(args, all_events_written, SIGTERM, dir.file("log.txt"));
    const std::string log = test::read_file(dir.file("log.txt"));
    ASSERT_TRUE(status == 143 || status == 0) << status << "\n" << log;
    if (status == 0) {
      // The signal came after the last stop check: a finished run with its fit.
      EXPECT_EQ(run_status(out), RunStatus::Finished);
      EXPECT_TRUE(fitted(test::read_file(out + "/summary.json")));
      continue;
    }
    ++stopped_runs;
    EXPECT_NE(log.find("stopped by SIGTERM after 60000 of 60000 events"), std::string::npos) << log;
    EXPECT_EQ(run_status(out), RunStatus::Interrupted);
    const std::string stopped = test::read_file(out + "/summary.json");
    EXPECT_NE(stopped.find("\"events\": 60000,"), std::string::npos) << stopped;
    EXPECT_NE(stopped.find("\"b_mle\": null"), std::string::npos) << stopped;
    EXPECT_NE(stopped.find("no fit: interrupted"), std::string::npos) << stopped;
    EXPECT_EQ(CheckpointFiles(out).read().progress.events_done, 60000);

    std::vector<std::string> resume = args;
    resume.push_back("--resume");
    const auto r = test::run_bkquake(resume);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string summary = test::read_file(out + "/summary.json");
    EXPECT_NE(summary.find("\"resumes\": 1"), std::string::npos) << summary;
    EXPECT_TRUE(fitted(summary)) << summary;
    EXPECT_EQ(run_status(out), RunStatus::Finished);
  }
  RecordProperty("stopped_runs", stopped_runs);
}

}  // namespace
}  // namespace bkq
