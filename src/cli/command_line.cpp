// A command row turned into a parser (boost::program_options, the one file that includes
// it), into the synopsis and into the --help text; see commands.hpp.
#include <algorithm>
#include <boost/program_options.hpp>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <utility>

#include "cli/commands.hpp"
#include "core/error.hpp"

namespace bkq {

namespace po = boost::program_options;

Option Option::required() const {
  Option o = *this;
  o.is_required = true;
  return o;
}

Option Option::hidden() const {
  Option o = *this;
  o.is_hidden = true;
  return o;
}

namespace opt {
namespace {
Option make(Option::Kind kind, std::string name, std::string value, std::string help,
            std::string dflt) {
  Option o;
  o.kind = kind;
  o.name = std::move(name);
  o.value = std::move(value);
  o.help = std::move(help);
  o.default_value = std::move(dflt);
  return o;
}
}  // namespace

Option flag(std::string name, std::string help) {
  return make(Option::Kind::Flag, std::move(name), "", std::move(help), "");
}
Option text(std::string name, std::string value, std::string help, std::string dflt) {
  return make(Option::Kind::Text, std::move(name), std::move(value), std::move(help),
              std::move(dflt));
}
Option integer(std::string name, std::string value, std::string help, std::string dflt) {
  return make(Option::Kind::Integer, std::move(name), std::move(value), std::move(help),
              std::move(dflt));
}
Option integer64(std::string name, std::string value, std::string help, std::string dflt) {
  return make(Option::Kind::Integer64, std::move(name), std::move(value), std::move(help),
              std::move(dflt));
}
Option real(std::string name, std::string value, std::string help, std::string dflt) {
  return make(Option::Kind::Real, std::move(name), std::move(value), std::move(help),
              std::move(dflt));
}
Option repeated(std::string name, std::string value, std::string help) {
  return make(Option::Kind::Repeated, std::move(name), std::move(value), std::move(help), "");
}
}  // namespace opt

struct Args::Values {
  po::variables_map vm;
};

Args::Args(const Command& command, std::shared_ptr<const Values> values)
    : command_(&command), values_(std::move(values)) {}

const std::string& Args::command() const {
  return command_->name;
}

const Option& Args::declared(const std::string& name) const {
  for (const Option& o : command_->options)
    if (o.name == name) return o;
  throw std::logic_error(command_->name + " asks for --" + name + ", which it does not declare");
}

bool Args::has(const std::string& name) const {
  declared(name);
  return values_->vm.count(name) > 0;
}

bool Args::given(const std::string& name) const {
  return has(name) && !values_->vm[name].defaulted();
}

std::string Args::text(const std::string& name) const {
  declared(name);
  return values_->vm[name].as<std::string>();
}
int Args::integer(const std::string& name) const {
  declared(name);
  return values_->vm[name].as<int>();
}
std::int64_t Args::integer64(const std::string& name) const {
  declared(name);
  return values_->vm[name].as<std::int64_t>();
}
double Args::real(const std::string& name) const {
  declared(name);
  return values_->vm[name].as<double>();
}
std::vector<std::string> Args::texts(const std::string& name) const {
  if (!has(name)) return {};
  return values_->vm[name].as<std::vector<std::string>>();
}

namespace {

// The operands' key in the parser (no option is named so).
constexpr const char* kOperands = "operands";

}  // namespace

std::vector<std::string> Args::operands() const {
  if (!values_->vm.count(kOperands)) return {};
  const auto& v = values_->vm[kOperands].value();
  if (const auto* one = boost::any_cast<std::string>(&v)) return {*one};
  return boost::any_cast<std::vector<std::string>>(v);
}

namespace {

// The option as the parser takes it, its default typed as the option is.
void add_to_parser(po::options_description& opts, const Option& o) {
  const std::string& d = o.default_value;
  switch (o.kind) {
    case Option::Kind::Flag:
      opts.add_options()(o.name.c_str(), "");
      return;
    case Option::Kind::Text: {
      auto* v = po::value<std::string>();
      if (!d.empty()) v->default_value(d);
      opts.add_options()(o.name.c_str(), v, "");
      return;
    }
    case Option::Kind::Integer: {
      auto* v = po::value<int>();
      if (!d.empty()) v->default_value(std::stoi(d), d);
      opts.add_options()(o.name.c_str(), v, "");
      return;
    }
    case Option::Kind::Integer64: {
      auto* v = po::value<std::int64_t>();
      if (!d.empty()) v->default_value(std::stoll(d), d);
      opts.add_options()(o.name.c_str(), v, "");
      return;
    }
    case Option::Kind::Real: {
      auto* v = po::value<double>();
      if (!d.empty()) v->default_value(std::strtod(d.c_str(), nullptr), d);
      opts.add_options()(o.name.c_str(), v, "");
      return;
    }
    case Option::Kind::Repeated:
      opts.add_options()(o.name.c_str(), po::value<std::vector<std::string>>()->composing(), "");
      return;
  }
}

// "[--out DIR]", "--out DIR", "[--set section.key=value]...", "[--force]".
std::string synopsis_item(const Option& o) {
  std::string item = "--" + o.name + (o.value.empty() ? "" : " " + o.value);
  if (!o.is_required) item = "[" + item + "]";
  if (o.kind == Option::Kind::Repeated) item += "...";
  return item;
}

// `items` joined by spaces after `head`, wrapped at `width`, continuation lines indented
// to line up after `head` (or by 4 when `head` is too long for that).
std::string wrap_items(const std::string& head, const std::vector<std::string>& items,
                       std::size_t width) {
  const std::size_t indent = head.size() + 1 <= width / 2 ? head.size() + 1 : 4;
  std::string out = head;
  std::size_t column = head.size();
  for (const auto& item : items) {
    if (column > indent && column + 1 + item.size() > width) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
    } else if (!out.empty()) {
      out += " ";
      ++column;
    }
    out += item;
    column += item.size();
  }
  return out;
}

// Words of `text` wrapped at `width`, each line after the first indented by `indent`;
// the first line starts at `column`.
std::string wrap_words(const std::string& text, std::size_t column, std::size_t indent,
                       std::size_t width) {
  std::string out;
  std::size_t at = 0;
  bool first_word = true;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    const std::string word = text.substr(at, end - at);
    at = end + 1;
    if (word.empty()) continue;
    if (!first_word && column + 1 + word.size() > width) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
    } else if (!first_word) {
      out += " ";
      ++column;
    }
    out += word;
    column += word.size();
    first_word = false;
  }
  return out;
}

