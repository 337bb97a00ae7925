// The friction laws' name table, from the list (model/law_list.hpp).
#include "model/friction_laws.hpp"

namespace bkq {

std::optional<FrictionLaw> law_named(std::string_view name) {
  for (int i = 0; i < law::All::size; ++i)
    if (law_traits(FrictionLaw{i}).name == name) return FrictionLaw{i};
  return std::nullopt;
}

std::vector<std::string> law_names() {
  std::vector<std::string> names;
  for (int i = 0; i < law::All::size; ++i) names.emplace_back(law_traits(FrictionLaw{i}).name);
  return names;
}

}  // namespace bkq
