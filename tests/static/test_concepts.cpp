// Positive and negative static_asserts for the solver's problem concepts.

#include <doctest/doctest.h>

#include "blockdem/damping/maxwell_fit.hpp"
#include "blockdem/solve/levenberg_marquardt.hpp"

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_concepts {

namespace {
using blockdem::solve::Vector;

struct ResidualsOnly {
  static constexpr int num_parameters = 1;
  int num_residuals() const { return 1; }
  Vector<1> prepare(const Vector<1>& x) const { return x; }
  double residual(const Vector<1>& x, int) const { return x[0]; }
};
struct WithJacobian : ResidualsOnly {
  using ResidualsOnly::residual;
  double residual(const Vector<1>& x, int, Vector<1>& g) const {
    g[0] = 1;
    return x[0];
  }
};
struct NoPrepare {
  static constexpr int num_parameters = 1;
  int num_residuals() const { return 1; }
  double residual(const Vector<1>& x, int) const { return x[0]; }
};
struct NoParameters {
  static constexpr int num_parameters = 0;
  int num_residuals() const { return 1; }
  Vector<0> prepare(const Vector<0>& x) const { return x; }
  double residual(const Vector<0>&, int) const { return 0; }
};
}  // namespace

static_assert(blockdem::solve::LeastSquaresProblem<ResidualsOnly>);
static_assert(!blockdem::solve::HasAnalyticJacobian<ResidualsOnly>);
static_assert(blockdem::solve::HasAnalyticJacobian<WithJacobian>);
static_assert(!blockdem::solve::LeastSquaresProblem<NoPrepare>);
static_assert(!blockdem::solve::LeastSquaresProblem<NoParameters>);
static_assert(!blockdem::solve::LeastSquaresProblem<int>);
static_assert(blockdem::solve::HasAnalyticJacobian<blockdem::damping::detail::MaxwellFitProblem<3>>);
static_assert(blockdem::solve::HasAnalyticJacobian<blockdem::damping::detail::MaxwellFitProblem<8>>);

TEST_CASE("static: the problem concepts accept and reject what they should (checked at compile time)") { CHECK(true); }

}  // namespace test_concepts
