// spectrum.csv; see spectrum_csv.hpp.
#include "io/spectrum_csv.hpp"

#include "core/format.hpp"

namespace bkq {

const Schema& spectrum_schema() {
  static const Schema schema = {
      {"frequency", "1/time", "f_k = k / (n dt), k = 0 .. n/2"},
      {"amplitude", "signal", "2 |X_k| / sum of the window: a sine of amplitude A reads A"},
  };
  return schema;
}

std::string spectrum_csv(const Spectrum& s, const std::vector<std::string>& comments) {
  std::string out;
  out.reserve(48 * s.frequency.size() + 512);
  for (const auto& c : comments) out += "# " + c + "\n";
  out += header_of(spectrum_schema()) + "\n";
  for (std::size_t k = 0; k < s.frequency.size(); ++k)
    out += format_real(s.frequency[k]) + "," + format_real(s.amplitude[k]) + "\n";
  return out;
}

}  // namespace bkq
