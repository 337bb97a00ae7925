// The one INI parser of bkquake: `[section]` headers, `key = value` lines and `#` comments,
// read with Boost.Program_options' config-file syntax. Scene::from_text checks every entry
// against the parameter table; the run-folder readers take only the keys they need from a
// finished run's scene.ini, so scenes written by older versions still read.
#pragma once

#include <string>
#include <vector>

namespace bkq {

struct IniEntry {
  std::string key;    // "section.key"
  std::string value;  // as written, surrounding spaces removed
};

// The entries in file order; a UTF-8 byte-order mark at the start is skipped. A syntax error
// throws bkq::Error ending in " (<where>)".
std::vector<IniEntry> parse_ini(const std::string& text, const std::string& where);

// The whole file as text, at most kMaxTextFileBytes (io/input_file.hpp); bkq::Error "cannot
// read <what> '<path>': <reason>" for a folder, an unreadable or too large file, a read error.
std::string read_text_file(const std::string& path, const std::string& what);

}  // namespace bkq
