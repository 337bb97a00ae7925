// Implementation of sweep files (see sweep_file.hpp).
#include "io/sweep_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/ini.hpp"

namespace bkq {

namespace {

std::string trim_spaces(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto at = s.find(sep, start);
    parts.push_back(
        trim_spaces(s.substr(start, at == std::string::npos ? std::string::npos : at - start)));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

double range_number(const std::string& key, const std::string& text, const std::string& part) {
  char* end = nullptr;
  const double x = std::strtod(part.c_str(), &end);
  if (part.empty() || *end != '\0' || !std::isfinite(x))
    throw Error(key + " = " + text + ": '" + part +
                "' is not a number (ranges are lo:hi:count or log:lo:hi:count)");
  return x;
}

int range_count(const std::string& key, const std::string& text, const std::string& part) {
  char* end = nullptr;
  const long n = std::strtol(part.c_str(), &end, 10);
  if (part.empty() || *end != '\0' || n < 1 || n > static_cast<long>(kMaxSweepPoints))
    throw Error(key + " = " + text + ": count '" + part + "' must be an integer in [1, " +
                std::to_string(kMaxSweepPoints) + "]");
  return static_cast<int>(n);
}

}  // namespace

std::vector<std::string> expand_sweep_values(const std::string& key, const std::string& text) {
  const std::string t = trim_spaces(text);
  if (t.empty()) throw Error(key + ": empty list of values to sweep");
  if (t.find(':') == std::string::npos) {
    std::vector<std::string> values = split(t, ',');
    for (const auto& v : values)
      if (v.empty()) throw Error(key + " = " + text + ": empty entry in the list of values");
    return values;
  }
  std::vector<std::string> parts = split(t, ':');
  const bool log = parts.front() == "log";
  if (log) parts.erase(parts.begin());
  if (parts.size() != 3)
    throw Error(key + " = " + text + ": a range is lo:hi:count or log:lo:hi:count");
  const double lo = range_number(key, text, parts[0]);
  const double hi = range_number(key, text, parts[1]);
  const int n = range_count(key, text, parts[2]);
  if (log && !(lo > 0 && hi > 0))
    throw Error(key + " = " + text + ": a log range needs lo > 0 and hi > 0");
  if (n == 1 && lo != hi) throw Error(key + " = " + text + ": a range with count 1 needs lo = hi");
  std::vector<std::string> values;
  for (int i = 0; i < n; ++i) {
    // Both ends exactly as written; the points between evenly spaced (in log for log:).
    const double f = n == 1 ? 0.0 : static_cast<double>(i) / (n - 1);
    double x =
        log ? std::exp(std::log(lo) + f * (std::log(hi) - std::log(lo))) : lo + f * (hi - lo);
    if (i == 0) x = lo;
    if (i == n - 1) x = hi;
    values.push_back(format_real(x));
  }
  return values;
}

SweepSpec read_sweep_file(const std::string& path, const std::vector<std::string>& overrides) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_sweep(read_text_file(path, "sweep file"), path, dir, overrides);
}

SweepSpec parse_sweep(const std::string& text, const std::string& origin,
                      const std::string& base_dir, const std::vector<std::string>& overrides) {
  SweepSpec spec;
  spec.origin = origin;
  spec.text = text;
  const std::string where = " (in " + origin + ")";
  std::string scene_file;
  std::vector<IniEntry> sets;
  std::set<std::string> seen;
  const std::vector<IniEntry> entries = parse_ini(text, "in " + origin);
  // Whether the lists are zipped, known before any list is expanded (see [vary] below).
  const bool zipped = std::any_of(entries.begin(), entries.end(), [](const IniEntry& e) {
    return e.key == "sweep.combine" && e.value == "zip";
  });
  for (const auto& [key, value] : entries) {
    if (!seen.insert(key).second) throw Error(key + ": given more than once" + where);
    const auto dot = key.find('.');
    const std::string section = key.substr(0, dot);
    const std::string name = dot == std::string::npos ? "" : key.substr(dot + 1);
    if (section == "sweep") {
      if (name == "scene") {
        scene_file = value;
      } else if (name == "combine") {
        if (value == "product")
          spec.combine = SweepCombine::Product;
        else if (value == "zip")
          spec.combine = SweepCombine::Zip;
        else
          throw Error("sweep.combine = " + value + ": expected product|zip" + where);
      } else if (name == "replicas") {
        char* end = nullptr;
        const long r = std::strtol(value.c_str(), &end, 10);
        if (value.empty() || *end != '\0' || r < 1 || r > 100000)
          throw Error("sweep.replicas = " + value + ": expected an integer in [1, 100000]" + where);
        spec.replicas = static_cast<int>(r);
      } else if (name == "collect") {
        spec.keep_catalog = spec.keep_histogram = false;
        for (const auto& item : split(value, ',')) {
          if (item == "catalog")
            spec.keep_catalog = true;
          else if (item == "histogram")
            spec.keep_histogram = true;
          else if (item != "summary" && !item.empty())
            throw Error("sweep.collect = " + value + ": '" + item +
                        "' is not one of catalog, histogram, summary" + where);
        }
      } else {
        throw Error("sweep." + name + ": unknown key; the [sweep] keys are scene, combine, " +
                    "replicas, collect" + where);
      }
    } else if (section == "vary") {
      const ParamSpec* p = find_param(name);
      if (!p)
        throw Error("vary." + name + ": '" + name + "' is not a scene key" + key_suggestion(name) +
                    where);
      SweptKey k{name, {}};
      Scene check;  // one scene checks every value (a scene per value costs 14 KB and time)
      for (const auto& v : expand_sweep_values(name, value)) {
        std::string raw = v;
        if (p->type == ParamType::Integer && v.find_first_of(".eE") != std::string::npos)
          raw = std::to_string(std::llround(std::strtod(v.c_str(), nullptr)));
        check.set(name, raw, "vary." + name + " in " + origin);
        k.values.push_back(check.text(name));
      }
      spec.keys.push_back(std::move(k));
      // The product so far, checked as each list comes, so a huge sweep is refused before its
      // next lists are expanded (zip's length is checked once all are read).
      if (!zipped) {
        double so_far = 1;
        for (const auto& sk : spec.keys) so_far *= static_cast<double>(sk.values.size());
        if (so_far > static_cast<double>(kMaxSweepPoints))
          throw Error("the sweep has at least " + format_real(so_far) +
                      " points (the product of the lengths of its [vary] lists up to " + name +
                      "); at most " + std::to_string(kMaxSweepPoints) +
                      " are allowed: vary fewer values or split the sweep" + where);
      }
    } else if (section == "set") {
      sets.push_back({name, value});
    } else {
      throw Error(key + ": unknown section '[" + section + "]'; a sweep file has [sweep], " +
                  "[vary] and [set]" + where);
    }
  }
  if (spec.keys.empty()) throw Error("no [vary] keys: nothing to sweep" + where);
  // A product with a value twice would run the same points twice; a zip may repeat a value
  // of one key (each point is a column of the lists).
  if (spec.combine == SweepCombine::Product)
    for (const auto& k : spec.keys) {
      std::set<std::string> distinct;
      for (const auto& v : k.values)
        if (!distinct.insert(v).second)
          throw Error("vary." + k.key + ": the value " + v + " comes twice" + where);
    }
  if (spec.combine == SweepCombine::Zip)
    for (const auto& k : spec.keys)
      if (k.values.size() != spec.keys.front().values.size())
        throw Error("sweep.combine = zip needs lists of one length: " + k.key + " has " +
                    std::to_string(k.values.size()) + " values, " + spec.keys.front().key +
                    " has " + std::to_string(spec.keys.front().values.size()) + where);

  if (!scene_file.empty()) {
    const std::filesystem::path sp(scene_file);
    const std::filesystem::path resolved =
        sp.is_absolute() || base_dir.empty() ? sp : std::filesystem::path(base_dir) / sp;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(resolved, ec))
      throw Error("sweep.scene = " + scene_file + ": no scene file '" + resolved.string() + "'" +
                  (sp.is_absolute() ? std::string()
                                    : " (a relative path is read from the sweep file's folder '" +
                                          (base_dir.empty() ? std::string(".") : base_dir) + "')") +
                  where);
    spec.base = Scene::from_file(resolved.string());
  }
  for (const auto& [key, value] : sets) spec.base.set(key, value, "set." + key + " in " + origin);
  for (const auto& o : overrides) spec.base.apply_override(o);
  for (const auto& k : spec.keys)
    for (const auto& o : sets)
      if (o.key == k.key) throw Error(k.key + ": both in [set] and in [vary]" + where);
  return spec;
}

