#ifndef mpm_stress_update_h
#define mpm_stress_update_h

#include <mpm/background_grid.h>
#include <mpm/integrator_parameters.h>
#include <mpm/material_points.h>
#include <mpm/step_parts.h>
#include <mpm/transfer/f_bar.h>
#include <mpm/work_account.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The stress stage of the step: from the strain rate L each point holds
   * after the kinematics, F-bar's volume average over cells (if the scene
   * asks for it), each deformable body's material update, and the stress
   * power they absorb (the energy residual, if asked for). The
   * integrator calls update() once per step, wherever its update scheme
   * puts the stress update.
   */
  template <int dim>
  class StressUpdate
  {
  public:
    StressUpdate(const StepParts<dim> &parts);

    /// Update the stresses of all deformable bodies over a step of @p dt.
    void
    update(const double dt);

  private:
    /// Half of the step's stress power V sigma : L dt (see there), at the
    /// stress before the update (@p before) or after it.
    void
    add_stress_power(const double dt, const bool before);

    const bool                 f_bar;
    const bool                 energy_residual;
    const BackgroundGrid<dim> &grid;
    MaterialPoints<dim>       &points;
    const StepContext         &context;
    /// F-bar's volume average over cells.
    FBar<dim> cell_averages;
    /// Where the absorbed work goes (WorkAccount::absorbed).
    WorkAccount &account;
  };
} // namespace mpm

#endif
