// Runs side by side; see compare.hpp.
#include "app/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/catalog_reader.hpp"
#include "io/ini.hpp"
#include "io/json.hpp"
#include "stats/seismicity/moments.hpp"

namespace bkq {

namespace {

namespace fs = std::filesystem;

// A folder: false where the name cannot be one (too long, say) instead of a filesystem_error.
bool is_folder(const std::string& name) {
  std::error_code ec;
  return fs::is_directory(name, ec);
}

fs::path catalog_of(const std::string& run) {
  const fs::path dir(run);
  if (!is_folder(run))
    throw Error("compare: " + quote_printable(run) +
                ": no such folder; allowed: run folders holding catalog.csv or catalog.h5");
  for (const char* name : {"catalog.csv", "catalog.h5"})
    if (fs::is_regular_file(dir / name)) return dir / name;
  throw Error("compare: " + quote_printable(run) +
              ": holds no catalog.csv or catalog.h5 (a run with output.catalog = none keeps no "
              "catalogue)");
}

std::string window_text(const CompareRequest& req) {
  std::string w = req.from ? format_real(*req.from) + " < load" : "load";
  if (req.to) w += " <= " + format_real(*req.to);
  return req.from || req.to ? w : "all events";
}

// The members of a RUN_DIR argument: the folder, or a group's comma-separated folders.
std::vector<std::string> members_of(const std::string& arg) {
  if (arg.find(',') == std::string::npos || is_folder(arg)) return {arg};
  std::vector<std::string> m;
  for (std::size_t p = 0; p <= arg.size();) {
    const std::size_t comma = std::min(arg.find(',', p), arg.size());
    if (comma == p)
      throw Error("compare: " + quote_printable(arg) +
                  ": an empty folder name in a group; allowed: folders separated by single "
                  "commas");
    m.push_back(arg.substr(p, comma - p));
    p = comma + 1;
  }
  return m;
}

std::string name_of(const std::string& folder) {
  std::string name = fs::path(folder).lexically_normal().filename().string();
  if (name.empty()) name = fs::path(folder).lexically_normal().parent_path().filename().string();
  return name;
}

// One member's events in the window: magnitudes (appended to the run's), and their loads for
// the large-event pass.
void read_window(const CompareRequest& req, const std::string& folder, CompareRun& run,
                 std::vector<double>& loads) {
  CatalogReader reader(catalog_of(folder));
  reader.set_growing();  // a run still writing: its last, unfinished row ends the reading
  if (!reader.has_load())
    throw Error("compare: " + reader.file() +
                " has no load column: the window and the recurrence need the catalogue's clock");
  CatalogEvent e;
  bool first = true;
  double first_load = 0, last_load = 0;
  while (reader.next(e)) {
    if (first) first_load = e.load;
    first = false;
    last_load = e.load;
    if ((req.from && !(e.load > *req.from)) || (req.to && !(e.load <= *req.to))) continue;
    run.mu.push_back(std::log(e.moment));
    loads.push_back(e.load);
  }
  const auto read = static_cast<std::size_t>(reader.events_read());
  if (loads.empty())
    throw Error("compare: " + folder + " has no events with " + window_text(req) + " (" +
                std::to_string(read) + " events, load " + format_real(first_load) + " to " +
                format_real(last_load) +
                "); allowed: --from and --to that hold events of every run");
  run.first_load = run.events_read == 0 ? first_load : std::min(run.first_load, first_load);
  run.last_load = run.events_read == 0 ? last_load : std::max(run.last_load, last_load);
  run.events_read += read;
}

std::optional<CompareAftershocks> aftershocks_of(const std::string& folder) {
  const fs::path json = fs::path(folder) / "seismicity" / "seismicity.json";
  if (!fs::is_regular_file(json)) return std::nullopt;
  const std::string o = json.string(), t = read_text_file(o, "seismicity result");
  CompareAftershocks a;
  a.rule = json_string_at(t, "mainshocks.rule", o).value_or("");
  a.mainshocks = json_number_at(t, "mainshocks.count", o).value_or(0);
  a.p = json_number_at(t, "omori.p", o);  // null without an excess over the background
  a.excess = a.p.has_value();
  a.p_err = json_number_at(t, "omori.p_err", o);
  a.c = json_number_at(t, "omori.c", o);
  a.c_err = json_number_at(t, "omori.c_err", o);
  a.k = json_number_at(t, "omori.K", o);
  a.k_err = json_number_at(t, "omori.K_err", o);
  a.aftershocks = json_number_at(t, "omori.aftershocks", o);
  a.duration = json_number_at(t, "bath.window", o);
  a.note = json_string_at(t, "omori.note", o).value_or("");
  return a;
}

std::string num(double x) {
  if (!std::isfinite(x)) return "–";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

std::string num_err(const std::optional<double>& x, const std::optional<double>& err) {
  if (!x) return "–";
  return err && std::isfinite(*err) ? num(*x) + " ± " + num(*err) : num(*x);
}

double mean_of(const std::vector<double>& x) {
  double s = 0;
  for (const double v : x) s += v;
  return x.empty() ? NAN : s / static_cast<double>(x.size());
}

}  // namespace

CompareReport compare_runs(const CompareRequest& req) {
  if (req.runs.size() < 2)
    throw Error("compare: " + std::to_string(req.runs.size()) +
                " run folder(s) given; allowed: two or more (the first is the reference)");
  if (req.from && req.to && !(*req.from < *req.to))
    throw Error("compare: --from = " + format_real(*req.from) + " is not below --to = " +
                format_real(*req.to) + "; allowed: a window from < load <= to");
  if (!req.mu_large && !(req.large_quantile > 0 && req.large_quantile < 1))
    throw Error("compare: --large-quantile = " + format_real(req.large_quantile) +
                "; allowed: (0, 1)");
  CompareReport rep;
  // loads[i][m]: the window's loads of member m of run i, in the order of its magnitudes.
  std::vector<std::vector<std::vector<double>>> loads(req.runs.size());
  for (std::size_t i = 0; i < req.runs.size(); ++i) {
    CompareRun run;
    run.folder = req.runs[i];
    run.members = members_of(run.folder);
    run.name = name_of(run.members[0]);
    if (run.members.size() > 1) run.name += ",… (" + std::to_string(run.members.size()) + " runs)";
    loads[i].resize(run.members.size());
    for (std::size_t m = 0; m < run.members.size(); ++m)
      read_window(req, run.members[m], run, loads[i][m]);
    if (run.members.size() == 1) run.aftershocks = aftershocks_of(run.folder);
    rep.runs.push_back(std::move(run));
  }
  if (req.mu_large) {
    rep.mu_large = *req.mu_large;
    rep.large_rule = "mu >= " + format_real(rep.mu_large) + " (--mu-large)";
  } else {
    rep.mu_large = quantile(rep.runs[0].mu, req.large_quantile);
    rep.large_rule = "mu >= " + num(rep.mu_large) + ", the " + num(req.large_quantile) +
                     " quantile of " + rep.runs[0].name + "'s window";
  }
  for (std::size_t i = 0; i < rep.runs.size(); ++i) {
    CompareRun& r = rep.runs[i];
    std::size_t k = 0;  // the run's magnitudes follow its members' loads in order
    r.large_times.resize(r.members.size());
    seis::Moments per_run;
    for (std::size_t m = 0; m < r.members.size(); ++m) {
      for (const double load : loads[i][m])
        if (r.mu[k++] >= rep.mu_large) r.large_times[m].push_back(load);
      per_run.add(static_cast<double>(r.large_times[m].size()));
    }
    r.recurrence = recurrence_of_runs(r.large_times);
    r.large_mean = per_run.mean();
    r.large_sd = r.members.size() > 1 ? std::sqrt(per_run.variance()) : NAN;
  }
  const CompareRun& ref = rep.runs[0];
  const std::vector<double> ref_dt = intervals_of_runs(ref.large_times);
  for (CompareRun& r : rep.runs) {
    r.ks_mu = ks_distance(ref.mu, r.mu);
    r.ks_mu_crit = ks_critical_5pct(ref.mu.size(), r.mu.size());
    const std::vector<double> dt = intervals_of_runs(r.large_times);
    r.ks_intervals = ks_distance(ref_dt, dt);
    r.ks_intervals_crit = ks_critical_5pct(ref_dt.size(), dt.size());
  }
  return rep;
}

void print_compare(const CompareReport& rep, const CompareRequest& req, std::ostream& out) {
  const CompareRun& ref = rep.runs[0];
  out << "compare: " << rep.runs.size() << " runs against " << ref.name << ", window "
      << window_text(req) << " (load: the catalogue's clock; V_pl t for rate-and-state)\n";
  out << "KS of " << rep.runs[1].name << " to " << ref.name
      << ", doubled: " << num(2 * rep.runs[1].ks_mu)
      << " (the yardstick when the first two runs are two starts of one scene)\n\n";
  out << "Magnitudes (mu = ln M) in the window:\n\n"
      << "| run | events | in window | load of the last event | mean mu | KS to " << ref.name
      << " | 5 % critical |\n|---|---|---|---|---|---|---|\n";
  for (const CompareRun& r : rep.runs)
    out << "| " << r.name << " | " << r.events_read << " | " << r.mu.size() << " | "
        << num(r.last_load) << " | " << num(mean_of(r.mu)) << " | " << num(r.ks_mu) << " | "
        << num(r.ks_mu_crit) << " |\n";
  out << "\nRecurrence of the large events (" << rep.large_rule
      << "), intervals in load; errors: count sqrt(n), mean s/sqrt(n), COV delta method:\n\n"
      << "| run | large events | a run (mean ± s.d.) | mean interval | COV | KS of intervals to "
      << ref.name << " | 5 % critical |\n|---|---|---|---|---|---|---|\n";
  for (const CompareRun& r : rep.runs) {
    const Recurrence& c = r.recurrence;
    out << "| " << r.name << " | " << c.count << " ± " << num(c.count_err) << " | "
        << (r.members.size() > 1 ? num(r.large_mean) + " ± " + num(r.large_sd) : "–") << " | "
        << num_err(c.mean, c.mean_err) << " | " << num_err(c.cov, c.cov_err) << " | "
        << num(r.ks_intervals) << " | " << num(r.ks_intervals_crit) << " |\n";
  }
  out << "\nAftershocks (each run's seismicity/seismicity.json, over its whole catalogue; "
         "times in load; duration: until the Omori term falls to the background):\n\n"
      << "| run | mainshocks | Omori p | c | K | aftershocks above background | duration |\n"
      << "|---|---|---|---|---|---|---|\n";
  std::string rules;
  for (const CompareRun& r : rep.runs) {
    out << "| " << r.name << " | ";
    if (r.members.size() > 1) {
      out << "a group: bkquake seismicity fits each run alone (compare them one by one) | | | | "
             "| |\n";
      continue;
    }
    if (!r.aftershocks) {
      out << "no seismicity/seismicity.json (run bkquake seismicity " << r.folder
          << ") | | | | | |\n";
      continue;
    }
    const CompareAftershocks& a = *r.aftershocks;
    out << num(a.mainshocks) << " | " << (a.excess ? num_err(a.p, a.p_err) : "no excess: " + a.note)
        << " | " << num_err(a.c, a.c_err) << " | " << num_err(a.k, a.k_err) << " | "
        << (a.aftershocks ? num(*a.aftershocks) : "–") << " | "
        << (a.duration ? num(*a.duration) : "–") << " |\n";
    if (rules.find(a.rule) == std::string::npos) rules += (rules.empty() ? "" : "; ") + a.rule;
  }
  if (!rules.empty()) out << "\nmainshocks: " << rules << "\n";
}

}  // namespace bkq
