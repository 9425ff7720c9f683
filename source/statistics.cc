#include <deal.II/base/mpi.h>

#include <mpm/statistics.h>

namespace mpm
{
  template <int dim>
  Statistics<dim>
  Statistics<dim>::compute(const MaterialPoints<dim> &points,
                           const Tensor<1, dim>      &gravity,
                           MPI_Comm                   comm)
  {
    const FieldLayout &l = points.layout();
    Statistics         s;
    points.for_each_by_cell([&](const auto &p) {
      const double        *q    = p.get_properties().data();
      const double         m    = q[l.mass];
      const Tensor<1, dim> v    = Fields::vector<dim>(q + l.velocity);
      const Point<dim>     x    = p.get_location();
      const auto          &body = points.bodies()[q[l.body]];
      s.kinetic_energy += 0.5 * m * v.norm_square();
      s.strain_energy += body.material->strain_energy(q, l);
      s.gravitational_energy -= m * (gravity * x);
      if (body.rigid_velocity)
        {
          s.rigid_kinetic_energy += 0.5 * m * v.norm_square();
          s.rigid_gravitational_energy -= m * (gravity * x);
        }
      s.momentum += m * v;
      if constexpr (dim == 2)
        s.angular_momentum[0] += m * (x[0] * v[1] - x[1] * v[0]);
      if constexpr (dim == 3)
        s.angular_momentum += m * cross_product_3d(x, v);
      s.mass += m;
      s.momentum_scale += m * v.norm();
      ++s.n_particles;
    });
    // One reduction for all sums.
    std::vector<double> sums = {s.kinetic_energy,
                                s.strain_energy,
                                s.gravitational_energy,
                                s.mass,
                                s.momentum_scale,
                                double(s.n_particles),
                                s.rigid_kinetic_energy,
                                s.rigid_gravitational_energy};
    for (unsigned int d = 0; d < dim; ++d)
      sums.push_back(s.momentum[d]);
    for (unsigned int d = 0; d < s.angular_momentum.dimension; ++d)
      sums.push_back(s.angular_momentum[d]);
    MPI_Allreduce(
      MPI_IN_PLACE, sums.data(), sums.size(), MPI_DOUBLE, MPI_SUM, comm);
    s.kinetic_energy             = sums[0];
    s.strain_energy              = sums[1];
    s.gravitational_energy       = sums[2];
    s.mass                       = sums[3];
    s.momentum_scale             = sums[4];
    s.n_particles                = static_cast<types::particle_index>(sums[5]);
    s.rigid_kinetic_energy       = sums[6];
    s.rigid_gravitational_energy = sums[7];
    for (unsigned int d = 0; d < dim; ++d)
      s.momentum[d] = sums[8 + d];
    for (unsigned int d = 0; d < s.angular_momentum.dimension; ++d)
      s.angular_momentum[d] = sums[8 + dim + d];
    return s;
  }


  template struct Statistics<1>;
  template struct Statistics<2>;
  template struct Statistics<3>;
} // namespace mpm
