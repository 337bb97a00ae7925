// catalog.h5 (see catalog_h5.hpp): what holds with and without HDF5. The rest is in
// catalog_h5_hdf5.cpp (built with HDF5) or catalog_h5_none.cpp (without), one of the two.
#include "io/catalog_h5.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>

namespace bkq {

bool is_hdf5_file(const std::string& path) {
  static const char signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  // Only a plain file is looked into: a FIFO's opening would wait for a writer, a device's
  // reads never end (the readers refuse them, io/input_file.hpp).
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  return in.read(head, 8) && std::memcmp(head, signature, 8) == 0;
}

}  // namespace bkq
