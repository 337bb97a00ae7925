// The replayed event start: an event's first steps taken from the lone block's recorded
// slide (engine/lone_slip.hpp) up to the step at which the block sticks or a neighbour
// breaks loose, where rounding cannot change the outcome. Chains with nearest-neighbour
// springs and lattices (any stencil in the plane: a record per stiffness of a site, its
// partners tested each with its spring); no dashpots, no moving pad; Crossing schemes and
// transitions located on fixed steps (a neighbour's failure then left to the general step).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/lone_slip.hpp"
#include "engine/relaxation.hpp"

namespace bkq {

class ReplayPath final : public RelaxationPath {
 public:
  const char* name() const override { return "replay"; }
  // Applies at the first step of an event only.
  bool advance(Relaxation& rx, PathReport& out) override;

  // Events started from the record (a study count): all of them, those it finished there
  // (no neighbour broke loose), the steps it took from it, and the events it could have
  // started there but left to the integration because a decision lay within the rounding
  // bound; located, also those where a neighbour fails in the first step (nothing to
  // replay: the general path locates the failure).
  struct Starts {
    std::int64_t replayed = 0, finished = 0, steps = 0, declined = 0, immediate = 0;
  };
  const Starts& starts() const { return starts_; }

 private:
  // The record for block j of a chain or site j of a lattice (built when first needed),
  // with partners_ set to the blocks its slide pulls on.
  const LoneSlip& chain_lone_slip(const Relaxation& rx, int j);
  const LoneSlip& lattice_lone_slip(const Relaxation& rx, int j);

  // The lone slip of an interior block [0] and of a block at a free chain end [1], built
  // when first needed.
  LoneSlip lone_[2];
  bool lone_built_[2] = {false, false};
  // A lattice's records, one per stiffness met (interior, edge and corner sites), and the
  // largest sum of a site's springs (the rounding bound's, lone_slip_tolerance).
  std::vector<LoneSlip> lattice_lone_;
  double lattice_coupled_ = 0;
  // The blocks a lone block's slide pulls on, the spring to each and the step at which each
  // breaks loose (past the record: never).
  struct Partner {
    int site = 0;
    double k = 0;
    std::int64_t breaks_at = 0;
  };
  std::vector<Partner> partners_;
  std::vector<int> released_;
  Starts starts_;
};

}  // namespace bkq
