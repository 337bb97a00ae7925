// The command table: each command's row comes from its own file, and this list alone says
// which commands exist and in which order `bkquake --help` shows them (commands.hpp).
#include "cli/commands.hpp"

#include <algorithm>

namespace bkq {

Command run_command_row();             // cli/run.cpp
Command fit_command_row();             // cli/fit.cpp
Command merge_command_row();           // cli/merge.cpp
Command accuracy_command_row();        // cli/accuracy.cpp
Command spectrum_command_row();        // cli/spectrum.cpp
Command special_speed_command_row();   // cli/special_speed.cpp
Command special_law_command_row();     // cli/special_law.cpp
Command sweep_command_row();           // cli/sweep.cpp
Command friction_study_command_row();  // cli/friction_study.cpp
Command stability_command_row();       // cli/stability.cpp
Command seismicity_command_row();      // cli/seismicity.cpp
Command compare_command_row();         // cli/compare.cpp
Command readme_tables_command_row();   // cli/readme_tables.cpp (not listed)

const std::vector<Command>& command_table() {
  static const std::vector<Command> table = {
      run_command_row(),           fit_command_row(),        merge_command_row(),
      accuracy_command_row(),      spectrum_command_row(),   special_speed_command_row(),
      special_law_command_row(),   sweep_command_row(),      friction_study_command_row(),
      stability_command_row(),     seismicity_command_row(), compare_command_row(),
      readme_tables_command_row(),
  };
  return table;
}

const Command* find_command(const std::string& name) {
  for (const Command& c : command_table())
    if (c.name == name) return &c;
  return nullptr;
}

std::string command_names() {
  std::string names;
  for (const Command& c : command_table())
    if (c.listed) names += (names.empty() ? "" : ", ") + c.name;
  return names;
}

std::string usage_text() {
  std::string out =
      "bkquake: earthquake statistics for Burridge-Knopoff spring-block chains and the BK-Pad "
      "model\n\nUsage:\n";
  std::size_t name_width = 0;
  for (const Command& c : command_table())
    if (c.listed) {
      // Each line indented by two, continuation lines too.
      std::string lines = synopsis(c, 88);
      for (std::size_t at = lines.find('\n'); at != std::string::npos;
           at = lines.find('\n', at + 1))
        lines.insert(at + 1, "  ");
      out += "  " + lines + "\n";
      name_width = std::max(name_width, c.name.size());
    }
  out += "  bkquake --help | --version\n\nCommands:\n";
  for (const Command& c : command_table())
    if (c.listed) {
      out += "  " + c.name;
      out.append(name_width + 2 - c.name.size(), ' ');
      out += c.summary + "\n";
    }
  out += R"(
Examples:
  bkquake run                                    the Carlson-Langer reference, event-driven
  bkquake run data/scenes/thesis.ini --out runs/thesis
  bkquake run data/scenes/carlson-langer.ini --set friction.alpha=1 --set run.events=20000
  bkquake run --dump-defaults > my.ini           a commented scene, every key at its default

Each command takes --help. Every scene key, its default, range and meaning:
'bkquake run --dump-defaults' and the documentation, docs/reference/scenes.md.
)";
  return out;
}

}  // namespace bkq
