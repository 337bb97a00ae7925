// Implementation of the INI parser (see ini.hpp).
#include "io/ini.hpp"

#include <boost/program_options.hpp>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace bkq {

std::vector<IniEntry> parse_ini(const std::string& text, const std::string& where) {
  namespace po = boost::program_options;
  // No option is declared: every entry comes back unregistered, and the caller decides
  // which keys it knows.
  const po::options_description none;
  std::istringstream in(text);
  po::parsed_options parsed(&none);
  try {
    parsed = po::parse_config_file(in, none, /*allow_unregistered=*/true);
  } catch (const po::error& e) {
    throw Error(std::string(e.what()) + " (" + where + ")");
  }
  std::vector<IniEntry> entries;
  entries.reserve(parsed.options.size());
  for (const auto& opt : parsed.options)
    entries.push_back({opt.string_key, opt.value.empty() ? std::string() : opt.value.front()});
  return entries;
}

std::string read_text_file(const std::string& path, const std::string& what) {
  const std::string prefix = "cannot read " + what + " '" + path + "': ";
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(prefix + std::strerror(EISDIR));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(prefix + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(prefix + std::strerror(errno));
  return text.str();
}

}  // namespace bkq
