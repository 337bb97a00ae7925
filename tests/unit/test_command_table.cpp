// The command table (src/cli/commands.hpp) is the one list of commands and options: every
// option of every command shows in the command's synopsis, in its --help and in
// docs/reference/commands.md; names are unique and summaries fit one line of --help.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/readme_tables.hpp"

namespace bkq {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// True when `text` holds `--name` as a whole option, not as the start of a longer one
// (`--mu` in `--mu-min`).
bool names_option(const std::string& text, const std::string& name) {
  const std::string word = "--" + name;
  for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
    const std::size_t end = at + word.size();
    if (end == text.size() || !(std::isalnum(static_cast<unsigned char>(text[end])) ||
                                text[end] == '-' || text[end] == '_'))
      return true;
  }
  return false;
}

// `text` with every line break and the indentation after it made one space.
std::string one_line(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n') {
      out += text[i];
      continue;
    }
    while (i + 1 < text.size() && text[i + 1] == ' ') ++i;
    out += ' ';
  }
  return out;
}

TEST(CommandTable, NamesAreUniqueAndSummariesFitOneLine) {
  std::set<std::string> commands;
  for (const Command& c : command_table()) {
    EXPECT_TRUE(commands.insert(c.name).second) << "two commands named " << c.name;
    EXPECT_NE(c.run, nullptr) << c.name;
    EXPECT_EQ(find_command(c.name), &c) << c.name;
    EXPECT_EQ(c.summary.find('\n'), std::string::npos) << c.name;
    EXPECT_LE(c.summary.size(), 72u) << c.name << ": " << c.summary;
    EXPECT_TRUE(c.about.empty() || c.about.back() == '\n') << c.name;
    std::set<std::string> options = {"help"};
    for (const Option& o : c.options) {
      EXPECT_TRUE(options.insert(o.name).second) << c.name << " --" << o.name << " twice";
      EXPECT_EQ(o.value.empty(), o.kind == Option::Kind::Flag) << c.name << " --" << o.name;
      EXPECT_FALSE(o.help.empty()) << c.name << " --" << o.name;
    }
  }
  EXPECT_EQ(find_command("frobnicate"), nullptr);
  EXPECT_GE(commands.size(), 11u);
}

TEST(CommandTable, EveryOptionIsInItsSynopsisItsHelpAndTheReferencePage) {
  const std::string page =
      slurp(fs::path(BKQUAKE_SOURCE_DIR) / "docs" / "reference" / "commands.md");
  const std::string usage = usage_text();
  for (const Command& c : command_table()) {
    const std::string syn = synopsis(c);
    const std::string help = help_text(c);
    EXPECT_EQ(syn.rfind("bkquake " + c.name, 0), 0u) << syn;
    EXPECT_EQ(help.rfind("Usage: bkquake " + c.name, 0), 0u) << help;
    EXPECT_NE(help.find(c.operands), std::string::npos) << c.name;
    const auto block = readme_block(page, "help " + c.name);
    EXPECT_EQ(block.has_value(), c.listed)
        << "docs/reference/commands.md and the table disagree on " << c.name;
    EXPECT_EQ(usage.find("  bkquake " + c.name + " ") != std::string::npos ||
                  usage.find("  bkquake " + c.name + "\n") != std::string::npos,
              c.listed)
        << c.name;
    // The options list of the help: the part after "Options:".
    const std::string list = help.substr(help.find("\nOptions:\n"));
    const std::string flat = one_line(list);
    for (const Option& o : c.options) {
      if (o.is_hidden) {
        EXPECT_FALSE(names_option(help, o.name)) << c.name << " shows hidden --" << o.name;
        continue;
      }
      EXPECT_TRUE(names_option(syn, o.name)) << c.name << " --" << o.name << " not in " << syn;
      EXPECT_TRUE(names_option(list, o.name)) << c.name << " --" << o.name;
      if (!o.default_value.empty()) {
        EXPECT_NE(flat.find("(default: " + o.default_value + ")"), std::string::npos)
            << c.name << " --" << o.name;
      }
      if (c.listed) {
        EXPECT_TRUE(names_option(usage, o.name)) << c.name << " --" << o.name;
        if (block) {
          EXPECT_TRUE(names_option(*block, o.name)) << c.name << " --" << o.name;
        }
      }
    }
  }
}

// A default that depends on the machine, or on files beside the input, says so.
TEST(CommandTable, DefaultsWorkedOutByTheCommandSaySo) {
  const auto row = [](const std::string& command, const std::string& option) {
    const Command* c = find_command(command);
    EXPECT_NE(c, nullptr) << command;
    for (const Option& o : c->options)
      if (o.name == option) return o;
    ADD_FAILURE() << command << " has no --" << option;
    return Option{};
  };
  const Option jobs = row("friction-study", "jobs");
  EXPECT_TRUE(jobs.default_value.empty());
  EXPECT_NE(jobs.help.find("the machine's cores"), std::string::npos) << jobs.help;
  const Option b = row("seismicity", "b-mu-min");
  EXPECT_NE(b.help.find("summary.json"), std::string::npos) << b.help;
  EXPECT_LT(b.help.find("summary.json"), b.help.find("else maximum curvature")) << b.help;
}

// The parser a row makes: defaults typed as declared, repeated options in order, operands,
// no abbreviations, and a command asking for an option it never declared is a bug.
TEST(CommandTable, ARowParsesItsOptions) {
  static std::vector<std::string> seen;
  Command c;
  c.name = "probe";
  c.max_operands = -1;
  c.options = {opt::text("out", "DIR", "folder", "here"), opt::integer("jobs", "J", "jobs", "3"),
               opt::real("x", "X", "a real", "0.25"), opt::repeated("set", "K=V", "keys"),
               opt::flag("force", "force")};
  c.run = [](const Args& a) {
    seen = {a.text("out"), std::to_string(a.integer("jobs")), std::to_string(a.real("x")),
            a.given("out") ? "given" : "default", a.has("force") ? "force" : "-"};
    for (const auto& s : a.texts("set")) seen.push_back(s);
    for (const auto& s : a.operands()) seen.push_back(s);
    return 7;
  };
  EXPECT_EQ(run_command(c, {"A", "--set", "k=1", "B", "--set", "k=2", "--jobs", "5"}), 7);
  EXPECT_EQ(seen, (std::vector<std::string>{"here", "5", "0.250000", "default", "-", "k=1", "k=2",
                                            "A", "B"}));
  EXPECT_EQ(run_command(c, {"--out", "there", "--force"}), 7);
  EXPECT_EQ(seen[0], "there");
  EXPECT_EQ(seen[3], "given");
  EXPECT_EQ(seen[4], "force");
  EXPECT_THROW(run_command(c, {"--for"}), Error);           // not --force
  EXPECT_THROW(run_command(c, {"--jobs", "many"}), Error);  // not an integer
  c.run = [](const Args& a) { return a.has("forse") ? 1 : 0; };
  EXPECT_THROW(run_command(c, {}), std::logic_error);
}

}  // namespace
}  // namespace bkq
