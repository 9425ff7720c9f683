#ifndef mpm_basis_h
#define mpm_basis_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>

namespace mpm
{
  using namespace dealii;

  /**
   * The linear (FE_Q(1)) basis on a Cartesian cell, evaluated from the
   * particle's reference coordinates in a few flops instead of through
   * FEValues. Node v of the stencil is vertex v of the cell in deal.II's
   * lexicographic order: bit d of v says whether the node is at the upper
   * side in direction d.
   *
   * Smoother bases (GIMP, B-splines) will provide the same interface with
   * a larger stencil; the transfer kernels are templated on the basis so
   * the per-particle loops stay free of virtual calls.
   */
  template <int dim>
  struct LinearBasis
  {
    static constexpr unsigned int n_nodes = 1u << dim;

    /// Weights and physical gradients at reference point @p xi of a cell
    /// with inverse size @p inv_h.
    static inline void
    evaluate(const Point<dim>                    &xi,
             const Tensor<1, dim>                &inv_h,
             std::array<double, n_nodes>         &weights,
             std::array<Tensor<1, dim>, n_nodes> &gradients)
    {
      double lo[dim], hi[dim];
      for (unsigned int d = 0; d < dim; ++d)
        {
          hi[d] = xi[d];
          lo[d] = 1. - xi[d];
        }
      for (unsigned int v = 0; v < n_nodes; ++v)
        {
          double w = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            w *= ((v >> d) & 1u) ? hi[d] : lo[d];
          weights[v] = w;
          for (unsigned int d = 0; d < dim; ++d)
            {
              // d/dx_d of the product: replace factor d by its derivative.
              double g = ((v >> d) & 1u) ? inv_h[d] : -inv_h[d];
              for (unsigned int e = 0; e < dim; ++e)
                if (e != d)
                  g *= ((v >> e) & 1u) ? hi[e] : lo[e];
              gradients[v][d] = g;
            }
        }
    }
  };
} // namespace mpm

#endif
