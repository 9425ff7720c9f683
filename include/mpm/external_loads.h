#ifndef mpm_external_loads_h
#define mpm_external_loads_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <mpm/boundary_conditions/rigid_wall.h>
#include <mpm/material_points.h>
#include <mpm/parameters.h>
#include <mpm/step_parts.h>
#include <mpm/work_account.h>

#include <array>
#include <sstream>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The loads of the step and the account of the work done on the bodies
   * from outside: the point loads (pressure and traction on a loaded
   * surface, the rigid walls' penalty forces), the body forces, the rigid
   * walls putting back the points behind them, and the work of whatever
   * else acts on the grid (velocity regions, rigid bodies, the virtual
   * fluid), which the integrator adds with add_work(). The energy guard
   * reads the totals. The scatter adds the loads to the nodal forces.
   *
   * A load given by an expression can only be checked where it is
   * evaluated: a magnitude beyond largest_input is kept as the step's
   * diagnosis (StepContext::fail).
   */
  template <int dim>
  class ExternalLoads
  {
  public:
    ExternalLoads(const StepParts<dim>      &parts,
                  const std::vector<double> &wave_modulus_of_body);

    /// Does a body force act on any body?
    bool
    has_body_forces() const
    {
      return with_body_forces;
    }

    /// Evaluate the body forces at time @p time from now on.
    void
    set_body_force_time(const double time);

    /// Body force per unit mass b(X, t) of a point (without gravity).
    Tensor<1, dim>
    body_force(const double *q) const;

    /// Note a failure naming the parameter if a load expression of body
    /// @p body (@p name: "traction", ...) has a value of @p magnitude
    /// beyond largest_input (or not finite) at @p x.
    void
    check_load(const double       magnitude,
               const unsigned int body,
               const char        *name,
               const Point<dim>  &x) const;

    /// Fill each point's 'point load' field for the coming step of @p dt:
    /// the pressure and traction on a loaded surface at the point's
    /// position and the rigid walls' contact forces, and take the first
    /// half of their work. A pass of its own, only in scenes with such
    /// loads, so that the scatter adds one vector and needs no position.
    void
    make_point_loads(const double dt);

    /// The power of the body forces at the velocities the step starts
    /// from (the scatter's sum on this rank).
    void
    set_body_force_power(const double power)
    {
      body_force_power = power;
    }

    /// Add @p w to the step's external work (this rank's share).
    void
    add_work(const double w)
    {
      step_work += w;
    }

    /// The step's external work so far (USF with cpGIMP scatters twice
    /// and takes back the first scatter's share with set_step_work()).
    double
    step_work_so_far() const
    {
      return step_work;
    }
    void
    set_step_work(const double w)
    {
      step_work = w;
    }

    /// End the step's account of external work (see there).
    void
    close_step(const double dt);

    /// Every rigid wall puts back the points that fell behind it by @p
    /// time (RigidWall::put_back); notes a failure if walls pinch a point
    /// between them.
    void
    keep_points_in_front_of_rigid_walls(const double time);

  private:
    /// Add @p weight times the point loads' power at the points' current
    /// velocities to the step's external work (see there).
    void
    add_point_load_work(const double weight);

    MaterialPoints<dim> &points;
    /// The integrator's list (StepParts::rigid_walls).
    const std::vector<RigidWall<dim> *> &rigid_walls;
    const std::vector<double>           &wave_modulus_of_body;
    StepContext                         &context;

    /// Each body's pressure and traction on its loaded surface and its
    /// body force (null: none).
    std::vector<FunctionParser<dim> *> pressures, tractions, body_forces;
    bool                               with_body_forces = false;
    /// Where each step's external work goes (WorkAccount::external and
    /// its absolute sum): the work done on the bodies by everything
    /// outside them but gravity (loads, body forces, rigid walls and
    /// bodies, velocity regions, the virtual fluid).
    WorkAccount &account;
    /// This rank's share of the step's external work so far, and the body
    /// forces' power in the last scatter.
    double step_work = 0, body_force_power = 0;
  };


  // The two that the scatter calls for every point, inline there.

  template <int dim>
  inline Tensor<1, dim>
  ExternalLoads<dim>::body_force(const double *q) const
  {
    const FieldLayout &l = points.layout();
    Tensor<1, dim>     b;
    if (FunctionParser<dim> *f = body_forces[q[l.body]])
      {
        const Point<dim> X(Fields::vector<dim>(q + l.initial_position));
        for (unsigned int d = 0; d < dim; ++d)
          b[d] = f->value(X, d);
      }
    return b;
  }


  /**
   * A load given by an expression (pressure, traction, body force) can
   * only be checked where it is evaluated. A magnitude beyond
   * largest_input (or not finite) is a mistake in the scene: it is named
   * here, before the forces it makes overflow the point's motion into a
   * diagnosis that names no parameter.
   */
  template <int dim>
  inline void
  ExternalLoads<dim>::check_load(const double       magnitude,
                                 const unsigned int body,
                                 const char        *name,
                                 const Point<dim>  &x) const
  {
    if (magnitude <= largest_input || context.failed())
      return;
    std::ostringstream msg;
    msg << context.when() << ": parameter '" << points.bodies()[body].name
        << "/" << name << "' is " << magnitude << " in magnitude at (" << x
        << "): a load must be finite and at most " << largest_input
        << " in magnitude (Pa, or m/s^2 for a body force)";
    context.fail(msg.str());
  }
} // namespace mpm

#endif
