// Amplitude spectra with GSL; see spectrum.hpp.
#include "stats/spectrum.hpp"

#include <gsl/gsl_fft_real.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace bkq {

namespace {

// Largest 2^a 3^b 5^c <= n.
std::size_t smooth_length(std::size_t n) {
  for (std::size_t m = n; m > 1; --m) {
    std::size_t r = m;
    for (std::size_t p : {2u, 3u, 5u})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
  return 1;
}

}  // namespace

const char* to_string(Window w) {
  return w == Window::Hann ? "hann" : "rectangular";
}

Spectrum amplitude_spectrum(const std::vector<double>& x, double dt, Window window) {
  if (x.size() < 4) throw std::invalid_argument("spectrum: need at least 4 samples");
  if (!(dt > 0)) throw std::invalid_argument("spectrum: sample spacing must be > 0");
  const std::size_t n = smooth_length(x.size());
  std::vector<double> y(x.end() - static_cast<std::ptrdiff_t>(n), x.end());
  double mean = 0;
  for (double v : y) mean += v;
  mean /= static_cast<double>(n);
  double gain = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = window == Window::Hann
                         ? 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(i) /
                                                static_cast<double>(n))
                         : 1.0;
    y[i] = (y[i] - mean) * w;
    gain += w;
  }
  gsl_fft_real_wavetable* table = gsl_fft_real_wavetable_alloc(n);
  gsl_fft_real_workspace* work = gsl_fft_real_workspace_alloc(n);
  const int status = gsl_fft_real_transform(y.data(), 1, n, table, work);
  gsl_fft_real_workspace_free(work);
  gsl_fft_real_wavetable_free(table);
  if (status != 0) throw std::runtime_error("spectrum: GSL FFT failed");

  // Half-complex layout: y[0] = Re X_0, then (Re X_k, Im X_k) at 2k-1, 2k; for even n the
  // last is Re X_{n/2}.
  Spectrum s;
  s.used = n;
  s.resolution = 1.0 / (static_cast<double>(n) * dt);
  const std::size_t half = n / 2;
  s.frequency.resize(half + 1);
  s.amplitude.resize(half + 1);
  for (std::size_t k = 0; k <= half; ++k) {
    double mag;
    if (k == 0) {
      mag = std::abs(y[0]);
    } else if (2 * k == n) {
      mag = std::abs(y[n - 1]);
    } else {
      mag = std::hypot(y[2 * k - 1], y[2 * k]);
    }
    const double scale = (k == 0 || 2 * k == n) ? 1.0 : 2.0;
    s.frequency[k] = static_cast<double>(k) * s.resolution;
    s.amplitude[k] = scale * mag / gain;
  }
  return s;
}

std::vector<Peak> strongest_peaks(const Spectrum& s, int count, double f_min) {
  std::vector<Peak> peaks;
  const std::size_t m = s.amplitude.size();
  for (std::size_t k = 1; k < m; ++k) {
    if (s.frequency[k] < f_min) continue;
    const double a = s.amplitude[k];
    const bool left = a > s.amplitude[k - 1];
    const bool right = k + 1 == m || a >= s.amplitude[k + 1];
    if (left && right && a > 0) peaks.push_back({s.frequency[k], a});
  }
  std::sort(peaks.begin(), peaks.end(),
            [](const Peak& a, const Peak& b) { return a.amplitude > b.amplitude; });
  if (peaks.size() > static_cast<std::size_t>(std::max(count, 0)))
    peaks.resize(static_cast<std::size_t>(std::max(count, 0)));
  return peaks;
}

NaturalFrequencies natural_frequencies(const ModelParams& p) {
  NaturalFrequencies f;
  const double two_pi = 2 * std::numbers::pi;
  if (p.pad_moves()) {
    const double k = p.k_p0 + p.n * p.k_p;
    f.pad = std::sqrt(k / p.m_x) / two_pi;
    const double zeta = p.c_p / (2 * std::sqrt(k * p.m_x));
    f.pad_damped = zeta < 1 ? f.pad * std::sqrt(1 - zeta * zeta) : 0.0;
  }
  f.block = std::sqrt((p.k_p + 2 * p.k_c) / p.m_u) / two_pi;
  return f;
}

}  // namespace bkq