// The synopsis after `head` ("bkquake fit", "Usage: bkquake fit").
std::string synopsis_after(const std::string& head, const Command& command, std::size_t width) {
  std::vector<std::string> items;
  if (!command.operands.empty()) items.push_back(command.operands);
  for (const Option& o : command.options)
    if (!o.is_hidden) items.push_back(synopsis_item(o));
  return wrap_items(head, items, width);
}

}  // namespace

std::string synopsis(const Command& command, std::size_t width) {
  return synopsis_after("bkquake " + command.name, command, width);
}

std::string help_text(const Command& command) {
  constexpr std::size_t kWidth = 88;
  std::string out = synopsis_after("Usage: bkquake " + command.name, command, kWidth) + "\n" +
                    command.about + "\nOptions:\n";
  // Two columns: "  --name VALUE" and the help, which starts on the next line when the
  // first column is wider than kColumn.
  constexpr std::size_t kColumn = 26;
  const auto row = [&](const std::string& left, std::string help) {
    std::string line = "  " + left;
    if (line.size() + 2 > kColumn) {
      out += line + '\n';
      out.append(kColumn, ' ');
    } else {
      out += line;
      out.append(kColumn - line.size(), ' ');
    }
    out += wrap_words(help, kColumn, kColumn, kWidth) + "\n";
  };
  for (const Option& o : command.options) {
    if (o.is_hidden) continue;
    std::string help = o.help;
    if (!o.default_value.empty()) help += " (default: " + o.default_value + ")";
    if (o.kind == Option::Kind::Repeated) help += " (repeatable)";
    row("--" + o.name + (o.value.empty() ? "" : " " + o.value), help);
  }
  row("-h, --help", "show this help");
  return out;
}

int run_command(const Command& command, const std::vector<std::string>& args) {
  po::options_description opts;
  opts.add_options()("help,h", "");
  for (const Option& o : command.options) add_to_parser(opts, o);
  po::positional_options_description positional;
  if (command.max_operands == 1)
    opts.add_options()(kOperands, po::value<std::string>(), "");
  else if (command.max_operands != 0)
    opts.add_options()(kOperands, po::value<std::vector<std::string>>(), "");
  if (command.max_operands != 0) positional.add(kOperands, command.max_operands);
  auto values = std::make_shared<Args::Values>();
  try {
    // No abbreviations: `--for` silently meaning --force would be a surprise.
    const int style = po::command_line_style::unix_style & ~po::command_line_style::allow_guessing;
    po::store(po::command_line_parser(args).options(opts).positional(positional).style(style).run(),
              values->vm);
    po::notify(values->vm);
  } catch (const po::error& e) {
    throw Error(command.name + ": " + e.what() + "; try 'bkquake " + command.name + " --help'");
  }
  if (values->vm.count("help")) {
    std::cout << help_text(command);
    return 0;
  }
  return command.run(Args(command, std::move(values)));
}

}  // namespace bkq