std::size_t SweepSpec::point_count() const {
  const std::string where = " (in " + origin + ")";
  std::size_t count = 1;
  if (combine == SweepCombine::Zip) {
    count = keys.front().values.size();
  } else {
    // The product, stopped as soon as it passes the bound (so it cannot overflow); the
    // message gives the whole product as a real number.
    double whole = 1;
    for (const auto& k : keys) whole *= static_cast<double>(k.values.size());
    for (const auto& k : keys) {
      count *= k.values.size();
      if (count > kMaxSweepPoints)
        throw Error("the sweep has " + format_real(whole) + " points (the product of the " +
                    "[vary] lists' lengths); at most " + std::to_string(kMaxSweepPoints) +
                    " are allowed: vary fewer values or split the sweep" + where);
    }
  }
  if (count > kMaxSweepPoints)
    throw Error("the sweep has " + std::to_string(count) + " points; at most " +
                std::to_string(kMaxSweepPoints) + " are allowed: vary fewer values or split the " +
                "sweep" + where);
  if (count * static_cast<std::size_t>(replicas) > kMaxSweepTasks)
    throw Error("the sweep has " + std::to_string(count) + " points x " + std::to_string(replicas) +
                " replicas = " + std::to_string(count * static_cast<std::size_t>(replicas)) +
                " runs; at most " + std::to_string(kMaxSweepTasks) + " are allowed" + where);
  return count;
}

