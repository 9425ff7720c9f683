// The stress stage of the step: F-bar's volume average, each body's
// material update, and the stress power they absorb (the energy residual).
#include <mpm/stress_update.h>
#include <mpm/transfer/deformation_increment.h>

#include <array>
#include <vector>

namespace mpm
{
  template <int dim>
  StressUpdate<dim>::StressUpdate(const StepParts<dim> &parts)
    : f_bar(parts.parameters.f_bar)
    , energy_residual(parts.parameters.energy_residual)
    , grid(parts.grid)
    , points(parts.points)
    , context(parts.context)
    , density_of_body(deformable_densities(points.bodies()))
    , account(parts.work)
  {
  }


  template <int dim>
  void
  StressUpdate<dim>::update(const double dt)
  {
    if (f_bar)
      average_volume_change_over_cells(dt);
    if (energy_residual)
      add_stress_power(dt, true);
    {
      TimerOutput::Scope scope(context.timer, "stress");
      for (unsigned int b = 0; b < points.bodies().size(); ++b)
        if (!points.bodies()[b].rigid_velocity) // a rigid body has no stress
          points.bodies()[b].material->update_stresses(
            points.handler(), points.layout(), b, dt, context.comm);
    }
    if (energy_residual)
      add_stress_power(dt, false);
  }


  /**
   * With the linear basis a cell's nodes can follow far fewer volume
   * changes than it holds points, so a nearly incompressible body locks:
   * each point's J is a constraint. F-bar (de Souza Neto et al. 1996; for
   * MPM Coombs et al. 2018) gives every point the J of its cell,
   *
   *   J_cell = sum V_p / sum V0_p   over the cell's points of one body,
   *
   * and keeps its isochoric deformation: the step's increment becomes
   * dF_bar = (J_cell / J_p)^(1/dim) dF. Averaging the total J, not the
   * step's increment, matters: with increments alone, points that arrive
   * from other cells carry their own J, and at K / mu = 500 those
   * differences are the pressure noise F-bar is meant to remove (the
   * settling block of tests/block_settling.prm at nu = 0.499: stress error
   * 0.129 by increments, 0.103 by the total J; 1.37 without F-bar). Bodies that
   * share a cell are not mixed, the volume is conserved per cell, and V, F and
   * L stay consistent (V = V0 det F, I + dt L = dF_bar). In 2D (plane strain)
   * the exponent 1/2 acts in the plane, where all the volume change happens.
   */
  template <int dim>
  void
  StressUpdate<dim>::average_volume_change_over_cells(const double dt)
  {
    TimerOutput::Scope               scope(context.timer, "F-bar");
    const FieldLayout               &l         = points.layout();
    Particles::ParticleHandler<dim> &particles = points.handler();
    const unsigned int               n_bodies  = density_of_body.size();
    const unsigned int cells_of_tile = Utilities::pow(grid.tile_size(), dim);
    // Per cell of the tile and body: the current and the reference volume
    // of its points, and per cell the number of points.
    std::vector<std::array<double, 2>> volumes(cells_of_tile * n_bodies);
    std::vector<unsigned int>          n_in_cell(cells_of_tile);
    // The tile's points of deformable bodies with their (cell, body) bin,
    // visited twice: deal.II's particle iterator is walked once.
    std::vector<std::pair<double *, unsigned int>> deformable;
    const auto                                     body = [&](const double *q) {
      return static_cast<unsigned int>(q[l.body]);
    };
    const auto reference_volume = [&](const double *q) {
      return q[l.mass] / density_of_body[body(q)];
    };
    for (const unsigned int index : grid.locally_owned_tiles())
      {
        const auto        &tile = grid.tile(index);
        const unsigned int n    = particles.n_particles_in_cell(tile);
        if (n < 2)
          continue;
        std::fill(volumes.begin(), volumes.end(), std::array<double, 2>{});
        std::fill(n_in_cell.begin(), n_in_cell.end(), 0u);
        deformable.clear();
        const auto first = grid.first_cell_of_tile(index);
        auto       p     = particles.particles_in_cell(tile).begin();
        for (unsigned int i = 0; i < n; ++i, ++p)
          {
            typename BackgroundGrid<dim>::CellCoordinates cell;
            Point<dim>                                    xi;
            grid.cell_in_tile(first, p->get_reference_location(), cell, xi);
            unsigned int c = 0;
            for (int d = dim - 1; d >= 0; --d)
              c = c * grid.tile_size() + (cell[d] - first[d]);
            ++n_in_cell[c];
            double *const q = p->get_properties().data();
            if (density_of_body[body(q)] > 0) // not a rigid body
              {
                const unsigned int bin = c * n_bodies + body(q);
                volumes[bin][0] += q[l.volume];
                volumes[bin][1] += reference_volume(q);
                deformable.emplace_back(q, bin);
              }
          }
        for (const auto &[q, bin] : deformable)
          {
            // A point alone in its cell keeps its own J.
            if (n_in_cell[bin / n_bodies] < 2)
              continue;
            const double J_cell = volumes[bin][0] / volumes[bin][1];
            const double V0     = reference_volume(q);
            const double ratio  = J_cell * V0 / q[l.volume];
            const double scale  = dim == 1   ? ratio
                                  : dim == 2 ? std::sqrt(ratio)
                                             : std::cbrt(ratio);
            // I + dt L_bar = scale (I + dt L).
            Tensor<2, dim> L =
              scale * Fields::tensor<dim>(q + l.velocity_gradient);
            for (unsigned int d = 0; d < dim; ++d)
              L[d][d] += (scale - 1.) / dt;
            Fields::store(L, q + l.velocity_gradient);
            q[l.volume] = J_cell * V0;
            if (l.deformation_gradient != FieldLayout::absent)
              Fields::store(Tensor<2, dim>(
                              scale *
                              Fields::tensor<dim>(q + l.deformation_gradient)),
                            q + l.deformation_gradient);
          }
      }
  }


  /**
   * The work the points' stresses absorbed over the step, V sigma : L dt
   * with the strain rate their update used, by the trapezoidal rule over
   * the update: half at the stress before (and the volume the step started
   * from), half after. Elastic, its sum is the change of strain energy to
   * the order of the rule; plastic, it also holds what plasticity
   * dissipated (see EnergyGuard: the energy residual).
   */
  template <int dim>
  void
  StressUpdate<dim>::add_stress_power(const double dt, const bool before)
  {
    TimerOutput::Scope scope(context.timer, "energy residual");
    const FieldLayout &l     = points.layout();
    double             power = 0;
    for (const auto &p : points.handler())
      {
        const double        *q = p.get_properties().data();
        const Tensor<2, dim> L = Fields::tensor<dim>(q + l.velocity_gradient);
        double               V = q[l.volume];
        if (before)
          {
            // The volume the step started from: V = V_n det(I + dt L).
            V /= determinant(deformation_increment(L, dt));
          }
        power += V * scalar_product(Fields::symmetric<dim>(q + l.stress), L);
      }
    account.absorbed += 0.5 * dt * power;
  }


  template class StressUpdate<1>;
  template class StressUpdate<2>;
  template class StressUpdate<3>;
} // namespace mpm
