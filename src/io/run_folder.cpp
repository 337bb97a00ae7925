// Implementation of the minimal run-folder readers (see run_folder.hpp).
#include "io/run_folder.hpp"

#include <cctype>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/csv_util.hpp"

namespace bkq {

namespace {
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}
}  // namespace

SceneModelInfo read_scene_model(const std::filesystem::path& scene_ini) {
  std::ifstream in(scene_ini);
  if (!in) throw Error(scene_ini.string() + ": cannot open");
  SceneModelInfo info;
  std::string section, line;
  std::int64_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto hash = line.find_first_of(";#");
    line = trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (line.empty()) continue;
    if (line.front() == '[' && line.back() == ']') {
      section = trim(line.substr(1, line.size() - 2));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
    if (section == "model" && key == "blocks") {
      const auto n = csv::parse_int(value, scene_ini.string(), lineno, "model.blocks");
      if (n < 1 || n > 1'000'000'000)
        throw Error(scene_ini.string() + " line " + std::to_string(lineno) +
                    ": model.blocks: expected a positive integer, got " + value);
      info.blocks = static_cast<int>(n);
    } else if (section == "model" && key == "boundary") {
      info.boundary = value;
    } else if (section == "friction" && key == "alpha") {
      info.alpha = value;
    }
  }
  return info;
}

std::optional<double> read_json_number(const std::filesystem::path& json, const std::string& key) {
  std::ifstream in(json);
  if (!in) throw Error(json.string() + ": cannot open");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  // Walk the text tracking nesting depth so only top-level keys match.
  int depth = 0;
  bool in_string = false;
  std::size_t string_start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
        if (depth == 1 && text.compare(string_start, i - string_start, key) == 0 &&
            i - string_start == key.size()) {
          std::size_t j = i + 1;
          while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
          if (j >= text.size() || text[j] != ':') continue;  // a value, not a key
          ++j;
          while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
          std::size_t k = j;
          while (k < text.size() && text[k] != ',' && text[k] != '}' && text[k] != '\n' &&
                 !std::isspace(static_cast<unsigned char>(text[k])))
            ++k;
          const std::string value = text.substr(j, k - j);
          if (value == "null") return std::nullopt;
          try {
            return csv::parse_double(value, json.string(), 0, key);
          } catch (const Error&) {
            throw Error(json.string() + ": \"" + key + "\": expected a number, got " + value);
          }
        }
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      string_start = i + 1;
    } else if (c == '{' || c == '[') {
      ++depth;
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return std::nullopt;
}

}  // namespace bkq
