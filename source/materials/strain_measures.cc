// Strain measures for output, computed as the log-strain models compute
// their elastic strain.
#include <mpm/materials/log_strain.h>
#include <mpm/materials/strain_measures.h>

namespace mpm
{
  template <int dim>
  SymmetricTensor<2, 3>
  log_strain(const Tensor<2, dim> &F)
  {
    SymmetricTensor<2, 3> b;
    for (unsigned int i = 0; i < 3; ++i)
      b[i][i] = 1.;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        {
          double b_ij = 0;
          for (unsigned int k = 0; k < dim; ++k)
            b_ij += F[i][k] * F[j][k];
          b[i][j] = b_ij;
        }
    const LogStrain::Spectral s = LogStrain::decompose<dim>(b);
    return LogStrain::compose<dim>(LogStrain::half_log(s), s);
  }


  double
  deviatoric_strain(const SymmetricTensor<2, 3> &strain)
  {
    const SymmetricTensor<2, 3> e = deviator(strain);
    return std::sqrt(2. / 3. * (e * e));
  }


  template SymmetricTensor<2, 3>
  log_strain<1>(const Tensor<2, 1> &);
  template SymmetricTensor<2, 3>
  log_strain<2>(const Tensor<2, 2> &);
  template SymmetricTensor<2, 3>
  log_strain<3>(const Tensor<2, 3> &);
} // namespace mpm
