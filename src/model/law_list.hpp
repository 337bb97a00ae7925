// The friction laws' registry: the list of their policy types, one file each under
// model/laws/ (model/friction_laws.hpp includes them and says what a law supplies). A
// law's place in the list is its run-time id (FrictionLaw), its `name` the scene's
// keyword. Naming a type in the list declares it, so a new law is its file, one entry
// here and its #include in model/friction_laws.hpp.
#pragma once

#include "core/type_list.hpp"

namespace bkq {

namespace law {
using All = TypeList<struct Thesis, struct Clst91, struct Cl89, struct None, struct Table>;
}  // namespace law

// Which law a scene uses: its place in law::All.
struct FrictionLaw {
  int index = 0;

  template <class Law>
  static constexpr FrictionLaw of() {
    return FrictionLaw{law::All::index_of<Law>()};
  }
  friend constexpr bool operator==(FrictionLaw, FrictionLaw) = default;
};

template <class Law>
inline constexpr FrictionLaw law_id = FrictionLaw::of<Law>();

}  // namespace bkq
