// Checks the command-line tests share: a refusal (exit 2, one error line naming what was
// wrong) and the bytes of a folder, to show a command left it untouched.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli_helpers.hpp"

namespace bkq::test {

// Exit 2 with exactly one stderr line that contains every one of `parts`.
inline void expect_refused(const ProcessResult& r, const std::vector<std::string>& parts) {
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r.err;
  for (const auto& p : parts)
    EXPECT_NE(lines[0].find(p), std::string::npos) << lines[0] << " lacks " << p;
}

// Every regular file under `dir` (or `dir` itself, if it is a file) with its bytes.
inline std::map<std::string, std::string> tree_bytes(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> files;
  if (!fs::exists(dir)) return files;
  if (fs::is_regular_file(dir)) return {{dir.string(), read_file(dir.string())}};
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[e.path().string()] = read_file(e.path().string());
  return files;
}

}  // namespace bkq::test
