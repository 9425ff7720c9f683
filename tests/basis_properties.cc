// Every basis, on small grids (2 and 3 cells per direction, so that most
// points sit next to the boundary where the kernels are folded), at random
// points and at points on and next to cell faces and the walls:
//  - weights are non-negative and sum to one (partition of unity),
//  - they reproduce linear functions and their gradients (linear
//    completeness), and the gradients sum to zero,
//  - the gradients are the derivatives of the weights (central differences
//    of a smooth interpolated field),
//  - APIC's affine weights recover the gradient A of any affine field
//    A x + b exactly (to 1e-9: within 1e-12 cells of a wall, the folded
//    weights are exact to round-off in absolute terms only, and APIC
//    divides by their second moment, which tends to zero there),
//  - a point on a wall is carried by the wall node alone (B-splines and
//    linear), so a fixed wall holds,
//  - inside the grid (stencils away from the walls' folded kernels),
//    Basis::gradient_vanishes_with_weight holds: if true, a node whose
//    weight is below 1e-6 has no gradient component above 1e-2 per cell;
//    if false (linear), some such node has one above 0.5 (APIC leaves
//    those nodes' force increments out, see
//    TimeIntegrator::discount_light_node_increments). At a wall the folded
//    B-splines are like the linear hat (a point on the wall has weight 0
//    and a full gradient at the next node), which the program prints.
// The program prints the largest defects and fails if one exceeds its
// bound.
#include <deal.II/base/point.h>

#include <mpm/basis.h>

#include <algorithm>
#include <iostream>
#include <random>
#include <string>

using namespace dealii;

struct Defects
{
  double unity = 0, linear = 0, gradient_sum = 0, linear_gradient = 0,
         derivative = 0, affine = 0, wall = 0, min_weight = 1;

  bool
  acceptable() const
  {
    return unity < 1e-13 && linear < 1e-13 && gradient_sum < 1e-11 &&
           linear_gradient < 1e-11 && derivative < 1e-5 && affine < 1e-9 &&
           wall < 1e-15 && min_weight > -1e-15;
  }
};


template <int dim, typename Basis>
Defects
check(const double half_width, const bool interpolates_at_walls)
{
  std::mt19937                           rng(42);
  std::uniform_real_distribution<double> unit(0., 1.);
  std::array<unsigned int, dim>          n_cells;
  Tensor<1, dim>                         h, a;
  Tensor<2, dim>                         A;
  Point<dim>                             origin;
  for (unsigned int d = 0; d < dim; ++d)
    {
      n_cells[d] = 2 + d % 2;
      h[d]       = 0.1 * (d + 1);
      origin[d]  = -0.3 + d;
      a[d]       = 1.5 - d; // f(x) = 2 + a.x
      for (unsigned int e = 0; e < dim; ++e)
        A[d][e] = 0.3 * d - 0.7 * e + 0.1; // v(x) = A x + a
    }
  const Basis    basis(n_cells, h);
  Tensor<1, dim> l;
  for (unsigned int d = 0; d < dim; ++d)
    l[d] = half_width;

  auto node_position = [&](unsigned int node) {
    Point<dim> x = origin;
    for (unsigned int d = 0; d < dim; ++d)
      {
        x[d] += (node % (n_cells[d] + 1)) * h[d];
        node /= n_cells[d] + 1;
      }
    return x;
  };
  auto smooth = [](const Point<dim> &x) {
    double f = 1;
    for (unsigned int d = 0; d < dim; ++d)
      f *= std::sin(1.3 * x[d] + d);
    return f;
  };
  // The nodes by their lexicographic index in the grid of nodes.
  auto node_index = [&](const std::array<unsigned int, dim> &node) {
    unsigned int index = 0;
    for (int d = dim - 1; d >= 0; --d)
      index = index * (n_cells[d] + 1) + node[d];
    return index;
  };
  // The interpolant sum w_I g(x_I) of a smooth g at a point.
  auto interpolate = [&](const std::array<unsigned int, dim> &cell,
                         const Point<dim>                    &xi) {
    typename Basis::Stencil                  s;
    std::array<unsigned int, Basis::n_nodes> nodes;
    basis.evaluate(cell, xi, l, s);
    basis.node_pattern(cell, s, nodes, node_index);
    s.nodes  = nodes.data();
    double f = 0;
    for (unsigned int v = 0; v < Basis::n_nodes; ++v)
      f += s.weights[v] * smooth(node_position(s.nodes[v]));
    return f;
  };

  Defects                                    e;
  typename Basis::Stencil                    s;
  std::array<Tensor<1, dim>, Basis::n_nodes> affine;
  std::array<unsigned int, Basis::n_nodes>   nodes;
  for (unsigned int k = 0; k < 20000; ++k)
    {
      std::array<unsigned int, dim> cell;
      Point<dim>                    xi;
      for (unsigned int d = 0; d < dim; ++d)
        {
          cell[d] =
            std::min<unsigned int>(unit(rng) * n_cells[d], n_cells[d] - 1);
          const double r = unit(rng);
          // A quarter of the coordinates on or next to a face.
          xi[d] = k % 4 == 0   ? (r < 0.5 ? 0. : 1. - 1e-15)
                  : k % 4 == 1 ? 1e-12 * r
                               : r;
        }
      basis.evaluate(cell, xi, l, s);
      basis.node_pattern(cell, s, nodes, node_index);
      s.nodes = nodes.data();
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = origin[d] + (cell[d] + xi[d]) * h[d];

      double         sum = 0, f = 0;
      Tensor<1, dim> gsum, gf, g_smooth;
      Tensor<2, dim> C;
      basis.affine_weights(s, affine);
      for (unsigned int v = 0; v < Basis::n_nodes; ++v)
        {
          const Point<dim> node   = node_position(s.nodes[v]);
          const double     f_node = 2 + a * node;
          sum += s.weights[v];
          f += s.weights[v] * f_node;
          gsum += s.gradients[v];
          gf += f_node * s.gradients[v];
          g_smooth += smooth(node) * s.gradients[v];
          C += outer_product(Tensor<1, dim>(A * node + a), affine[v]);
          e.min_weight = std::min(e.min_weight, s.weights[v]);
          // The node offsets must agree with the node positions.
          AssertThrow((node - x - s.node_offset(v)).norm() < 1e-12 ||
                        s.weights[v] == 0,
                      ExcInternalError());
        }
      e.unity           = std::max(e.unity, std::abs(sum - 1));
      e.linear          = std::max(e.linear, std::abs(f - (2 + a * x)));
      e.gradient_sum    = std::max(e.gradient_sum, gsum.norm());
      e.linear_gradient = std::max(e.linear_gradient, (gf - a).norm());
      e.affine          = std::max(e.affine, (C - A).norm() / A.norm());

      // Derivatives, by central differences inside the cell.
      if (k % 4 == 2)
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double delta = 1e-6;
            if (xi[d] < 2 * delta || xi[d] > 1 - 2 * delta)
              continue;
            Point<dim> lo = xi, hi = xi;
            lo[d] -= delta;
            hi[d] += delta;
            const double fd = (interpolate(cell, hi) - interpolate(cell, lo)) /
                              (2 * delta * h[d]);
            e.derivative = std::max(e.derivative, std::abs(fd - g_smooth[d]));
          }

      // A point on a wall: only the wall node carries it.
      if (interpolates_at_walls && k % 4 == 0)
        {
          bool on_wall = true;
          for (unsigned int d = 0; d < dim; ++d)
            on_wall = on_wall && ((cell[d] == 0 && xi[d] == 0.));
          if (on_wall)
            {
              double off_wall = 0;
              for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                if (s.nodes[v] != 0)
                  off_wall += std::abs(s.weights[v]);
              e.wall = std::max(e.wall, off_wall);
            }
        }
    }
  return e;
}


