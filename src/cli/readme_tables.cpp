// `bkquake readme-tables [--update README.md]` (not listed in --help: a maintainer's tool):
// prints the README's generated tables with their markers, or rewrites them in place in the
// given README (io/readme_tables.hpp).
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/ini.hpp"
#include "io/output.hpp"
#include "io/readme_tables.hpp"

namespace bkq {

int cmd_readme_tables(const std::vector<std::string>& args) {
  if (args.empty()) {
    for (const auto& t : readme_tables())
      std::cout << readme_begin_marker(t.name) << "\n"
                << t.markdown << readme_end_marker(t.name) << "\n\n";
    return 0;
  }
  if (args.size() != 2 || args[0] != "--update")
    throw Error("readme-tables: usage: bkquake readme-tables [--update README.md]");
  const std::string& path = args[1];
  const std::string before = read_text_file(path, "README");
  const std::string after = update_readme(before);
  if (after != before) write_file_atomic(path, after);
  std::cout << path << (after != before ? ": tables updated\n" : ": tables already up to date\n");
  return 0;
}

}  // namespace bkq
