#ifndef mpm_materials_strain_measures_h
#define mpm_materials_strain_measures_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The logarithmic (Hencky) strain of the deformation gradient @p F,
   * 1/2 ln(F F^T), in 3D: in 1D and 2D the out-of-plane stretches are 1
   * (plane strain), so its out-of-plane components are 0. The strain the
   * log-strain materials split into elastic and plastic parts, computed
   * with their eigen-decomposition (LogStrain::decompose).
   */
  template <int dim>
  SymmetricTensor<2, 3>
  log_strain(const Tensor<2, dim> &F);

  /**
   * The equivalent deviatoric strain sqrt(2/3 e : e), e the deviator of
   * @p strain: the shear strain geotechnical codes plot to show a failure
   * surface (pure shear by gamma: gamma / sqrt(3); uniaxial strain eps at
   * constant volume: eps).
   */
  double
  deviatoric_strain(const SymmetricTensor<2, 3> &strain);
} // namespace mpm

#endif
