// Opening and reading a file bkquake did not just write (a scene, a catalogue, a histogram, a
// friction table, a checkpoint, summary.json): a folder given where a file is expected, an
// unreadable file and a read error part way (EIO, /proc/self/mem) each end in bkq::Error
// naming the file and what failed, never in an "empty file" or a default taken silently. Text
// read whole is bounded in size, so a huge or endless file is refused instead of filling
// memory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>

namespace bkq {

// The largest file read whole as text (scenes, sweep files, summary.json, scene.ini): 64 MiB,
// about a thousand times the largest bkquake writes.
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{64} << 20;

// bkq::Error "cannot read <what> '<path>': <reason>" unless `path` is (or links to) a plain
// file: a folder, a device (whose reads never end), a FIFO or a socket (whose opening waits
// for a writer) is refused before it is opened. Every reader of a file bkquake did not just
// write checks this first (open_input does; so do the whole-table readers and the Python
// module's through them).
void check_input_file(const std::filesystem::path& path, const std::string& what);

// Opens `path` for reading after check_input_file; bkq::Error as there, or when it cannot be
// opened.
std::ifstream open_input(const std::filesystem::path& path, const std::string& what,
                         std::ios::openmode mode = std::ios::in);

// After a read loop on `in` stopped: bkq::Error "cannot read <what> '<path>': <reason> after
// line <L>" when it stopped on a read error rather than at the end of the file.
void check_read(const std::istream& in, const std::filesystem::path& path, const std::string& what,
                long long after_line);

}  // namespace bkq
