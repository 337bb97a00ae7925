// FNV-1a, 64 bit: the one checksum of the scene hash, the checkpoint file and a friction
// table's bytes; catalog.csv's rows take its step on 8 bytes at a time (line_hash), since
// they are hashed as they are written. Not cryptographic: it finds accidental changes.
#pragma once

#include <cstdint>
#include <cstring>
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

// The checksum of catalog.csv's lines that a checkpoint keeps (observer state
// "catalog.rowhash"), so an edited row is found: line by line (`line` ends with its '\n'),
// FNV-1a's step taken on 8 bytes at a time (the last word zero-padded after the '\n'), a
// multiply per 8 bytes instead of per byte. Each step is a bijection of the running value,
// so one changed word always changes the result.
inline constexpr std::uint64_t kLineHashSeed = kFnv1a64Basis;
inline std::uint64_t line_hash(std::string_view line, std::uint64_t h) {
  constexpr std::uint64_t prime = 1099511628211ull;  // FNV prime
  const char* p = line.data();
  std::size_t n = line.size();
  for (; n >= 8; n -= 8, p += 8) {
    std::uint64_t w;
    std::memcpy(&w, p, 8);
    h = (h ^ w) * prime;
  }
  if (n > 0) {
    std::uint64_t w = 0;
    std::memcpy(&w, p, n);
    h = (h ^ w) * prime;
  }
  return h;
}

}  // namespace bkq
