#pragma once
// Index of a type in a pack: the position of a law among a simulation's laws, of a parameter set among theirs.

#include <cstddef>
#include <type_traits>

namespace blockdem {

/// The position of T in Ts..., or sizeof...(Ts) if it is not there.
template <class T, class... Ts>
consteval std::size_t index_in() {
  constexpr bool same[] = {std::is_same_v<T, Ts>..., false};
  for (std::size_t i = 0; i < sizeof...(Ts); ++i)
    if (same[i]) return i;
  return sizeof...(Ts);
}

}  // namespace blockdem
