// The spectrum of a run's signal; see spectrum.hpp.
#include "app/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ostream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "io/output.hpp"
#include "io/run_folder.hpp"
#include "io/scene.hpp"
#include "io/segments_csv.hpp"
#include "io/settings.hpp"
#include "io/spectrum_csv.hpp"
#include "model/equilibrium.hpp"

namespace bkq {

namespace {

namespace fs = std::filesystem;

// The file and column holding `signal`.
std::pair<std::string, std::string> column_of(const std::string& signal, int blocks) {
  if (signal == "pad_position") return {"timeseries.csv", "pad_x"};
  if (signal == "pad_velocity") return {"timeseries.csv", "pad_v"};
  if (signal == "pad_friction") return {"timeseries.csv", "pad_friction"};
  if (signal.rfind("block:", 0) == 0) {
    const std::string j = signal.substr(6);
    char* end = nullptr;
    const long v = std::strtol(j.c_str(), &end, 10);
    if (!j.empty() && *end == '\0' && v >= 0 && v < blocks) {
      std::string name = "u";
      name += std::to_string(v);
      return {"blocks.csv", name};
    }
  }
  throw Error("spectrum: --signal = " + signal +
              ": expected pad_position, pad_velocity, pad_friction or block:J with 0 <= J < " +
              std::to_string(blocks));
}

}  // namespace

SpectrumReport spectrum_of_run(const SpectrumRequest& req) {
  const fs::path dir(req.run_dir);
  const fs::path scene_file = dir / "scene.ini";
  if (!fs::exists(scene_file))
    throw Error("spectrum: " + req.run_dir + " is not a run folder (no scene.ini)");
  const Scene scene = Scene::from_file(scene_file.string());
  if (scene_values(scene).drive.mode != DriveMode::Continuous)
    throw Error("spectrum: " + req.run_dir +
                " is an event-driven run (drive.mode = events); spectra need a continuous run "
                "(drive.mode = continuous)");
  const Settings settings = settings_from_scene(scene);
  SpectrumReport r;
  r.natural = natural_frequencies(settings.model);
  r.signal = req.signal;
  const auto [file, column] = column_of(req.signal, settings.model.n);
  if (!fs::exists(dir / file))
    throw Error("spectrum: " + (dir / file).string() + " is missing" +
                (file == "blocks.csv" ? " (run with output.blocks = true)" : ""));
  // The folder rule (io/run_folder.hpp): never over an input or a run's own file; the run
  // folder's lock while writing into it.
  r.out = req.out.empty() ? (dir / "spectrum.csv").string() : req.out;
  const DerivedOutput output(r.out, {dir / file, dir / "segments.csv", dir / "scene.ini"},
                             "spectrum");

  double lo = 0, hi = settings.run.duration;
  if (req.segment) {
    const auto rows = read_segments_csv(dir / "segments.csv");
    if (*req.segment < 0 || *req.segment >= static_cast<std::int64_t>(rows.size()))
      throw Error("spectrum: --segment = " + std::to_string(*req.segment) + ": the run has " +
                  std::to_string(rows.size()) + " segments (0 .. " +
                  std::to_string(static_cast<std::int64_t>(rows.size()) - 1) + ")");
    const SegmentRow& s = rows[static_cast<std::size_t>(*req.segment)];
    lo = 0.5 * (s.t_start + s.t_end);
    hi = s.t_end;
    r.speed = s.speed;
  }
  if (r.speed < 0 && settings.drive.schedule == Schedule::Constant) r.speed = settings.drive.speed;
  if (r.speed > 0) {
    NoEquilibrium why = NoEquilibrium::None;
    const KineticBranch branch = kinetic_branch(settings.model, r.speed, &why);
    // The modal reduction is not exact for a free chain with range coupling: no lines then.
    const ModelParams& m = settings.model;
    // Nor is there one for a lattice (the modes are a chain's).
    const bool modal =
        !(m.reach() > 1 && (m.long_range() || m.viscous()) && m.boundary == Boundary::Free) &&
        !m.lattice();
    if (why == NoEquilibrium::None && modal) {
      r.linear = modal_eigenmodes(settings.model, branch.slope);
      std::erase_if(r.linear, [](const Eigenmode& m) { return !(m.frequency() > 0); });
      std::stable_sort(
          r.linear.begin(), r.linear.end(),
          [](const Eigenmode& a, const Eigenmode& b) { return a.frequency() < b.frequency(); });
    }
  }
  if (req.from) lo = *req.from;
  if (req.to) hi = *req.to;
  if (!(hi > lo))
    throw Error("spectrum: empty time span [" + format_real(lo) + ", " + format_real(hi) + "]");

  const auto cols = read_numeric_columns(dir / file, {"t", column});
  std::vector<double> x;
  double first = NAN, last = NAN;
  const double tol = 1e-9 * settings.output.every;
  for (std::size_t i = 0; i < cols[0].size(); ++i) {
    const double t = cols[0][i];
    if (t < lo - tol || t > hi + tol) continue;
    if (x.empty()) first = t;
    last = t;
    x.push_back(cols[1][i]);
  }
  if (x.size() < 4)
    throw Error("spectrum: only " + std::to_string(x.size()) + " samples of " + file + " in [" +
                format_real(lo) + ", " + format_real(hi) + "]; need at least 4");
  r.dt = (last - first) / static_cast<double>(x.size() - 1);
  r.spectrum = amplitude_spectrum(x, r.dt, req.window);
  r.samples = r.spectrum.used;
  r.t_from = last - r.dt * static_cast<double>(r.samples - 1);
  r.t_to = last;
  r.peaks = strongest_peaks(r.spectrum, req.peaks, req.f_min);

  std::vector<std::string> comments = provenance_lines(scene);
  std::string what = "spectrum of ";
  what += req.run_dir;
  what += ": signal ";
  what += req.signal;
  what += " (" + file + " column " + column + ")";
  comments.insert(comments.begin(), what);
  std::string span = "samples ";
  span += std::to_string(r.samples);
  span += " from t = " + format_real(r.t_from);
  span += " to " + format_real(r.t_to);
  span += ", spacing " + format_real(r.dt);
  comments.push_back(span);
  std::string how = "window ";
  how += to_string(req.window);
  how += ", mean removed, resolution " + format_real(r.spectrum.resolution);
  how += ", Nyquist " + format_real(0.5 / r.dt);
  comments.push_back(how);
  write_file_atomic(r.out, spectrum_csv(r.spectrum, comments));
  return r;
}

void print_spectrum_report(const SpectrumReport& r, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line,
                "spectrum of %s over t = %.6g .. %.6g (%zu samples, spacing %.6g)%s\n",
                r.signal.c_str(), r.t_from, r.t_to, r.samples, r.dt,
                r.speed >= 0 ? (", speed " + format_real(r.speed)).c_str() : "");
  out << line;
  std::snprintf(line, sizeof line, "  resolution %.6g, Nyquist %.6g\n", r.spectrum.resolution,
                0.5 / r.dt);
  out << line << "  strongest peaks:\n    frequency   amplitude\n";
  for (const Peak& p : r.peaks) {
    std::snprintf(line, sizeof line, "    %9.5f   %.6g\n", p.frequency, p.amplitude);
    out << line;
  }
  out << "  natural frequencies of the scene:\n";
  if (r.natural.pad > 0) {
    std::snprintf(line, sizeof line,
                  "    pad      %.5f undamped, %.5f damped (thesis eqs. 4.5-4.6)\n", r.natural.pad,
                  r.natural.pad_damped);
    out << line;
  }
  std::snprintf(line, sizeof line, "    block    %.5f (thesis eq. 4.7)%s\n", r.natural.block,
                r.natural.block > 0.5 / r.dt ? ", above the Nyquist frequency" : "");
  out << line << "  written " << r.out << "\n";
  if (!r.linear.empty()) {
    out << "  linear modes of steady sliding at v = " << format_real(r.speed)
        << " (bkquake stability), lowest frequencies:\n";
    for (std::size_t i = 0; i < r.linear.size() && i < 5; ++i) {
      const Eigenmode& m = r.linear[i];
      std::snprintf(line, sizeof line, "    %-6s %-4d %.5f  growth %+.4g%s\n", to_string(m.family),
                    m.index, m.frequency(), m.growth(), m.unstable() ? "  unstable" : "");
      out << line;
    }
  }
}

}  // namespace bkq
