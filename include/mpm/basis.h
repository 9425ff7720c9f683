#ifndef mpm_basis_h
#define mpm_basis_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/utilities.h>

#include <mpm/options.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace mpm
{
  using namespace dealii;

  /// The shape functions that connect material points and grid nodes.
  enum class BasisType
  {
    linear,            ///< FE_Q(1) hat functions, 2 nodes per direction
    uniform_gimp,      ///< uGIMP: hat convolved with a fixed point domain
    cpgimp,            ///< cpGIMP: the domain follows the deformation
    quadratic_bspline, ///< C1 quadratic B-spline, 3 nodes per direction
    cubic_bspline      ///< C2 cubic B-spline, 4 nodes per direction
  };

  /// The bases by the names a scene gives them ('Simulation/basis').
  inline const OptionTable<BasisType> basis_names = {
    {"linear", BasisType::linear},
    {"uGIMP", BasisType::uniform_gimp},
    {"cpGIMP", BasisType::cpgimp},
    {"quadratic B-spline", BasisType::quadratic_bspline},
    {"cubic B-spline", BasisType::cubic_bspline}};


  /// How far a point's weights reach, in cells: the half-width of the
  /// basis' support (GIMP: the hat's plus the point's @p half_width).
  inline double
  support_reach(const BasisType basis, const double half_width)
  {
    switch (basis)
      {
        case BasisType::linear:
          return 1;
        case BasisType::uniform_gimp:
        case BasisType::cpgimp:
          return 1 + half_width;
        case BasisType::quadratic_bspline:
          return 1.5;
        case BasisType::cubic_bspline:
          return 2;
      }
    return 2;
  }


  /**
   * One-dimensional kernels, in cell units. evaluate() receives the
   * point's coordinate xi in [0, 1) within its cell and (GIMP only) the
   * half-width l of the point's domain in cells; it fills the weights w[k]
   * and derivatives dw[k] (per cell length) of the n_nodes consecutive
   * nodes the point touches and returns the first of them relative to the
   * cell's lower node (0 or -1). Node k sits at distance
   * r = xi - (first + k) from the point.
   */
  namespace Kernels
  {
    struct Linear
    {
      static constexpr unsigned int n_nodes          = 2;
      static constexpr bool         needs_half_width = false;

      static constexpr bool exact_surface_weights = false;
      /// The hat's slope is +-1 up to the edge of its support, where its
      /// value vanishes: a node the point barely reaches has a full-size
      /// gradient (see TimeIntegrator::discount_light_node_increments).
      static constexpr bool gradient_vanishes_with_weight = false;

      static inline int
      evaluate(const double xi, const double, double *w, double *dw)
      {
        w[0]  = 1. - xi;
        w[1]  = xi;
        dw[0] = -1.;
        dw[1] = 1.;
        return 0;
      }
    };


    /**
     * GIMP (Bardenhagen & Kober 2004): the hat function averaged over the
     * point's domain [x - l, x + l]. With l <= 1/2 a point touches at most
     * three nodes: the nearest one and its two neighbours.
     */
    struct GIMP
    {
      static constexpr unsigned int n_nodes                       = 3;
      static constexpr bool         needs_half_width              = true;
      static constexpr bool         exact_surface_weights         = false;
      static constexpr bool         gradient_vanishes_with_weight = true;

      static inline int
      evaluate(const double xi, const double l, double *w, double *dw)
      {
        const int first = xi < 0.5 ? -1 : 0;
        for (unsigned int k = 0; k < n_nodes; ++k)
          {
            const double r    = xi - (first + static_cast<int>(k));
            const double a    = std::abs(r);
            const double sign = r < 0 ? -1. : 1.;
            if (a < l)
              {
                w[k]  = 1. - (r * r + l * l) / (2. * l);
                dw[k] = -r / l;
              }
            else if (a <= 1. - l)
              {
                w[k]  = 1. - a;
                dw[k] = -sign;
              }
            else if (a < 1. + l)
              {
                const double s = 1. + l - a;
                w[k]           = s * s / (4. * l);
                dw[k]          = -sign * s / (2. * l);
              }
            else
              w[k] = dw[k] = 0.;
          }
        return first;
      }
    };


    /// Quadratic B-spline centred on each node, support 3 cells.
    struct QuadraticBSpline
    {
      static constexpr unsigned int n_nodes          = 3;
      static constexpr bool         needs_half_width = false;
      /// Surface loads through the functions at the surface itself
      /// (TensorProductBasis::weights_at), see ParticleToGrid::scatter.
      static constexpr bool exact_surface_weights         = true;
      static constexpr bool gradient_vanishes_with_weight = true;

      static inline int
      evaluate(const double xi, const double, double *w, double *dw)
      {
        const int first = xi < 0.5 ? -1 : 0;
        evaluate_piece(xi, first, w, dw);
        return first;
      }

      /// The functions of the nodes first, first + 1, first + 2 at @p xi.
      static inline void
      evaluate_piece(const double xi, const int first, double *w, double *dw)
      {
        const double r = xi - first; // distance to the first node
        const double a = 1.5 - r, b = r - 1., c = r - 0.5; // a, c in [0, 1]
        w[0]  = 0.5 * a * a;
        w[1]  = 0.75 - b * b;
        w[2]  = 0.5 * c * c;
        dw[0] = -a;
        dw[1] = -2. * b;
        dw[2] = c;
      }

      /// Whether those three functions are one polynomial piece each there.
      static inline bool
      in_piece(const double xi, const int first)
      {
        return xi >= first + 0.5 && xi <= first + 1.5;
      }
    };


    /// Cubic B-spline centred on each node, support 4 cells.
    struct CubicBSpline
    {
      static constexpr unsigned int n_nodes          = 4;
      static constexpr bool         needs_half_width = false;

      static constexpr bool exact_surface_weights         = false;
      static constexpr bool gradient_vanishes_with_weight = true;

      static inline int
      evaluate(const double xi, const double, double *w, double *dw)
      {
        const double s = 1. - xi;
        w[0]           = s * s * s / 6.;
        w[1]           = 2. / 3. - xi * xi + 0.5 * xi * xi * xi;
        w[2]           = 2. / 3. - s * s + 0.5 * s * s * s;
        w[3]           = xi * xi * xi / 6.;
        dw[0]          = -0.5 * s * s;
        dw[1]          = -2. * xi + 1.5 * xi * xi;
        dw[2]          = 2. * s - 1.5 * s * s;
        dw[3]          = 0.5 * xi * xi;
        return -1;
      }
    };
  } // namespace Kernels


  /**
   * A tensor-product basis on the Cartesian grid, built from a 1D kernel.
   * Weights and gradients come from the point's cell and reference
   * coordinates in a few flops; the stencil names the nodes by their
   * Cartesian indices, which the grid maps to vector entries.
   *
   * Grid boundary. Where a stencil reaches a node beyond the grid (only
   * ever the one node just outside), that node's function is folded into
   * the two nearest grid nodes as if its value were extrapolated linearly
   * from them: w_0 += 2 w_-1, w_1 -= w_-1. This keeps partition of unity
   * and linear completeness. For the B-splines it is exactly the basis of
   * a clamped (open) knot vector with the interior B-spline assigned to
   * nodes by its Greville abscissa: in the boundary half-cell the
   * quadratic spline becomes the linear hat pair (1 - xi, xi), and in the
   * boundary cell the cubic one becomes (1 - xi + xi^3/6, xi - xi^3/3,
   * xi^3/6). All weights stay non-negative, and the boundary node alone
   * carries a point that sits on the wall, so a fixed wall holds.
   */
  template <int dim, typename Kernel>
  class TensorProductBasis
  {
  public:
    static constexpr unsigned int n_1d             = Kernel::n_nodes;
    static constexpr unsigned int n_nodes          = Utilities::pow(n_1d, dim);
    static constexpr bool         needs_half_width = Kernel::needs_half_width;
    static constexpr bool         gradient_vanishes_with_weight =
      Kernel::gradient_vanishes_with_weight;

    /// Which nodes a point touches, relative to its cell, is one of this
    /// many patterns (the first node is 0 or -1 in each direction).
    static constexpr unsigned int n_patterns = 1u << dim;

    /// What a point sees of the grid.
    struct Stencil
    {
      /// The nodes (set by the user of the basis from node_pattern(): all
      /// points of a cell with the same pattern share one list).
      const unsigned int                 *nodes;
      unsigned int                        pattern;
      std::array<double, n_nodes>         weights;
      std::array<Tensor<1, dim>, n_nodes> gradients;
      /// Per direction: 1D weights and derivatives, the first node
      /// relative to the cell, and the point's reference coordinate.
      double w1[dim][n_1d];
      double dw1[dim][n_1d];
      int    first[dim];
      double xi[dim];
      /// The cell it was evaluated in.
      std::array<unsigned int, dim> cell;
      /// Cell size (for node offsets).
      Tensor<1, dim> h;

      /// Node position minus point position, in direction @p d, of the
      /// k-th node in that direction.
      double
      offset1(const unsigned int d, const unsigned int k) const
      {
        return (first[d] + static_cast<int>(k) - xi[d]) * h[d];
      }

      /// x_node - x_point of stencil node @p v.
      Tensor<1, dim>
      node_offset(const unsigned int v) const
      {
        Tensor<1, dim> r;
        unsigned int   rest = v;
        for (unsigned int d = 0; d < dim; ++d, rest /= n_1d)
          r[d] = offset1(d, rest % n_1d);
        return r;
      }
    };

    TensorProductBasis(const std::array<unsigned int, dim> &n_cells,
                       const Tensor<1, dim>                &cell_size)
      : n_cells(n_cells)
      , h(cell_size)
    {
      for (unsigned int d = 0; d < dim; ++d)
        inv_h[d] = 1. / h[d];
    }

    /**
     * Fill the weights, gradients and pattern of @p s for a point at
     * reference coordinates @p xi of the cell with Cartesian indices
     * @p cell. @p half_width is the half-width of the point's domain in
     * cells (GIMP only).
     */
    inline void
    evaluate(const std::array<unsigned int, dim> &cell,
             const Point<dim>                    &xi,
             const Tensor<1, dim>                &half_width,
             Stencil                             &s) const
    {
      s.pattern = 0;
      s.h       = h;
      s.cell    = cell;
      for (unsigned int d = 0; d < dim; ++d)
        {
          double   *w     = s.w1[d];
          double   *dw    = s.dw1[d];
          const int first = Kernel::evaluate(xi[d], half_width[d], w, dw);
          fold_at_grid_ends(d, static_cast<int>(cell[d]) + first, w, dw);
          for (unsigned int k = 0; k < n_1d; ++k)
            dw[k] *= inv_h[d];
          s.first[d] = first;
          s.xi[d]    = xi[d];
          s.pattern |= (first + 1) << d;
        }

      for (unsigned int v = 0; v < n_nodes; ++v)
        {
          unsigned int rest = v;
          double       wd[dim], dwd[dim];
          for (unsigned int d = 0; d < dim; ++d, rest /= n_1d)
            {
              wd[d]  = s.w1[d][rest % n_1d];
              dwd[d] = s.dw1[d][rest % n_1d];
            }
          s.weights[v] = product_except(wd, dim);
          for (unsigned int d = 0; d < dim; ++d)
            s.gradients[v][d] = dwd[d] * product_except(wd, d);
        }
    }

    /**
     * The weights at x_p + @p offset of the nodes of stencil @p s: the
     * functions of its nodes evaluated at another point, as a surface load
     * needs them at the surface rather than at the point. False (and
     * @p w unset) where those functions are not one polynomial piece from
     * the point to there (the other point sees other nodes or another
     * piece); then the caller needs another form. Exact where true.
     */
    inline bool
    weights_at(const Stencil               &s,
               const Tensor<1, dim>        &offset,
               std::array<double, n_nodes> &w) const
    {
      // A little beyond a piece's end is still exact to round-off: the
      // functions are continuous there (a face on a node line).
      constexpr double tolerance = 1e-9;
      if constexpr (!Kernel::exact_surface_weights)
        return false;
      else
        {
          double w1[dim][n_1d], dw1[n_1d];
          for (unsigned int d = 0; d < dim; ++d)
            {
              double xi = s.xi[d] + offset[d] * inv_h[d];
              if (!Kernel::in_piece(xi, s.first[d]))
                {
                  if (Kernel::in_piece(xi - tolerance, s.first[d]))
                    xi -= tolerance;
                  else if (Kernel::in_piece(xi + tolerance, s.first[d]))
                    xi += tolerance;
                  else
                    return false;
                }
              Kernel::evaluate_piece(xi, s.first[d], w1[d], dw1);
              fold_at_grid_ends(d,
                                static_cast<int>(s.cell[d]) + s.first[d],
                                w1[d],
                                dw1);
            }
          for (unsigned int v = 0; v < n_nodes; ++v)
            {
              unsigned int rest = v;
              double       wd[dim];
              for (unsigned int d = 0; d < dim; ++d, rest /= n_1d)
                wd[d] = w1[d][rest % n_1d];
              w[v] = product_except(wd, dim);
            }
          return true;
        }
    }

    /**
     * The nodes of stencil @p s (after evaluate()), in the order of its
     * weights, as @p index_of(Cartesian indices of the node): the grid's
     * local index. A node beyond the grid, whose weight the folding has
     * set to zero, is replaced by the nearest grid node.
     */
    template <typename NodeIndex>
    inline void
    node_pattern(const std::array<unsigned int, dim> &cell,
                 const Stencil                       &s,
                 std::array<unsigned int, n_nodes>   &nodes,
                 const NodeIndex                     &index_of) const
    {
      unsigned int node1[dim][n_1d];
      for (unsigned int d = 0; d < dim; ++d)
        for (unsigned int k = 0; k < n_1d; ++k)
          node1[d][k] = std::clamp(static_cast<int>(cell[d] + k) + s.first[d],
                                   0,
                                   static_cast<int>(n_cells[d]));
      for (unsigned int v = 0; v < n_nodes; ++v)
        {
          std::array<unsigned int, dim> node;
          unsigned int                  rest = v;
          for (unsigned int d = 0; d < dim; ++d, rest /= n_1d)
            node[d] = node1[d][rest % n_1d];
          nodes[v] = index_of(node);
        }
    }

    /**
     * APIC (Jiang et al. 2015): the vectors a_I with C_p = sum_I v_I (x) a_I,
     * that is w_I D_p^{-1} (x_I - x_p) with the inertia tensor
     * D_p = sum_I w_I (x_I - x_p)(x_I - x_p)^T. For a tensor-product basis
     * that is linearly complete, D_p is diagonal, and its entries are 1D
     * second moments; they equal h^2/4 (quadratic) and h^2/3 (cubic)
     * inside the grid and differ next to the boundary, where the folded
     * kernels change. Computing D from the weights gives C_p = A exactly
     * for any affine grid velocity A x + b, with every basis. Where D
     * vanishes (a point on a node of a basis that is linear there),
     * w_I (x_I - x_p) / D tends to the gradient, which is used instead.
     */
    inline void
    affine_weights(const Stencil                       &s,
                   std::array<Tensor<1, dim>, n_nodes> &a) const
    {
      double af1[dim][n_1d];
      for (unsigned int d = 0; d < dim; ++d)
        {
          double D = 0;
          for (unsigned int k = 0; k < n_1d; ++k)
            D += s.w1[d][k] * s.offset1(d, k) * s.offset1(d, k);
          const bool degenerate = D < 1e-12 * h[d] * h[d];
          for (unsigned int k = 0; k < n_1d; ++k)
            af1[d][k] =
              degenerate ? s.dw1[d][k] : s.w1[d][k] * s.offset1(d, k) / D;
        }
      for (unsigned int v = 0; v < n_nodes; ++v)
        {
          unsigned int rest = v;
          double       wd[dim], ad[dim];
          for (unsigned int d = 0; d < dim; ++d, rest /= n_1d)
            {
              wd[d] = s.w1[d][rest % n_1d];
              ad[d] = af1[d][rest % n_1d];
            }
          for (unsigned int d = 0; d < dim; ++d)
            a[v][d] = ad[d] * product_except(wd, d);
        }
    }

  private:
    /// Fold the 1D functions @p w, @p dw of direction @p d whose first node
    /// is @p first_node (the grid's node index, possibly -1) at the grid's
    /// ends (see the class documentation).
    inline void
    fold_at_grid_ends(const unsigned int d,
                      const int          first_node,
                      double            *w,
                      double            *dw) const
    {
      if constexpr (n_1d >= 3)
        {
          if (first_node < 0)
            fold_outside_node(w, dw, 0, 1, 2);
          if (first_node + static_cast<int>(n_1d) - 1 >
              static_cast<int>(n_cells[d]))
            fold_outside_node(w, dw, n_1d - 1, n_1d - 2, n_1d - 3);
        }
    }

    /// Fold the function of stencil entry @p out (a node beyond the grid)
    /// into the boundary node @p b and its inner neighbour @p c.
    static inline void
    fold_outside_node(double            *w,
                      double            *dw,
                      const unsigned int out,
                      const unsigned int b,
                      const unsigned int c)
    {
      w[b] += 2. * w[out];
      w[c] -= w[out];
      dw[b] += 2. * dw[out];
      dw[c] -= dw[out];
      w[out] = dw[out] = 0.;
    }

    /// Product of the first dim factors, leaving out factor @p skip.
    static inline double
    product_except(const double *f, const unsigned int skip)
    {
      double p = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        if (d != skip)
          p *= f[d];
      return p;
    }

    std::array<unsigned int, dim> n_cells;
    Tensor<1, dim>                h;
    Tensor<1, dim>                inv_h;
  };


  template <int dim>
  using LinearBasis = TensorProductBasis<dim, Kernels::Linear>;
  template <int dim>
  using GIMPBasis = TensorProductBasis<dim, Kernels::GIMP>;
  template <int dim>
  using QuadraticBSplineBasis =
    TensorProductBasis<dim, Kernels::QuadraticBSpline>;
  template <int dim>
  using CubicBSplineBasis = TensorProductBasis<dim, Kernels::CubicBSpline>;


  /**
   * Call @p f with a default-constructed tag of the basis class that
   * implements @p type, so that code templated on the basis is written
   * once and selected at run time in one place.
   */
  template <int dim, typename F>
  inline decltype(auto)
  with_basis(const BasisType type, F &&f)
  {
    switch (type)
      {
        case BasisType::linear:
          return f(static_cast<LinearBasis<dim> *>(nullptr));
        case BasisType::uniform_gimp:
        case BasisType::cpgimp:
          return f(static_cast<GIMPBasis<dim> *>(nullptr));
        case BasisType::quadratic_bspline:
          return f(static_cast<QuadraticBSplineBasis<dim> *>(nullptr));
        default:
          return f(static_cast<CubicBSplineBasis<dim> *>(nullptr));
      }
  }
} // namespace mpm

/**
 * Expand @p M(dim, Basis) for every basis class: the explicit
 * instantiations of a template on the basis (the transfers' loops) list
 * the bases here, as with_basis() does at run time.
 */
#define MPM_FOR_EACH_BASIS(M, dim)        \
  M(dim, mpm::LinearBasis<dim>)           \
  M(dim, mpm::GIMPBasis<dim>)             \
  M(dim, mpm::QuadraticBSplineBasis<dim>) \
  M(dim, mpm::CubicBSplineBasis<dim>)

/**
 * Instantiate the class template @p Class for dimensions 1, 2 and 3, and
 * expand @p M(dim, Basis) for every basis with each: a stage whose loops
 * are member templates on the basis.
 */
#define MPM_INSTANTIATE_WITH_EACH_BASIS(Class, M) \
  template class Class<1>;                        \
  MPM_FOR_EACH_BASIS(M, 1)                        \
  template class Class<2>;                        \
  MPM_FOR_EACH_BASIS(M, 2)                        \
  template class Class<3>;                        \
  MPM_FOR_EACH_BASIS(M, 3)

#endif
