// Implementation of the fit table and JSON (see gr_report.hpp).
#include "app/gr_report.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <utility>

#include "core/format.hpp"

namespace bkq {

namespace {

std::string fixed(double x, int digits = 4) {
  if (!std::isfinite(x)) return format_real(x);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}
std::string pm(double b, double err) {
  return fixed(b) + " +/- " + fixed(err);
}
// Sets each key to its value as a fit number, in the order given.
Json& set_fit_numbers(Json& o, std::initializer_list<std::pair<const char*, double>> numbers) {
  for (const auto& [key, x] : numbers) o.set(key, fit_number(x));
  return o;
}
}  // namespace

static std::string two_laws_and_notes(const GrFit& f);

// Why the window's top is where it is, in words (GrFit::mu_max_reason).
static std::string top_reason_text(const std::string& r) {
  if (r == "gap") return "below a gap of empty bins";
  if (r == "rise") return "below a rise of the distribution (the bump of large events)";
  if (r == "departure") return "where the events above depart from the power law";
  if (r == "goodness of fit") return "lowered until the window passes the goodness-of-fit test";
  if (r == "end of data") return "at the largest event";
  return r;
}

Json power_law_json(const PowerLawFit& f, const std::string& measure) {
  Json o = Json::object(), ln = Json::object(), cut = Json::object();
  o.set("measure", measure).set("ok", f.ok);
  if (!f.ok) o.set("no_fit_reason", f.no_fit_reason);
  // value and err: the exponent and its block-bootstrap error (Fisher's when no bootstrap).
  const double err = std::isfinite(f.alpha_boot_err) ? f.alpha_boot_err : f.alpha_err;
  set_fit_numbers(o, {{"value", f.alpha},
                      {"err", err},
                      {"err_fisher", f.alpha_err},
                      {"x_min", f.x_min},
                      {"x_max", std::isinf(f.x_max) ? NAN : f.x_max},
                      {"p", f.p}});
  o.set("discrete", f.discrete)
      .set("x_min_auto", f.x_min_auto)
      .set("x_min_candidates", f.x_min_candidates)
      .set("x_max_reason", f.x_max_reason)
      .set("events", f.n_total)
      .set("n_in_range", f.n_tail)
      .set("ks_distance", fit_number(f.ks))
      .set("gof_sets", f.gof_sets)
      .set("boot_block", f.boot_block)
      .set("boot_tau_int", fit_number(f.boot_tau_int));
  set_fit_numbers(ln, {{"mu", f.lognormal_mu},
                       {"sigma", f.lognormal_sigma},
                       {"ratio", f.lognormal_ratio},
                       {"p", f.lognormal_p}});
  set_fit_numbers(cut, {{"alpha", f.cutoff_alpha},
                        {"lambda", f.cutoff_lambda},
                        {"ratio", f.cutoff_ratio},
                        {"p", f.cutoff_p}});
  o.set("vs_lognormal", ln).set("vs_cutoff", cut).set("notes", Json::strings(f.notes));
  return o;
}

std::string power_law_table(const PowerLawFit& f, const std::string& measure) {
  std::string t = "measure           " + measure + (f.discrete ? " (integer)" : "") + ", " +
                  std::to_string(f.n_total) + " events\n";
  if (!f.ok) return t + "tau               none: " + f.no_fit_reason + "\n";
  const double err = std::isfinite(f.alpha_boot_err) ? f.alpha_boot_err : f.alpha_err;
  t += "range             [" + fixed(f.x_min, 3) + ", " +
       (std::isinf(f.x_max) ? std::string("inf") : fixed(f.x_max, 3)) + "]  " +
       std::to_string(f.n_tail) + " events; x_min " +
       (f.x_min_auto ? "by KS distance over " + std::to_string(f.x_min_candidates) + " candidates"
                     : std::string("given")) +
       ", x_max " + f.x_max_reason + "\n";
  t += "tau (MLE)         " + pm(f.alpha, err) +
       " (block bootstrap; p(x) ~ x^-tau, Clauset et al. 2009), Fisher error " +
       fixed(f.alpha_err) + "\n";
  t += "goodness of fit   KS " + fixed(f.ks) + ", p = " + fixed(f.p, 2) + " (" +
       std::to_string(f.gof_sets) + " synthetic sets; p > 0.1: consistent with a power law)\n";
  t += "vs lognormal      Vuong ratio " + fixed(f.lognormal_ratio, 2) +
       ", p = " + fixed(f.lognormal_p, 3) + " (> 0 favours the power law)\n";
  t += "vs cut-off        2 ln(L_cut/L_pl) = " + fixed(f.cutoff_ratio, 2) +
       ", p = " + fixed(f.cutoff_p, 3) + " (lambda = " + format_real(f.cutoff_lambda) +
       "; small p: the cut-off fits better)\n";
  for (const auto& n : f.notes) t += "note: " + n + "\n";
  return t;
}

Json gr_fit_json(const GrFit& f) {
  Json two = Json::object(), excess = Json::object(), o = Json::object();
  two.set("ok", f.two_law_ok);
  if (!f.two_law_ok && !f.two_law_reason.empty()) two.set("reason", f.two_law_reason);
  set_fit_numbers(two, {{"b1", f.two_law_b1},
                        {"b2", f.two_law_b2},
                        {"mu_cross", f.two_law_mu_cross},
                        {"moment_cross", f.two_law_moment_cross},
                        {"ln_A1", f.two_law_ln_A1},
                        {"ln_A2", f.two_law_ln_A2},
                        {"mu_low", f.two_law_mu_low},
                        {"mu_high", f.two_law_mu_high}});
  excess.set("found", f.excess_found)
      .set("mu", fit_number(f.excess_found ? f.excess_mu : NAN))
      .set("observed", f.excess_observed)
      .set("expected", fit_number(f.excess_expected))
      .set("count", fit_number(f.excess_count));
  o.set("b_ok", f.b_ok);
  if (!f.b_ok) o.set("no_b_reason", f.no_b_reason);
  o.set("bin_width", fit_number(f.bin_width))
      .set("events", f.n_total)
      .set("mu_min", fit_number(f.mu_min))
      .set("mu_max", fit_number(f.mu_max))
      .set("window_auto", f.window_auto)
      .set("mu_max_auto", f.mu_max_auto)
      .set("truncated", f.truncated)
      .set("n_in_window", f.n_in_window)
      .set("mu_max_reason", f.mu_max_reason)
      .set("warnings", Json::strings(f.warnings));
  set_fit_numbers(o, {{"b_mle", f.b_mle},
                      {"b_mle_err", f.b_mle_err},
                      {"b_mle_sys_err", f.b_mle_sys_err},
                      {"b_mw", b_moment_magnitude(f.b_mle)},
                      {"b_mw_err", b_moment_magnitude(f.b_mle_err)},
                      {"b_mw_sys_err", b_moment_magnitude(f.b_mle_sys_err)}});
  o.set("sys_windows", f.sys_windows);
  set_fit_numbers(o, {{"b_mle_boot_err", f.b_mle_boot_err},
                      {"b_mw_boot_err", b_moment_magnitude(f.b_mle_boot_err)},
                      {"boot_tau_int", f.boot_tau_int}});
  o.set("boot_block", f.boot_block).set("boot_resamples", f.boot_resamples);
  o.set("boot_note", f.boot_note);
  set_fit_numbers(o, {{"b_aki", f.b_aki},
                      {"b_aki_err", f.b_aki_err},
                      {"b_lsq", f.b_lsq},
                      {"b_lsq_err", f.b_lsq_err}});
  if (!f.b_lsq_reason.empty()) o.set("b_lsq_reason", f.b_lsq_reason);
  set_fit_numbers(o, {{"ln_A", f.ln_A}, {"ks_distance", f.ks_distance}})
      .set("two_power_law", two)
      .set("excess", excess)
      .set("notes", Json::strings(f.notes));
  return o;
}

Json class_counts_json(const EventClassCounts& c) {
  Json o = Json::object();
  o.set("single_block", c.single_block)
      .set("localised", c.localised)
      .set("delocalised", c.delocalised)
      .set("single_block_fraction", fit_number(c.fraction(EventClass::single_block)))
      .set("localised_fraction", fit_number(c.fraction(EventClass::localised)))
      .set("delocalised_fraction", fit_number(c.fraction(EventClass::delocalised)));
  return o;
}

std::string gr_fit_table(const GrFit& f) {
  std::string t;
  t += "events            " + std::to_string(f.n_total) + "\n";
  t += "window            [" + fixed(f.mu_min, 3) + ", " + fixed(f.mu_max, 3) + ")  " +
       std::to_string(f.n_in_window) + " events, " +
       (f.window_auto ? (f.mu_max_auto ? "mu_min and mu_max automatic" : "mu_min automatic")
                      : (f.mu_max_auto ? "mu_min given, mu_max automatic" : "mu_min given")) +
       (f.truncated ? ", truncated at mu_max" : "") + "\n";
  t += "bin width         " + fixed(f.bin_width, 3) + "\n";
  if (!f.mu_max_reason.empty()) t += "window ends       " + top_reason_text(f.mu_max_reason) + "\n";
  for (const auto& w : f.warnings) t += "warning: " + w + "\n";
  if (!f.b_ok) {
    t += "b                 none: " + f.no_b_reason + "\n";
    t += two_laws_and_notes(f);
    return t;
  }
  t += "b  binned MLE     " + pm(f.b_mle, f.b_mle_err) + " (stat.) +/- " + fixed(f.b_mle_sys_err) +
       " (sys.)   per unit of mu = ln M (Tinti & Mulargia 1987; Shi & "
       "Bolt error; sys.: half the range of b over " +
       std::to_string(f.sys_windows) + " nearby windows)\n";
  t += "b_mw              " + pm(b_moment_magnitude(f.b_mle), b_moment_magnitude(f.b_mle_err)) +
       " (stat.) +/- " + fixed(b_moment_magnitude(f.b_mle_sys_err)) +
       " (sys.)   per unit of Mw = (2/3) log10 M + const (= 1.5 b)\n";
  if (std::isfinite(f.b_mle_boot_err))
    t += "b  stat. error    " + fixed(f.b_mle_boot_err) +
         " (block bootstrap: correlated events; blocks of " + std::to_string(f.boot_block) +
         " events, " + std::to_string(f.boot_resamples) + " resamples), " + fixed(f.b_mle_err) +
         " (Shi & Bolt: independent events)\n";
  else
    t += "b  stat. error    " + fixed(f.b_mle_err) + " (Shi & Bolt: independent events; " +
         f.boot_note + ")\n";
  if (std::isnan(f.b_aki))
    t += "b  unbinned MLE   n/a (needs the magnitudes themselves, not a histogram)\n";
  else
    t += "b  unbinned MLE   " + pm(f.b_aki, f.b_aki_err) + "   (Aki 1965)\n";
  if (std::isfinite(f.b_lsq))
    t += "b  least squares  " + pm(f.b_lsq, f.b_lsq_err) + "   (slope of ln R, weights R)\n";
  else
    t += "b  least squares  none: " + f.b_lsq_reason + "\n";
  t += "KS distance       " + fixed(f.ks_distance) + "\n";
  return t + two_laws_and_notes(f);
}

// The lines after the b estimates: two power laws, excess, notes.
static std::string two_laws_and_notes(const GrFit& f) {
  std::string t;
  if (f.two_law_ok)
    t += "two power laws    b1 = " + fixed(f.two_law_b1) + ", b2 = " + fixed(f.two_law_b2) +
         ", crossover mu~ = " + fixed(f.two_law_mu_cross, 3) +
         " (M~ = " + fixed(f.two_law_moment_cross, 3) + ")   (thesis eq. 2.10)\n";
  else
    t += "two power laws    none: " +
         (f.two_law_reason.empty() ? std::string("not fitted") : f.two_law_reason) + "\n";
  if (!f.b_ok)
    t += "large-event excess not tested (no fitted line)\n";
  else if (f.excess_found)
    t += "large-event excess above mu = " + fixed(f.excess_mu, 3) + ": " +
         std::to_string(f.excess_observed) + " observed, " + fixed(f.excess_expected, 1) +
         " expected; up to " + fixed(f.excess_count, 1) + " events beyond the line\n";
  else
    t += "large-event excess none (> 2 sigma Poisson)\n";
  for (const auto& n : f.notes) t += "note: " + n + "\n";
  return t;
}

std::string class_counts_table(const EventClassCounts& c) {
  auto line = [&](const char* name, std::int64_t k, EventClass e) {
    return std::string(name) + std::to_string(k) + " (" + fixed(100 * c.fraction(e), 1) + " %)\n";
  };
  return line("single-block      ", c.single_block, EventClass::single_block) +
         line("localised         ", c.localised, EventClass::localised) +
         line("delocalised       ", c.delocalised, EventClass::delocalised);
}

}  // namespace bkq
