// `bkquake compare RUN_DIR RUN_DIR...`: two or more runs side by side, each against the first
// (the reference): the magnitude distribution of the events in a window of the catalogue's
// clock (load) by its Kolmogorov-Smirnov distance, the recurrence of the large events (count,
// mean interval, COV, and the KS distance between the interval distributions), and the
// aftershock rate that `bkquake seismicity` wrote into each run's seismicity/seismicity.json
// (Omori-Utsu p, c, K, the excess count, the sequence duration). A RUN_DIR argument that is
// no folder but a comma-separated list of folders is a group: several starts of one scene
// pooled (their magnitudes together, the large events' intervals within each run, the large
// events' count summed and its spread from run to run). Reads only: the runs' folders are not
// written.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stats/catalog_compare.hpp"

namespace bkq {

struct CompareRequest {
  std::vector<std::string> runs;   // run folders (catalog.csv or catalog.h5 in each) or groups
                                   // of them (folders separated by commas), >= 2
  std::optional<double> from, to;  // the window: from < load <= to (default: all events)
  std::optional<double> mu_large;  // large events: mu >= mu_large ...
  double large_quantile = 0.99;    // ... else mu at this quantile of the first run's window
};

// What seismicity.json says of a run's aftershocks; absent without the file.
struct CompareAftershocks {
  std::string rule;  // the mainshock rule
  double mainshocks = 0;
  bool excess = false;
  std::optional<double> p, p_err, c, c_err, k, k_err, aftershocks, duration;
  std::string note;
};

struct CompareRun {
  std::string name, folder;          // folder: the argument (a group: its list)
  std::vector<std::string> members;  // the run folders (one, or a group's)
  std::size_t events_read = 0;
  std::vector<double> mu;                        // magnitudes in the window (a group's pooled)
  std::vector<std::vector<double>> large_times;  // load of the large events, by member
  double first_load = 0, last_load = 0;
  Recurrence recurrence;
  double large_mean = 0, large_sd = 0;  // a group's large events per run: mean, sample s.d.
  double ks_mu = 0, ks_mu_crit = 0;     // to the first run
  double ks_intervals = 0, ks_intervals_crit = 0;  // the large events' intervals, to the first
  std::optional<CompareAftershocks> aftershocks;
};

struct CompareReport {
  std::vector<CompareRun> runs;
  double mu_large = 0;
  std::string large_rule;
};

// bkq::Error naming the value for fewer than two runs, a missing folder or catalogue, a window
// with from >= to, a quantile outside (0, 1), or a run without events in the window.
CompareReport compare_runs(const CompareRequest& req);

// The report as three Markdown tables (magnitudes, recurrence, aftershocks).
void print_compare(const CompareReport& report, const CompareRequest& req, std::ostream& out);

}  // namespace bkq
