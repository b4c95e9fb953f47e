// A consumer of blockdem: fits the paper's Maxwell branches and checks 1 + sum alpha (paper Fig. 10b: 1.39).
#include <blockdem/blockdem.hpp>
#include <cmath>
#include <cstdio>

int main() {
  blockdem::damping::MaxwellFitOptions options;
  options.damping_ratio = 0.04;
  const auto fit = blockdem::damping::fit_maxwell(options);
  std::printf("1 + sum alpha = %.4f\n", 1.0 + fit.sum_alpha);
  return fit.converged && std::abs(1.0 + fit.sum_alpha - 1.39) < 0.01 ? 0 : 1;
}
