// The linear basis on a Cartesian cell: at random points, including points
// on and next to the cell faces, the weights are non-negative, sum to one
// (partition of unity) and reproduce linear functions (linear
// completeness), and the gradients sum to zero and reproduce the gradient
// of a linear function. The program prints the largest defects and fails if
// one exceeds 1e-13.
#include <deal.II/base/point.h>

#include <mpm/basis.h>

#include <algorithm>
#include <iostream>
#include <random>

using namespace dealii;

template <int dim>
bool
check()
{
  using Basis = mpm::LinearBasis<dim>;
  std::mt19937                           rng(42);
  std::uniform_real_distribution<double> unit(0., 1.);
  Tensor<1, dim>                         h, inv_h, a;
  Point<dim>                             origin;
  for (unsigned int d = 0; d < dim; ++d)
    {
      h[d]      = 0.1 * (d + 1);
      inv_h[d]  = 1. / h[d];
      origin[d] = -0.3 + d;
      a[d]      = 1.5 - d; // the linear function f(x) = 2 + a.x
    }
  double unity = 0, linear = 0, gradient_sum = 0, gradient = 0, min_weight = 1;
  std::array<double, Basis::n_nodes>         w;
  std::array<Tensor<1, dim>, Basis::n_nodes> g;
  for (unsigned int k = 0; k < 10000; ++k)
    {
      Point<dim> xi;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double r = unit(rng);
          // A quarter of the coordinates on or next to a face.
          xi[d] = k % 4 == 0 ? (r < 0.5 ? 0. : 1.) : k % 4 == 1 ? 1e-12 * r : r;
        }
      Basis::evaluate(xi, inv_h, w, g);
      double         sum = 0, f = 0;
      Tensor<1, dim> gsum, gf;
      Point<dim>     x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = origin[d] + xi[d] * h[d];
      for (unsigned int v = 0; v < Basis::n_nodes; ++v)
        {
          Point<dim> node = origin;
          for (unsigned int d = 0; d < dim; ++d)
            node[d] += ((v >> d) & 1u) * h[d];
          const double f_node = 2 + a * node;
          sum += w[v];
          f += w[v] * f_node;
          gsum += g[v];
          gf += f_node * g[v];
          min_weight = std::min(min_weight, w[v]);
        }
      unity        = std::max(unity, std::abs(sum - 1));
      linear       = std::max(linear, std::abs(f - (2 + a * x)));
      gradient_sum = std::max(gradient_sum, gsum.norm());
      gradient     = std::max(gradient, (gf - a).norm());
    }
  std::cout << dim << "D: |sum w - 1| " << unity << ", linear field " << linear
            << ", |sum grad w| " << gradient_sum << ", linear gradient "
            << gradient << ", min weight " << min_weight << std::endl;
  return unity < 1e-13 && linear < 1e-13 && gradient_sum < 1e-12 &&
         gradient < 1e-12 && min_weight >= 0;
}

int
main()
{
  const bool ok = check<1>() && check<2>() && check<3>();
  std::cout << (ok ? "passed" : "FAILED") << std::endl;
  return ok ? 0 : 1;
}
