// The friction laws: their policy types (model/laws/, listed in model/law_list.hpp), the
// name table and the dispatch from a scene's law (FrictionLaw, a run-time id) to the
// kernels instantiated for its type (ChainForces::with_switches, model/chain.hpp).
//
// What a law supplies (see model/laws/thesis.hpp):
//   name             its friction.law keyword
//   backslip         may a block slide against the substrate (y < 0)?
//   frictionless     nothing ever holds a block (its threshold is below 0)
//   drives_events    can event-driven runs use it at all (cluster paths are compiled for it)?
//   Law(params)      its numbers from the model parameters
//   threshold        the static threshold on the spring force (a member)
//   magnitude(y)     |phi(y)| per unit mass for a block sliding at relative velocity y
//   check_events(p)  throws Error when event-driven runs cannot use it with these numbers
// Laws of the velocity-weakening family derive from law::Rational (model/laws/rational.hpp),
// which the theta scheme needs.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "model/friction.hpp"
#include "model/law_list.hpp"
#include "model/laws/cl89.hpp"
#include "model/laws/clst91.hpp"
#include "model/laws/none.hpp"
#include "model/laws/table.hpp"
#include "model/laws/thesis.hpp"
#include "model/parameters.hpp"

namespace bkq {

// One law's numbers, whichever the scene chose.
using LawVariant = law::All::apply<std::variant>;

// f.template operator()<Law>() with the type of the law `id`.
template <class F>
decltype(auto) visit_law(FrictionLaw id, F&& f) {
  return law::All::visit(id.index, f);
}

inline LawVariant make_law(const ModelParams& p) {
  return visit_law(p.law, [&]<class L>() { return LawVariant(std::in_place_type<L>, p); });
}

// The static side of the scene's law (threshold and backslip).
inline Friction friction_of(const ModelParams& p) {
  return visit_law(p.law, [&]<class L>() { return Friction{L(p).threshold, L::backslip}; });
}

// A law's compile-time flags, for code that reads them at run time.
struct LawTraits {
  std::string_view name;
  bool backslip = true;
  bool frictionless = false;
  bool drives_events = true;
};
namespace law_detail {
template <class... Ls>
constexpr std::array<LawTraits, sizeof...(Ls)> traits_of(TypeList<Ls...>) {
  return {LawTraits{Ls::name, Ls::backslip, Ls::frictionless, Ls::drives_events}...};
}
inline constexpr auto kTraits = traits_of(law::All{});
}  // namespace law_detail

// An id out of range reads as the list's last law (ids come from law_named or law_id).
inline const LawTraits& law_traits(FrictionLaw id) {
  const auto i = static_cast<std::size_t>(id.index);
  return law_detail::kTraits[i < law_detail::kTraits.size() ? i : law_detail::kTraits.size() - 1];
}
inline std::string_view law_name(FrictionLaw id) {
  return law_traits(id).name;
}
// The same as a C string (the names are literals).
inline const char* to_string(FrictionLaw id) {
  return law_name(id).data();
}
// The law with this keyword, if any.
std::optional<FrictionLaw> law_named(std::string_view name);
// Every keyword, in the list's order.
std::vector<std::string> law_names();

// Throws Error when event-driven runs cannot use the scene's law with its numbers.
inline void check_law_drives_events(const ModelParams& p) {
  visit_law(p.law, [&]<class L>() { L::check_events(p); });
}

}  // namespace bkq
