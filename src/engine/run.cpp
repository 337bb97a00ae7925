// Development placeholder: replaced by the drivers in this folder.
#include "engine/run.hpp"

#include "io/error.hpp"

namespace bkq {

int run_scene(const RunRequest&) { throw Error("run: the simulation drivers are not built yet"); }

}  // namespace bkq
