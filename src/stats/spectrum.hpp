// Amplitude spectra of sampled signals (Ferre 2018 §4.3, Figs. 4.13-4.14) with GSL's real FFT,
// and the natural frequencies of a scene to compare the peaks with.
//   The signal is cut to the largest length n = 2^a 3^b 5^c that fits (the earliest samples
//   go; GSL's mixed-radix FFT is slow for large prime factors), its mean is removed, it is
//   multiplied by the window w_i and transformed. Amplitude at f_k = k/(n dt):
//   A_k = 2 |X_k| / sum_i w_i, so a sine of amplitude A at a bin frequency reads A
//   (coherent-gain correction). Resolution df = 1/(n dt); the Hann window spreads a line
//   over about two bins and suppresses leakage far from it.
#pragma once

#include <vector>

#include "model/parameters.hpp"

namespace bkq {

enum class Window { Hann, Rectangular };
const char* to_string(Window w);

struct Spectrum {
  std::vector<double> frequency, amplitude;  // k = 0 .. n/2 (k = 0 is 0 after the mean goes)
  double resolution = 0;                     // 1/(n dt)
  std::size_t used = 0;                      // samples transformed (the last `used` of the input)
};

// `x` sampled every `dt`; std::invalid_argument for fewer than 4 samples or dt <= 0.
Spectrum amplitude_spectrum(const std::vector<double>& x, double dt, Window window);

struct Peak {
  double frequency = 0, amplitude = 0;
};
// The `count` largest local maxima with frequency >= f_min (bin 0 never), largest first.
std::vector<Peak> strongest_peaks(const Spectrum& s, int count, double f_min = 0);

// Thesis eqs. 4.5-4.7 for the scene's parameters (0 where the model has no such part):
//   pad: f_n = sqrt((k_p0 + N k_p)/m_x)/(2 pi), damped f_d = f_n sqrt(1 - zeta^2);
//   block: f = sqrt((k_p + 2 k_c)/m_u)/(2 pi) (its fastest linear mode, eq. 4.7).
struct NaturalFrequencies {
  double pad = 0, pad_damped = 0, block = 0;
};
NaturalFrequencies natural_frequencies(const ModelParams& p);

}  // namespace bkq
