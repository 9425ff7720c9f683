// The stress stage of the step: F-bar's volume average (transfer/f_bar.h),
// each body's material update, and the stress power they absorb (the energy
// residual).
#include <mpm/stress_update.h>
#include <mpm/transfer/deformation_increment.h>

namespace mpm
{
  template <int dim>
  StressUpdate<dim>::StressUpdate(const StepParts<dim> &parts)
    : f_bar(parts.parameters.f_bar)
    , energy_residual(parts.parameters.energy_residual)
    , grid(parts.grid)
    , points(parts.points)
    , context(parts.context)
    , cell_averages(grid, points)
    , account(parts.work)
  {
  }


  template <int dim>
  void
  StressUpdate<dim>::update(const double dt)
  {
    if (f_bar)
      {
        TimerOutput::Scope scope(context.timer, "F-bar");
        cell_averages.average_volume_change(dt);
      }
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
