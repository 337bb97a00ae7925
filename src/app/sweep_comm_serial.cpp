// The sweep's ranks without MPI (see sweep_comm.hpp): compiled only when the build does not
// find Boost.MPI and MPI (CMakeLists.txt, bkquake_extra_unit), in place of sweep_comm_mpi.cpp.
// A sweep runs as one rank, and refuses to run as several copies under mpirun.
#include <string>

#include "app/sweep_comm.hpp"
#include "core/error.hpp"

namespace bkq {

bool mpi_available() {
  return false;
}

std::unique_ptr<SweepComm> make_sweep_comm(std::string& note) {
  const int launched = launcher_world_size();
  if (launched > 1)
    throw Error("this bkquake was built without MPI (install libboost-mpi-dev and " +
                std::string("libopenmpi-dev, then rebuild), but was started as ") +
                std::to_string(launched) +
                " ranks: the copies would write one folder; run it without mpirun");
  note = "one rank: this bkquake was built without MPI";
  return make_one_rank_comm();
}

}  // namespace bkq
