#ifndef mpm_time_step_limit_h
#define mpm_time_step_limit_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <mpm/background_grid.h>
#include <mpm/boundary_conditions/rigid_wall.h>
#include <mpm/boundary_conditions/velocity_region.h>
#include <mpm/contact/multi_field.h>
#include <mpm/integrator_parameters.h>
#include <mpm/material_points.h>
#include <mpm/step_parts.h>

#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The size of the step: the CFL condition over the points' wave and
   * flow speeds (and the walls', regions' and rigid bodies' prescribed
   * speeds), the viscous limit, and on the way the per-point check that
   * stops an unstable run with a diagnosis (J outside its bounds, a
   * non-finite velocity, stress or volume). It keeps what each body
   * contributes, computed once: its wave modulus (which the rigid walls'
   * penalty reads too) and its viscous limit.
   */
  template <int dim>
  class TimeStepLimit
  {
  public:
    TimeStepLimit(const StepParts<dim> &parts);

    /// CFL number times h / max(c_p + |v_p|), or the viscous limit if
    /// smaller. Also checks that every point is sound; throws RunError (on
    /// all ranks) if not (collective).
    double
    stable_time_step();

    /// The length of the next explicit step: the stable step, or the
    /// scene's fixed time step (a RunError if the state has outgrown it).
    double
    explicit_time_step();

    /// The scene's fixed time step, or its substeps of the macro step, must
    /// be stable in the initial state: an InputError naming the parameter
    /// if not (collective).
    void
    check_requested_steps();

    /// The length of the explicit steps (substeps) the run starts with and
    /// what sets it, in words that name the parameter (collective).
    std::pair<double, std::string>
    initial_step();

    /// Each body's P-wave modulus (0 for a rigid body: no wave crosses it).
    const std::vector<double> &
    wave_modulus_of_body() const
    {
      return wave_modulus;
    }

  private:
    const IntegratorParameters<dim>     &prm;
    const BackgroundGrid<dim>           &grid;
    const MaterialPoints<dim>           &points;
    const std::vector<RigidWall<dim> *> &rigid_walls;
    const VelocityRegion<dim>           &velocity_region;
    MultiFieldContact<dim>              *contact;
    StepContext                         &context;

    std::vector<double> wave_modulus;
    /// dM/dp of each body (Material::wave_modulus_pressure_slope).
    std::vector<double> wave_modulus_pressure_slope;
    /// 1 / rho0 for bodies whose wave speed is sqrt(M / rho0), else 0.
    std::vector<double> fixed_inverse_density;
    /// rho0 of each body: J = V rho0 / m for the guard on J (0: a rigid
    /// body, whose points keep their volume).
    std::vector<double> density;
    /// The momentum-diffusion limit of viscous (fluid) bodies on the time
    /// step, min rho0 h^2 / (2 dim eta); infinite without them.
    double viscous_time_step = std::numeric_limits<double>::infinity();
    /// The body that sets it.
    unsigned int viscous_body = 0;
  };
} // namespace mpm

#endif
