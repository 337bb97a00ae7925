// The blocks an event's relaxation integrates: the covered ranges (every sliding block and
// the stuck blocks its springs reach), and the force tree over all the others, which
// answers "which stuck block fails next" while they are not integrated.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/force_tree.hpp"
#include "model/chain.hpp"

namespace bkq {

class ActiveSet {
 public:
  // margin: the stuck neighbours covered on each side of a sliding block on a chain (a
  // lattice covers a site's stencil partners); pad: the pad moves, so the tree is asked
  // during the event and a covered block is taken out of it.
  ActiveSet(const ChainForces& forces, int margin, bool pad);

  Ranges ranges() const { return ranges_; }
  const ForceTree& tree() const { return tree_; }
  // Every block in the tree, none covered.
  void rebuild_tree(const ChainState& st);
  // Covers block j and the neighbours it reaches.
  void cover(int j);
  // Re-fits the ranges to the sliding blocks; the blocks left go back into the tree.
  void shrink(const ChainState& st);
  // Uncovers everything (the end of an event, or the pad's free swing).
  void uncover_all(const ChainState& st);
  // How many times uncover_all has run: changes at the end of each event.
  std::uint64_t uncovers() const { return uncovers_; }

 private:
  void add_to_ranges(int k);

  const ChainForces& forces_;
  int n_, margin_;
  bool pad_;
  ForceTree tree_;
  std::vector<Range> ranges_;
  std::vector<unsigned char> covered_, need_;
  std::uint64_t uncovers_ = 0;
};

}  // namespace bkq
