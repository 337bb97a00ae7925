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

void check_input_file(const std::filesystem::path& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_directory(st))
    throw Error(prefix(path, what) + std::strerror(EISDIR) + ", expected a file");
  // A device (/dev/zero, /dev/urandom) reads without end, a FIFO's opening waits for a writer
  // that may never come: refused as no file of ours, before anything waits.
  if (fs::is_character_file(st) || fs::is_block_file(st))
    throw Error(prefix(path, what) + "it is a device, expected a file");
  if (fs::is_fifo(st)) throw Error(prefix(path, what) + "it is a FIFO (a pipe), expected a file");
  if (fs::is_socket(st)) throw Error(prefix(path, what) + "it is a socket, expected a file");
  if (fs::exists(st) && !fs::is_regular_file(st))
    throw Error(prefix(path, what) + "not a plain file");
}

std::ifstream open_input(const std::filesystem::path& path, const std::string& what,
                         std::ios::openmode mode) {
  check_input_file(path, what);
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
