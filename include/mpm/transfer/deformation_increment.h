#ifndef mpm_transfer_deformation_increment_h
#define mpm_transfer_deformation_increment_h

#include <deal.II/base/tensor.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The deformation increment of a step @p dt under the strain rate
   * @p L, I + dt L: what F and the volume are updated by (G2P), the macro
   * step accumulates, and APIC's C is advected with.
   */
  template <int dim>
  inline Tensor<2, dim>
  deformation_increment(const Tensor<2, dim> &L, const double dt)
  {
    Tensor<2, dim> dF = dt * L;
    for (unsigned int d = 0; d < dim; ++d)
      dF[d][d] += 1.;
    return dF;
  }
} // namespace mpm

#endif
