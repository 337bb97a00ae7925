// Implementation of the generated documentation tables (see readme_tables.hpp).
#include "io/readme_tables.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <utility>

#include "core/error.hpp"
#include "io/accuracy_schema.hpp"
#include "io/catalog.hpp"
#include "io/energy_csv.hpp"
#include "io/friction_table.hpp"
#include "io/histogram_csv.hpp"
#include "io/rsf_blocks.hpp"
#include "io/scene.hpp"
#include "io/segments_csv.hpp"
#include "io/seismicity_csv.hpp"
#include "io/spectrum_csv.hpp"
#include "io/stability_csv.hpp"
#include "io/sweep_file.hpp"
#include "io/timeseries.hpp"

namespace bkq {

namespace {

// A table cell: '|' would end the cell, so it is escaped.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

std::string code(const std::string& text) {
  std::string out(1, '`');  // appended, not "`" + ...: GCC 12 warns falsely (-Wrestrict) there
  out += cell(text);
  out += '`';
  return out;
}

}  // namespace

std::string scene_key_table() {
  std::string t =
      "| key | default | allowed | units | meaning |\n"
      "|---|---|---|---|---|\n";
  for (const auto& p : parameter_table())
    t += "| " + code(p.key) + " | " + code(p.default_value) + " | " +
         code(documented_allowed_text(p)) + " | " + cell(p.units) + " | " + cell(p.doc) + " |\n";
  return t;
}

std::string column_table(const Schema& schema) {
  std::string t =
      "| column | units | format | meaning |\n"
      "|---|---|---|---|\n";
  for (const auto& c : schema)
    t += "| " + code(c.name) + " | " + cell(c.units) + " | " + cell(c.format) + " | " +
         cell(c.doc) + " |\n";
  return t;
}

std::vector<ReadmeTable> readme_tables() {
  return {
      {"scene-keys", scene_key_table()},
      {"catalog.csv", column_table(catalog_schema())},
      {"ofc catalog.csv",
       column_table(catalog_schema(CatalogLayout{.topplings = true, .rows = true}))},
      {"rsf catalog.csv", column_table(rsf_catalog_columns())},
      {"slow_slip.csv", column_table(slow_slip_schema())},
      {"ofc event_slip.csv",
       column_table(event_slip_schema(SlipLayout{.rows = true, .topplings = true}))},
      {"histogram.csv", column_table(histogram_schema())},
      {"timeseries.csv", column_table(timeseries_schema())},
      {"timeseries.csv status", column_table(timeseries_status_schema())},
      {"energy.csv", column_table(energy_schema())},
      {"energy_samples.csv", column_table(energy_samples_schema())},
      {"accuracy.csv", column_table(accuracy_schema())},
      {"accuracy_orders.csv", column_table(accuracy_orders_schema())},
      {"segments.csv", column_table(segments_schema())},
      {"spectrum.csv", column_table(spectrum_schema())},
      {"special_law.csv", column_table(special_law_schema())},
      {"sweep.csv", column_table(sweep_csv_schema())},
      {"sweep_fit.csv", column_table(sweep_fit_schema())},
      {"friction_study.csv", column_table(friction_study_schema())},
      {"stability.csv", column_table(stability_schema())},
      {"stability_summary.csv", column_table(stability_summary_schema())},
      {"modes.csv", column_table(modes_schema())},
      {"friction-table.csv", column_table(friction_table_schema())},
  };
}

std::string readme_begin_marker(const std::string& name) {
  return "<!-- begin generated: " + name + " -->";
}
std::string readme_end_marker(const std::string& name) {
  return "<!-- end generated: " + name + " -->";
}

namespace {
// [first character of the block, one past its last) in `readme`.
std::optional<std::pair<std::size_t, std::size_t>> block_range(const std::string& readme,
                                                               const std::string& name) {
  const std::string begin = readme_begin_marker(name) + "\n";
  std::string end(1, '\n');
  end += readme_end_marker(name);
  const auto b = readme.find(begin);
  if (b == std::string::npos) return std::nullopt;
  const auto from = b + begin.size();
  const auto e = readme.find(end, from > 0 ? from - 1 : 0);
  if (e == std::string::npos) return std::nullopt;
  return std::pair{from, std::max(from, e + 1)};
}
}  // namespace

std::optional<std::string> readme_block(const std::string& readme, const std::string& name) {
  const auto r = block_range(readme, name);
  if (!r) return std::nullopt;
  return readme.substr(r->first, r->second - r->first);
}

std::string update_readme(const std::string& readme) {
  std::string out = readme;
  for (const auto& table : readme_tables()) {
    const auto r = block_range(out, table.name);
    if (!r)
      throw Error("README: no '" + readme_begin_marker(table.name) + "' ... '" +
                  readme_end_marker(table.name) +
                  "' block (the generated tables live in docs/: bkquake readme-tables "
                  "--update docs)");
    out.replace(r->first, r->second - r->first, table.markdown);
  }
  return out;
}

std::string update_blocks(const std::string& text, const std::vector<ReadmeTable>& tables,
                          std::vector<std::string>* found) {
  std::string out = text;
  for (const auto& table : tables) {
    const auto r = block_range(out, table.name);
    if (!r) continue;
    out.replace(r->first, r->second - r->first, table.markdown);
    if (found) found->push_back(table.name);
  }
  return out;
}

std::vector<DocPage> read_doc_pages(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw Error("readme-tables: '" + dir.string() + "' is not a folder of markdown pages");
  std::vector<DocPage> pages;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->is_symlink() || !it->is_regular_file() || it->path().extension() != ".md") continue;
    std::ifstream f(it->path(), std::ios::binary);
    if (!f) throw Error("readme-tables: cannot read '" + it->path().string() + "'");
    std::ostringstream text;
    text << f.rdbuf();
    pages.push_back({fs::relative(it->path(), dir).generic_string(), text.str()});
  }
  std::sort(pages.begin(), pages.end(),
            [](const DocPage& a, const DocPage& b) { return a.path < b.path; });
  return pages;
}

const DocPage* page_with_block(const std::vector<DocPage>& pages, const std::string& name) {
  for (const auto& p : pages)
    if (block_range(p.text, name)) return &p;
  return nullptr;
}

std::vector<DocPage> update_doc_pages(const std::vector<DocPage>& pages,
                                      const std::vector<ReadmeTable>& tables) {
  std::vector<DocPage> out;
  std::vector<std::pair<std::string, std::string>> holder;  // table name, page path
  for (const auto& p : pages) {
    std::vector<std::string> found;
    out.push_back({p.path, update_blocks(p.text, tables, &found)});
    for (const auto& name : found) holder.emplace_back(name, p.path);
  }
  for (const auto& table : tables) {
    std::vector<std::string> where;
    for (const auto& [name, path] : holder)
      if (name == table.name) where.push_back(path);
    if (where.empty())
      throw Error("docs: no page holds the block '" + readme_begin_marker(table.name) + "' ... '" +
                  readme_end_marker(table.name) + "'");
    if (where.size() > 1)
      throw Error("docs: the table '" + table.name + "' is in two pages, " + where[0] + " and " +
                  where[1] + "; keep it in one");
  }
  return out;
}

}  // namespace bkq
