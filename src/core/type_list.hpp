// A compile-time list of types, for registries whose entries are types (the friction
// laws, model/law_list.hpp): the position of a type, the type at a position, and a call
// with the type at a run-time position as a template argument.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>

namespace bkq {

template <class... Ts>
struct TypeList {
  static constexpr int size = static_cast<int>(sizeof...(Ts));

  // Position of T in the list (a compile error if T is not in it).
  template <class T>
  static constexpr int index_of() {
    constexpr bool match[] = {std::is_same_v<T, Ts>...};
    for (int i = 0; i < size; ++i)
      if (match[i]) return i;
    static_assert((std::is_same_v<T, Ts> || ...), "the type is not in the list");
    return -1;
  }

  template <template <class...> class Into>
  using apply = Into<Ts...>;

  // f.template operator()<T>() with T the type at `index`; the last type when index is
  // out of range (callers check the index where it comes from outside).
  template <class F>
  static decltype(auto) visit(int index, F&& f) {
    return visit_from<0, Ts...>(index, f);
  }

 private:
  template <int I, class T, class... Rest, class F>
  static decltype(auto) visit_from(int index, F& f) {
    if constexpr (sizeof...(Rest) == 0) {
      return f.template operator()<T>();
    } else {
      if (index == I) return f.template operator()<T>();
      return visit_from<I + 1, Rest...>(index, f);
    }
  }
};

}  // namespace bkq
