#ifndef mpm_grid_grid_update_h
#define mpm_grid_grid_update_h

#include <mpm/background_grid.h>
#include <mpm/boundary_conditions/grid_faces.h>
#include <mpm/boundary_conditions/velocity_region.h>
#include <mpm/boundary_conditions/virtual_fluid.h>
#include <mpm/contact/multi_field.h>
#include <mpm/external_loads.h>
#include <mpm/grid/nodal_state.h>
#include <mpm/integrator_parameters.h>
#include <mpm/step_parts.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The grid stage of the step: the nodal velocities from the scattered
   * momenta (after each transfer to the grid) and from the forces (the
   * force update, with damping and Newmark's factor), and the constraints
   * on them in this order: multi-body contact and rigid bodies, the
   * grid's faces (GridFaces), the velocity region. Where a constraint or
   * the virtual fluid does work on the bodies, it goes to the account of
   * ExternalLoads; with 'Simulation/energy residual', the work of the
   * grid's faces and of the damping (energy they only take out) goes to
   * the WorkAccount at each force update.
   *
   * It reads and writes the shared NodalState and owns only what lives
   * between the two velocity updates of one step: which nodes' fields
   * pressed on each other or on a rigid body at the force update (MUSL
   * with contact, see apply_contact()); the grid's faces keep theirs
   * (GridFaces::apply()).
   */
  template <int dim>
  class GridUpdate
  {
  public:
    /// @p light_mass: the small-mass guard's nodal mass (contact leaves
    /// fields this light out of its normals). The step's clock in
    /// @p context: the rigid bodies' motion.
    GridUpdate(const StepParts<dim> &parts,
               ExternalLoads<dim>   &loads,
               const double          light_mass);

    /// After the grid's partition changed (and the nodal arrays with it).
    void
    reinit();

    /// The velocities in @p slot from the momenta, then constrained;
    /// @p for_strain_rate: these velocities give the stress update's
    /// strain rate after the force update (MUSL), see apply_contact().
    void
    velocities_from_momentum(const unsigned int slot,
                             const bool         for_strain_rate = false);

    /// The force update v_new = v_old + dt f / m (with damping and
    /// Newmark's factor), then constrained; the fluid's work.
    void
    velocities_after_forces(const double dt);

    /// USF's strain-rate velocities, with deformable bodies in contact or
    /// friction faces: v_old into v_new, and where deformable fields would
    /// press on each other, or the stress push a node into a friction
    /// face, at a force update with the forces scattered so far (of the
    /// stress the step starts from), there they do not part along the
    /// normal (see apply_contact(), GridFaces::apply()).
    void
    usf_strain_rate_velocities(const double dt);

    /// Boundary constraints on the nodal velocities in @p slot: contact,
    /// the grid's faces, the velocity region; @p dt > 0 at the force
    /// update, where reactions are measured and dashpots act;
    /// @p for_strain_rate as in velocities_from_momentum().
    void
    apply_constraints(const unsigned int slot,
                      const double       dt              = 0,
                      const bool         for_strain_rate = false);

    /// Measure the out-of-balance force at each force update (a stage that
    /// ends at equilibrium); off, nothing is computed.
    bool measure_out_of_balance = false;
    /// This rank's sum over its owned nodes of the magnitude of the
    /// out-of-balance force at the last force update (see
    /// out_of_balance_force()).
    double local_out_of_balance = 0;

  private:
    /// The out-of-balance force of every owned node after the force update
    /// to @p dt: the force the body's stresses and loads put on the node,
    /// less what the supports (faces, walls, the velocity region) and
    /// contact with other bodies take, without the damping (which slows
    /// the motion but balances nothing). Summed over the node's fields,
    /// so that forces between two bodies cancel; the magnitudes summed
    /// over the nodes.
    double
    out_of_balance_force(const double dt) const;
    /// The work the damping did on the owned nodes at the force update to
    /// @p dt (after the constraints; see there).
    double
    damping_work(const double dt) const;
    /// Multi-body contact and rigid bodies at every owned node where a
    /// body has a field of its own; @p dt > 0 at the force update, where
    /// the rigid bodies' reactions are measured and where the fields press
    /// on each other is recorded for @p for_strain_rate (see there).
    /// Returns the work the rigid bodies' reactions did at their
    /// velocities (apply_constraints() counts it).
    double
    apply_contact(const unsigned int slot,
                  const double       dt,
                  const bool         for_strain_rate);
    /// The owned nodes where the contact would correct a field that
    /// moves into the others or a rigid body at the velocities in v_new
    /// (usf_strain_rate_velocities()'s trial force update).
    std::vector<unsigned int>
    nodes_pressed_in_contact() const;
    /// The contact's work on a node's deformable fields at the force
    /// update (see there).
    double
    contact_work_on_deformable_fields(const std::vector<double> &before,
                                      const double              *node) const;

    using Layout                               = NodalLayout<dim>;
    static constexpr unsigned int mass         = Layout::mass;
    static constexpr unsigned int momentum     = Layout::momentum;
    static constexpr unsigned int force        = Layout::force;
    static constexpr unsigned int n_sums       = Layout::n_sums;
    static constexpr unsigned int node_mass    = Layout::node_mass;
    static constexpr unsigned int v_old        = Layout::v_old;
    static constexpr unsigned int v_new        = Layout::v_new;
    static constexpr unsigned int n_velocities = Layout::n_velocities;

    const IntegratorParameters<dim> &prm;
    const BackgroundGrid<dim>       &grid;
    NodalState<dim>                 &nodes;
    /// The grid's faces (fixed, slip, friction, absorbing).
    GridFaces<dim>       faces;
    VelocityRegion<dim> &velocity_region;
    /// Null, or the multi-body contact (only if a body has its own field).
    MultiFieldContact<dim> *contact;
    /// Null, or a fluid acting on the bodies' surface (only if enabled).
    VirtualFluid<dim>  *virtual_fluid;
    ExternalLoads<dim> &loads;
    /// The energy balance's sums; the grid's own are kept only when
    /// account_grid_work ('Simulation/energy residual').
    WorkAccount       &work;
    const bool         account_grid_work;
    const double       light_mass;
    const StepContext &context;
    /// MUSL with contact only: per owned node, did a field press on the
    /// others or on a rigid body at this step's force update (see
    /// apply_contact())?
    std::vector<unsigned char> pressed_nodes;
  };
} // namespace mpm

#endif