/**
 * The largest gradient component (per cell) of a node whose weight is
 * below 1e-6, at random points and points on or next to cell faces in the
 * cells @p first to @p last - 1 of a grid of 8 cells per direction.
 */
template <int dim, typename Basis>
double
light_node_gradient(const double       half_width,
                    const unsigned int first,
                    const unsigned int last)
{
  std::mt19937                           rng(7);
  std::uniform_real_distribution<double> unit(0., 1.);
  std::array<unsigned int, dim>          n_cells;
  Tensor<1, dim>                         h, l;
  for (unsigned int d = 0; d < dim; ++d)
    {
      n_cells[d] = 8;
      h[d]       = 0.1 * (d + 1);
      l[d]       = half_width;
    }
  const Basis             basis(n_cells, h);
  typename Basis::Stencil s;
  double                  largest = 0;
  for (unsigned int k = 0; k < 20000; ++k)
    {
      std::array<unsigned int, dim> cell;
      Point<dim>                    xi;
      for (unsigned int d = 0; d < dim; ++d)
        {
          cell[d] = first + std::min<unsigned int>(unit(rng) * (last - first),
                                                   last - first - 1);
          const double r = unit(rng);
          xi[d]          = k % 3 == 0 ? 0. : k % 3 == 1 ? 1e-12 * r : r;
        }
      basis.evaluate(cell, xi, l, s);
      for (unsigned int v = 0; v < Basis::n_nodes; ++v)
        if (s.weights[v] < 1e-6)
          for (unsigned int d = 0; d < dim; ++d)
            largest = std::max(largest, std::abs(s.gradients[v][d]) * h[d]);
    }
  return largest;
}


template <int dim, typename Basis>
bool
report(const std::string &name,
       const double       half_width            = 0,
       const bool         interpolates_at_walls = true)
{
  const Defects e      = check<dim, Basis>(half_width, interpolates_at_walls);
  const double  inside = light_node_gradient<dim, Basis>(half_width, 3, 5);
  const bool    light_ok =
    Basis::gradient_vanishes_with_weight ? inside < 1e-2 : inside > 0.5;
  std::cout << dim << "D " << name << ": |sum w - 1| " << e.unity << ", linear "
            << e.linear << ", |sum grad| " << e.gradient_sum
            << ", linear gradient " << e.linear_gradient << ", derivative "
            << e.derivative << ", affine " << e.affine << ", wall " << e.wall
            << ", min weight " << e.min_weight
            << ", light-node gradient inside " << inside << " (at a wall "
            << light_node_gradient<dim, Basis>(half_width, 0, 1) << ")"
            << (e.acceptable() && light_ok ? "" : "  FAILED") << std::endl;
  return e.acceptable() && light_ok;
}


template <int dim>
bool
check_all()
{
  bool ok = report<dim, mpm::LinearBasis<dim>>("linear");
  for (const double l : {0.5, 0.25, 0.1})
    ok = report<dim, mpm::GIMPBasis<dim>>("GIMP l=" + std::to_string(l),
                                          l,
                                          false) &&
         ok;
  ok = report<dim, mpm::QuadraticBSplineBasis<dim>>("quadratic B-spline") && ok;
  ok = report<dim, mpm::CubicBSplineBasis<dim>>("cubic B-spline") && ok;
  return ok;
}


int
main()
{
  const bool ok = check_all<1>() & check_all<2>() & check_all<3>();
  std::cout << (ok ? "passed" : "FAILED") << std::endl;
  return ok ? 0 : 1;
}
