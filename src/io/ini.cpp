// Implementation of the INI parser (see ini.hpp).
#include "io/ini.hpp"

#include <boost/program_options.hpp>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/error.hpp"
#include "io/input_file.hpp"

namespace bkq {

std::vector<IniEntry> parse_ini(const std::string& text, const std::string& where) {
  namespace po = boost::program_options;
  // No option is declared: every entry comes back unregistered, and the caller decides
  // which keys it knows.
  const po::options_description none;
  // A byte-order mark (Windows editors save UTF-8 with one) is no part of the first line.
  static constexpr std::string_view kBom = "\xEF\xBB\xBF";
  std::istringstream in(text.starts_with(kBom) ? text.substr(kBom.size()) : text);
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
  std::ifstream in = open_input(path, what, std::ios::binary);
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxTextFileBytes)
      throw Error("cannot read " + what + " '" + path + "': larger than " +
                  std::to_string(kMaxTextFileBytes >> 20) + " MiB");
    if (!in) break;
  }
  check_read(in, path, what, 0);
  return text;
}

}  // namespace bkq
