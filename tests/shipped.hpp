#pragma once
// Tests that run every shipped law or policy (contact::ShippedLaws, damping::ShippedPolicies), or the part of the list
// a test is about: the subset is chosen per type, in one place, so that a new law or policy is either run or turned
// away with a reason, never forgotten.

#include <tuple>
#include <type_traits>
#include <utility>

namespace blockdem::test {

/// false, for any T: the else branch of a per-type `if constexpr` chain that must name every shipped type.
template <class T>
inline constexpr bool unlisted = false;

namespace detail {
template <template <class> class Keep, class Tuple>
struct Select;
template <template <class> class Keep>
struct Select<Keep, std::tuple<>> {
  using type = std::tuple<>;
};
template <template <class> class Keep, class First, class... Rest>
struct Select<Keep, std::tuple<First, Rest...>> {
  using rest = typename Select<Keep, std::tuple<Rest...>>::type;
  using type = std::conditional_t<Keep<First>::value,
                                  decltype(std::tuple_cat(std::declval<std::tuple<First>>(), std::declval<rest>())), rest>;
};
}  // namespace detail

/// The types T of the tuple for which Keep<T>::value is true, in their order, as a std::tuple (for
/// TEST_CASE_TEMPLATE_APPLY).
template <template <class> class Keep, class Tuple>
using Select = typename detail::Select<Keep, Tuple>::type;

}  // namespace blockdem::test
