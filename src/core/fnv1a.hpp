// FNV-1a, 64 bit: the one checksum of the scene hash, the checkpoint file, catalog.csv's
// rows and a friction table's bytes. Not cryptographic: it finds accidental changes.
#pragma once

#include <cstdint>
#include <string_view>

namespace bkq {

inline constexpr std::uint64_t kFnv1a64Basis = 14695981039346656037ull;

// FNV-1a 64 of `data`, continuing from `h` (so a file can be hashed in pieces).
inline std::uint64_t fnv1a64(std::string_view data, std::uint64_t h = kFnv1a64Basis) {
  for (const unsigned char c : data) {
    h ^= c;
    h *= 1099511628211ull;  // FNV prime
  }
  return h;
}

}  // namespace bkq
