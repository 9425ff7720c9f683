#ifndef mpm_step_parts_h
#define mpm_step_parts_h

#include <mpm/step_context.h>

#include <vector>

namespace mpm
{
  template <int dim>
  struct IntegratorParameters;
  template <int dim>
  class BackgroundGrid;
  template <int dim>
  class MaterialPoints;
  template <int dim>
  class VelocityRegion;
  template <int dim>
  class RigidWall;
  template <int dim>
  class VirtualFluid;
  template <int dim>
  class MultiFieldContact;
  template <int dim>
  class NodalState;
  template <int dim>
  class PointLoop;
  struct WorkAccount;

  /**
   * The parts of the scene the stages of the step act on, and what the
   * stages share of the step (its context, the nodal state, the loop over
   * the points), as the integrator hands them to each stage (in the
   * manner of ASPECT's SimulatorAccess): a stage's constructor takes this
   * and names beside it only what it takes from another stage. The
   * integrator owns this object, the context, the nodal state, the loop
   * and the work account; the scene's parts outlive the integrator.
   *
   * The fluid and the contact are null where they do not act, so that a
   * stage asks "is there one" and never "is it on".
   */
  template <int dim>
  struct StepParts
  {
    const IntegratorParameters<dim>     &parameters;
    const BackgroundGrid<dim>           &grid;
    MaterialPoints<dim>                 &points;
    VelocityRegion<dim>                 &velocity_region;
    const std::vector<RigidWall<dim> *> &rigid_walls;
    /// Null, or a fluid acting on the bodies' surface (only if enabled).
    VirtualFluid<dim> *virtual_fluid;
    /// Null, or the multi-body contact (only if a body has a field of its
    /// own).
    MultiFieldContact<dim> *contact;
    /// The clock, the step's first diagnosis, the timer, the communicator.
    StepContext &context;
    /// The nodal arrays and the velocity fields they hold per node.
    NodalState<dim> &nodes;
    /// The scene's basis and the loop over the points with it.
    const PointLoop<dim> &loop;
    /// The energy balance's running sums (external and absorbed work).
    WorkAccount &work;
  };
} // namespace mpm

#endif