std::vector<std::pair<std::string, std::string>> SweepSpec::point_values(std::size_t i) const {
  std::vector<std::size_t> pick(keys.size());
  std::size_t rest = i;
  for (std::size_t j = keys.size(); j-- > 0;) {
    if (combine == SweepCombine::Zip) {
      pick[j] = i;
    } else {
      pick[j] = rest % keys[j].values.size();
      rest /= keys[j].values.size();
    }
  }
  std::vector<std::pair<std::string, std::string>> values;
  for (std::size_t j = 0; j < keys.size(); ++j)
    values.emplace_back(keys[j].key, keys[j].values[pick[j]]);
  return values;
}

SweepPoint SweepSpec::point(std::size_t i) const {
  SweepPoint p{point_values(i), base};
  for (const auto& [key, value] : p.values)
    p.scene.set(key, value, "vary." + key + " in " + origin);
  return p;
}

std::vector<SweepPoint> SweepSpec::points() const {
  const std::size_t count = point_count();
  std::vector<SweepPoint> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) out.push_back(point(i));
  return out;
}

const Schema& sweep_csv_schema() {
  static const Schema schema = {
      {sweep_col::point, "", "0-based point number; the point's folder is points/p<number>",
       kInteger},
      {"status", "", "ok, failed (the error is in the last column) or pending (not run yet)",
       kText},
      {"replicas", "", "replicas run and merged into the point", kInteger},
      {"events", "", "recorded events over all replicas (slip episodes in continuous mode)",
       kInteger},
      {"b", "", "binned maximum-likelihood b of the merged histogram; empty when no window fits"},
      {"b_err", "", "its standard error (Shi & Bolt); empty when no window fits"},
      {"b_sys_err", "",
       "systematic error of b: half its range over the windows within 1 unit of mu inside "
       "both ends; empty when no window fits"},
      {"b_mw", "", "b per unit of moment magnitude Mw = (2/3) log10 M + const: 1.5 b"},
      {"mu_min", "", "lower end of the fit window (the scene's stats.mu_min, or automatic)"},
      {"mu_max", "", "upper end of the fit window"},
      {"run_seconds", "wall s", "wall-clock seconds of the point's replicas, summed"},
      {"error", "", "why the point failed (double-quoted), empty when ok", kText},
  };
  return schema;
}

const Schema& sweep_fit_schema() {
  static const Schema schema = {
      {sweep_col::point, "", "0-based point number, as in sweep.csv; the swept keys follow",
       kInteger},
      {"events", "", "events in the point's merged histogram", kInteger},
      {"b", "", "binned maximum-likelihood b on the refit's window; empty when none fits"},
      {"b_err", "", "its standard error (Shi & Bolt)"},
      {"b_sys_err", "", "its systematic error (half the range over the nearby windows)"},
      {"b_mw", "", "1.5 b: per unit of moment magnitude Mw"},
      {"mu_min", "", "lower end of the window (given, or automatic)"},
      {"mu_max", "", "upper end of the window"},
      {"tau_measure", "",
       "the size measure of tau: fit's --measure, else topplings (OFC) or blocks (a lattice); "
       "empty for a chain",
       kText},
      {"tau", "",
       "power-law exponent of that size over the point's replicas' catalogues (maximum "
       "likelihood, x_min by the KS distance); empty when none"},
      {"tau_err", "", "its block-bootstrap error"},
      {"tau_x_min", "", "lower end of tau's range"},
      {"tau_x_max", "", "upper end of tau's range; empty when none"},
      {"tau_p", "", "goodness-of-fit p of the power law (p > 0.1: plausible)"},
      {"tau_error", "",
       "why the point has no tau (double-quoted), empty when it has one or "
       "no measure applies",
       kText},
      {"error", "", "why the point has no b (double-quoted), empty when it has one", kText},
  };
  return schema;
}

}  // namespace bkq
