// The bkquake program's commands, declared once. Each command file (run.cpp, fit.cpp, ...)
// returns its row: name, one-line summary, operands, options and the function that runs it;
// the table (commands.cpp) lists the rows. From the rows alone come the dispatch in main(),
// `bkquake --help`, each command's `--help` (its synopsis generated from its options) and
// docs/reference/commands.md (readme_tables.cpp copies the help texts there).
// Parsing is boost::program_options, kept inside command_line.cpp.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bkq {

// One option of a command: `--name VALUE`, or a flag.
struct Option {
  enum class Kind { Flag, Text, Integer, Integer64, Real, Repeated };
  std::string name;  // without the leading "--"
  Kind kind = Kind::Flag;
  std::string value;          // the value's placeholder in the synopsis: DIR, N, free|periodic
  std::string help;           // one sentence; a default the command works out is said here
  std::string default_value;  // taken when the option is absent ("": none), shown in --help
  bool is_required = false;   // shown without brackets (the command says when it is missing)
  bool is_hidden = false;     // a maintainer's option: parsed, not shown

  Option required() const;
  Option hidden() const;
};

// The option rows, by kind: opt::text("out", "DIR", "output folder", "out").
namespace opt {
Option flag(std::string name, std::string help);
Option text(std::string name, std::string value, std::string help, std::string dflt = "");
Option integer(std::string name, std::string value, std::string help, std::string dflt = "");
Option integer64(std::string name, std::string value, std::string help, std::string dflt = "");
Option real(std::string name, std::string value, std::string help, std::string dflt = "");
// Repeatable, each occurrence kept in order: [--name VALUE]...
Option repeated(std::string name, std::string value, std::string help);
}  // namespace opt

struct Command;

// A parsed command line: the options given (or defaulted) and the operands. Asking for an
// option the command does not declare is a bug (std::logic_error), not an absent option.
class Args {
 public:
  struct Values;  // command_line.cpp
  Args(const Command& command, std::shared_ptr<const Values> values);

  const std::string& command() const;
  // Given, or absent with a default value.
  bool has(const std::string& name) const;
  // Given on the command line (not its default).
  bool given(const std::string& name) const;
  std::string text(const std::string& name) const;
  int integer(const std::string& name) const;
  std::int64_t integer64(const std::string& name) const;
  double real(const std::string& name) const;
  std::vector<std::string> texts(const std::string& name) const;  // a repeated option
  std::vector<std::string> operands() const;                      // in order

 private:
  const Option& declared(const std::string& name) const;
  const Command* command_;
  std::shared_ptr<const Values> values_;
};

// A row of the command table.
struct Command {
  std::string name;
  std::string summary;   // one line in `bkquake --help`
  std::string operands;  // the positional arguments in the synopsis: "[SCENE]", "RUN_DIR..."
  int max_operands = 0;  // how many the parser takes: 0, 1, or -1 (any; the command checks)
  std::string about;     // what --help says under the synopsis (lines ending in '\n')
  std::vector<Option> options;
  int (*run)(const Args& args) = nullptr;
  bool listed = true;  // false: a maintainer's tool, dispatched but not in --help
};

// The table, in the order `bkquake --help` lists the commands (commands.cpp).
const std::vector<Command>& command_table();
// The row named `name`; nullptr when none.
const Command* find_command(const std::string& name);
// "run, fit, merge, ...": the listed commands' names.
std::string command_names();

// "bkquake fit CATALOG [--mu-min MU] ...": every option of the command, wrapped at `width`.
std::string synopsis(const Command& command, std::size_t width = 92);
// What `bkquake COMMAND --help` prints: synopsis, about, options with their defaults.
std::string help_text(const Command& command);
// What `bkquake --help` prints: every listed command's synopsis and summary.
std::string usage_text();

// Parses `args` (without the program and command names) by the command's options, prints
// its help for --help, else runs it. Unknown options and bad values are bkq::Error naming
// the command and the option.
int run_command(const Command& command, const std::vector<std::string>& args);

}  // namespace bkq
