// `bkquake compare RUN_DIR RUN_DIR...`: parses the arguments and calls app/compare.hpp.
#include <iostream>

#include "app/compare.hpp"
#include "cli/commands.hpp"

namespace bkq {

namespace {

int cmd_compare(const Args& args) {
  CompareRequest req;
  req.runs = args.operands();
  if (args.has("from")) req.from = args.real("from");
  if (args.has("to")) req.to = args.real("to");
  if (args.has("mu-large")) req.mu_large = args.real("mu-large");
  req.large_quantile = args.real("large-quantile");
  print_compare(compare_runs(req), req, std::cout);
  return 0;
}

}  // namespace

Command compare_command_row() {
  return {
      "compare",
      "runs side by side: magnitudes, large-event recurrence, aftershocks",
      "RUN_DIR RUN_DIR...",
      -1,
      "Sets runs side by side, each against the first: the Kolmogorov-Smirnov distance\n"
      "between the magnitude distributions of the events in a window of the catalogue's\n"
      "clock (load), the recurrence of the large events (count, mean interval, COV, the\n"
      "KS distance between the interval distributions) and the Omori-Utsu aftershock fit\n"
      "that bkquake seismicity wrote into each run's seismicity/seismicity.json. A\n"
      "RUN_DIR may be a group, folders separated by commas (run1,run2,run3): several\n"
      "starts of one scene pooled, their large events' intervals taken within each run.\n"
      "Prints Markdown tables; writes nothing.\n",
      {opt::real("from", "LOAD", "window: events with load > LOAD (default: from the start)"),
       opt::real("to", "LOAD", "window: events with load <= LOAD (default: to the end)"),
       opt::real("mu-large", "MU",
                 "large events: mu = ln M >= MU (default: from --large-quantile)"),
       opt::real("large-quantile", "Q",
                 "large events: mu at or above the Q quantile of the first run's window", "0.99")},
      cmd_compare};
}

}  // namespace bkq
