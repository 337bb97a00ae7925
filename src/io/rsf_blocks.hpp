// Per-block rate-and-state parameters (rsf.blocks): a CSV file with the header block,a,b,dc
// and one row per block 0..N-1 in order, for asperities and barriers along a chain. Each row's
// a, b (the rate-and-state b) and D_c replace rsf.a, rsf.b and rsf.dc for that block; mu* and
// V* stay the scene's.
#pragma once

#include <filesystem>
#include <vector>

#include "io/schema.hpp"
#include "model/laws/rsf.hpp"

namespace bkq {

// `base` with each block's a, b_rsf, dc from the file; a bad file is a bkq::Error naming the
// file, the line and what is allowed (a > 0, b >= 0, dc > 0, finite; exactly `blocks` rows).
std::vector<rsf::Params> read_rsf_blocks(const std::filesystem::path& path, int blocks,
                                         const rsf::Params& base);

// slow_slip.csv (rsf.slow_slip_threshold): one row per slow-slip or afterslip episode.
const Schema& slow_slip_schema();

}  // namespace bkq
