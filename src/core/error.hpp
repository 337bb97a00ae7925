// The one error type of bkquake. Anything the user can get wrong (a scene key, a value,
// a file, an output folder) is reported by throwing bkq::Error with a one-line message
// that names the key or file, the value and what is allowed; main() prints it and exits 2.
#pragma once

#include <stdexcept>
#include <string>

namespace bkq {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Exit status for bad input (user error), as docs/reference/commands.md promises.
inline constexpr int kExitBadInput = 2;

}  // namespace bkq
