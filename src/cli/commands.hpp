// The subcommands of the bkquake program. main() only dispatches on the first word;
// each command parses its own arguments (args excludes the program and command names)
// and returns the exit status. User errors are thrown as bkq::Error.
#pragma once

#include <string>
#include <vector>

namespace bkq {

int cmd_run(const std::vector<std::string>& args);             // src/cli/run.cpp
int cmd_fit(const std::vector<std::string>& args);             // src/cli/fit.cpp
int cmd_merge(const std::vector<std::string>& args);           // src/cli/merge.cpp
int cmd_accuracy(const std::vector<std::string>& args);        // src/cli/accuracy.cpp
int cmd_spectrum(const std::vector<std::string>& args);        // src/cli/spectrum.cpp
int cmd_special_speed(const std::vector<std::string>& args);   // src/cli/special_speed.cpp
int cmd_special_law(const std::vector<std::string>& args);     // src/cli/special_law.cpp
int cmd_sweep(const std::vector<std::string>& args);           // src/cli/sweep.cpp
int cmd_friction_study(const std::vector<std::string>& args);  // src/cli/friction_study.cpp
int cmd_stability(const std::vector<std::string>& args);       // src/cli/stability.cpp
int cmd_seismicity(const std::vector<std::string>& args);      // src/cli/seismicity.cpp
// Hidden: regenerates the documentation's generated blocks (the key and column tables and
// the commands' help texts, mostly in docs/reference/).
int cmd_readme_tables(const std::vector<std::string>& args);  // src/cli/readme_tables.cpp

// What `bkquake --help` prints (src/cli/usage.cpp).
const char* usage_text();
// The commands `bkquake --help` lists, in its order, each with the function that runs it
// (src/cli/usage.cpp); docs/reference/commands.md shows each one's --help.
struct CommandEntry {
  const char* name;
  int (*run)(const std::vector<std::string>& args);
};
const std::vector<CommandEntry>& listed_commands();

}  // namespace bkq
