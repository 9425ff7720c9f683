#ifndef mpm_bodies_body_parameters_templates_h
#define mpm_bodies_body_parameters_templates_h

// BodyParameters::for_each_seed, for the files that visit the seeds
// (counting them for the partition, generating the points).
#include <mpm/bodies/body_parameters.h>

#include <algorithm>

namespace mpm
{
  template <int dim>
  template <typename Visitor>
  void
  BodyParameters<dim>::for_each_seed(const Point<dim> &cell_origin,
                                     const Visitor    &visit) const
  {
    const Tensor<1, dim> h = grid.cell_size();
    if (mesh_seeds)
      {
        const auto [first, last] = mesh_seed_range(cell_origin);
        for (unsigned int i = first; i < last; ++i)
          {
            const Point<dim> &x = mesh_seeds->positions[i];
            Point<dim>        xi;
            for (unsigned int d = 0; d < dim; ++d)
              xi[d] = std::clamp((x[d] - cell_origin[d]) / h[d], 0., 1.);
            visit(x,
                  xi,
                  mesh_seeds->volumes[i],
                  mesh_seeds->areas.empty()
                    ? SurfaceShare<dim>()
                    : SurfaceShare<dim>{mesh_seeds->areas[i],
                                        Tensor<1, dim>()});
          }
        return;
      }
    const unsigned int n      = particles_per_cell;
    const unsigned int n_sub  = Utilities::fixed_power<dim>(n);
    double             volume = 1. / n_sub;
    for (unsigned int d = 0; d < dim; ++d)
      volume *= h[d];
    for (unsigned int s = 0; s < n_sub; ++s)
      {
        // Points at the centres of n^dim sub-cells: interior, never on a
        // face, where deal.II 9.4's in-cell test can lose them.
        Point<dim>   xi;
        unsigned int rest = s;
        for (unsigned int d = 0; d < dim; ++d)
          {
            xi[d] = ((rest % n) + 0.5) / n;
            rest /= n;
          }
        Point<dim> x = cell_origin;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] += xi[d] * h[d];
        if (shape->contains(x))
          visit(x, xi, volume, shape_seed_surface(x, volume));
      }
  }
} // namespace mpm

#endif
