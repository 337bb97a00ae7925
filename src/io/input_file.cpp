// Implementation of the checked input files (see input_file.hpp).
#include "io/input_file.hpp"

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace bkq {

namespace {
std::string prefix(const std::filesystem::path& path, const std::string& what) {
  return "cannot read " + what + " '" + path.string() + "': ";
}
}  // namespace

std::ifstream open_input(const std::filesystem::path& path, const std::string& what,
                         std::ios::openmode mode) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error(prefix(path, what) + std::strerror(EISDIR) + ", expected a file");
  // A device (/dev/zero, /dev/urandom) reads without end: refused as no file of ours.
  if (std::filesystem::is_character_file(path, ec) || std::filesystem::is_block_file(path, ec))
    throw Error(prefix(path, what) + "it is a device, expected a file");
  errno = 0;
  std::ifstream in(path, mode | std::ios::in);
  if (!in) throw Error(prefix(path, what) + (errno ? std::strerror(errno) : "cannot open"));
  return in;
}

void check_read(const std::istream& in, const std::filesystem::path& path, const std::string& what,
                long long after_line) {
  if (!in.bad()) return;
  const int e = errno;
  throw Error(prefix(path, what) + (e ? std::strerror(e) : "read error") +
              (after_line > 0 ? " after line " + std::to_string(after_line) : " at its start"));
}

}  // namespace bkq
