// The cluster kernel: while the sliding blocks lie within one covered range of at most
// kMaxCluster interior blocks whose ends hold, the scheme's fixed-size form steps it
// (integrate/cluster.hpp). The same events bit for bit, in less time.
#pragma once

#include <cstdint>

#include "engine/relaxation.hpp"
#include "integrate/cluster.hpp"

namespace bkq {

class ClusterPath final : public RelaxationPath {
 public:
  const char* name() const override { return "cluster"; }
  bool advance(Relaxation& rx, PathReport& out) override;

  // Steps taken here (a study count): all of them, and those with more than one block
  // between the ends.
  struct Steps {
    std::int64_t all = 0, multi_block = 0;
  };
  const Steps& steps() const { return steps_; }

 private:
  // Whether the covered blocks form a cluster; if so, sets its shape in r.
  static bool ready(const Relaxation& rx, ClusterRelaxation& r);

  Steps steps_;
  int released_[kMaxCluster + 2] = {};
};

}  // namespace bkq
