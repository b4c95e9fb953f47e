#pragma once
// The benchmarks' walk over the shipped joint laws and damping policies (contact::ShippedLaws,
// damping::ShippedPolicies): each benchmark runs the types of the lists it has a row for, and names each type once.

#include <string>
#include <tuple>
#include <type_traits>

#include "blockdem/io/checkpoint.hpp"

namespace blockdem::benchmarks {

/// false, for any T: the else branch of a per-type `if constexpr` chain that must name every shipped type.
template <class T>
inline constexpr bool unlisted = false;

/// Calls f(std::type_identity<T>{}) for each type T of the tuple, in its order.
template <class Tuple, class F>
void for_each_type(F&& f) {
  [&]<class... T>(std::type_identity<std::tuple<T...>>) { (f(std::type_identity<T>{}), ...); }(std::type_identity<Tuple>{});
}

/// The type's name without the library's namespace, as the benchmarks print it: "contact::Elastic",
/// "damping::Maxwell<3>".
template <class T>
std::string short_name() {
  std::string name = io::type_name<T>();
  const std::string prefix = "blockdem::";
  for (auto at = name.find(prefix); at != std::string::npos; at = name.find(prefix)) name.erase(at, prefix.size());
  return name;
}

}  // namespace blockdem::benchmarks
