#ifndef mpm_statistics_h
#define mpm_statistics_h

#include <mpm/material_points.h>

namespace mpm
{
  using namespace dealii;

  /// Sums over all points of the scene at one instant (collective).
  template <int dim>
  struct Statistics
  {
    double kinetic_energy       = 0;
    double strain_energy        = 0;
    double gravitational_energy = 0;
    /// The part of the kinetic and gravitational energy that belongs to
    /// rigid bodies (their motion is prescribed).
    double                      rigid_kinetic_energy       = 0;
    double                      rigid_gravitational_energy = 0;
    Tensor<1, dim>              momentum;
    Tensor<1, dim == 2 ? 1 : 3> angular_momentum;
    double                      mass           = 0;
    double                      momentum_scale = 0; ///< sum of m |v|
    types::particle_index       n_particles    = 0;

    double
    total_energy() const
    {
      return kinetic_energy + strain_energy + gravitational_energy;
    }

    static Statistics
    compute(const MaterialPoints<dim> &points,
            const Tensor<1, dim>      &gravity,
            MPI_Comm                   comm);
  };
} // namespace mpm

#endif
