// `bkquake spectrum RUN_DIR`: the amplitude spectrum of one signal of a continuous run
// (stats/spectrum.hpp) over a segment's input (its last half, as segments.csv uses), a time
// span, or the whole run; writes spectrum.csv and reports the strongest peaks beside the
// scene's natural frequencies (Ferre 2018 eqs. 4.5-4.7).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "stats/spectrum.hpp"
#include "stats/stability.hpp"

namespace bkq {

struct SpectrumRequest {
  std::string run_dir;
  // pad_position | pad_velocity | pad_friction | block:J (J a block of blocks.csv)
  std::string signal = "pad_position";
  std::optional<std::int64_t> segment;  // 0-based row of segments.csv
  std::optional<double> from, to;       // time span [from, to]
  Window window = Window::Hann;
  int peaks = 6;
  double f_min = 0;  // peaks below this frequency are not reported (slow drift)
  std::string out;   // default RUN_DIR/spectrum.csv
};

struct SpectrumReport {
  Spectrum spectrum;
  std::vector<Peak> peaks;
  NaturalFrequencies natural;
  std::string signal, out;
  double t_from = 0, t_to = 0, dt = 0, speed = -1;  // speed: the segment's, -1 if none
  std::size_t samples = 0;
  // The linear modes of steady sliding at that speed (bkquake stability), lowest frequency
  // first, when the speed is known and a sliding equilibrium exists there.
  std::vector<Eigenmode> linear;
};

// Throws bkq::Error for a folder that is not a finished continuous run, an unknown signal,
// a segment or span outside the run, or too few samples.
SpectrumReport spectrum_of_run(const SpectrumRequest& req);
void print_spectrum_report(const SpectrumReport& r, std::ostream& out);

}  // namespace bkq
