// spectrum.csv (`bkquake spectrum`): '#' lines stating where the spectrum comes from (run,
// signal, time span, samples, window, resolution, provenance), then the columns of
// spectrum_schema().
#pragma once

#include <string>
#include <vector>

#include "io/schema.hpp"
#include "stats/spectrum.hpp"

namespace bkq {

const Schema& spectrum_schema();
// The whole file: each of `comments` as a '# ' line, the header, one row per frequency.
std::string spectrum_csv(const Spectrum& s, const std::vector<std::string>& comments);

}  // namespace bkq
