#ifndef mpm_time_integrator_h
#define mpm_time_integrator_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/background_grid.h>
#include <mpm/basis.h>
#include <mpm/boundary_conditions/rigid_wall.h>
#include <mpm/boundary_conditions/velocity_region.h>
#include <mpm/boundary_conditions/virtual_fluid.h>
#include <mpm/checkpoint.h>
#include <mpm/contact/multi_field.h>
#include <mpm/external_loads.h>
#include <mpm/grid/grid_update.h>
#include <mpm/grid/nodal_layout.h>
#include <mpm/grid/nodal_state.h>
#include <mpm/integrator_parameters.h>
#include <mpm/material_points.h>
#include <mpm/point_fields.h>
#include <mpm/step_parts.h>
#include <mpm/stress_update.h>
#include <mpm/substepping.h>
#include <mpm/time_step_limit.h>
#include <mpm/transfer/grid_to_particle.h>
#include <mpm/transfer/particle_to_grid.h>
#include <mpm/transfer/point_loop.h>
#include <mpm/work_account.h>

#include <array>
#include <functional>
#include <limits>

namespace mpm
{
  using namespace dealii;

  /**
   * The explicit MPM step, particles -> grid -> particles:
   *
   *   USL : P2G(m, mv, f)  grid(v, v*)  G2P(v, x, L, F)        stress
   *   USF : P2G(m, mv)     grid(v)      kinematics(L, F) stress
   *         P2G(f)         grid(v*)     G2P(v, x)
   *   MUSL: P2G(m, mv, f)  grid(v, v*)  G2P(v, x)
   *         P2G(mv) again  grid(v)      kinematics(L, F)       stress
   *
   * followed by relocation of the points and a check of their state. The
   * variants share every kernel; only the order differs.
   *
   * Nodal data (NodalState): `nodes.sums` holds [m, mv (dim), f (dim)]
   * per node and is summed over ranks with compress(add);
   * `nodes.velocities` holds [m, v, v*] per node (mass, velocity before
   * and after the force update) and is read through ghost values.
   *
   * Small-mass guard: a node that only the far corner of a point's stencil
   * reaches has a mass that tends to zero while its force does not, so its
   * force-updated velocity can become huge. Particle velocities and
   * positions are safe, because they see that node through weight/mass <=
   * 1/m_p; USL's strain rate, taken from the force-updated velocities, is
   * not when the gradient weight does not vanish with the weight (the
   * linear basis). There, nodes lighter than 'small mass fraction' times
   * the smallest point mass are left out of L (their velocity replaced by
   * the point's own grid velocity, which keeps L zero for a rigid
   * translation), and the internal force leaves them out the same way
   * (light_node_gradients in particle_to_grid.cc): the force stays the adjoint
   * of the strain rate, so its work is the stress power, and momentum is
   * conserved exactly. MUSL and USF take L from transferred velocities (means
   * of the points' velocities) and need no guard.
   */
  template <int dim>
  class TimeIntegrator
  {
  public:
    TimeIntegrator(const IntegratorParameters<dim>     &parameters,
                   const BackgroundGrid<dim>           &grid,
                   MaterialPoints<dim>                 &points,
                   VelocityRegion<dim>                 &velocity_region,
                   TimerOutput                         &timer,
                   MPI_Comm                             comm,
                   const std::vector<RigidWall<dim> *> &rigid_walls   = {},
                   VirtualFluid<dim>                   *virtual_fluid = nullptr,
                   MultiFieldContact<dim>              *contact = nullptr);

    /// (Re)create the nodal vectors and the nodal data that depend on the
    /// grid's partition (after BackgroundGrid::repartition()).
    void
    setup_nodal_data();

    /// Advance by one step, of at most @p max_dt: an explicit step, or a
    /// macro step of substeps if the scene sets a macro time step. Throws
    /// RunError (on all ranks) with a diagnosis if the new state is not
    /// sound.
    void
    step(const double max_dt);

    /// The macro steps (substepping; their counters are 0 without).
    const Substepper<dim> &
    substepping() const
    {
      return substepper;
    }
    Substepper<dim> &
    substepping()
    {
      return substepper;
    }

    double
    time() const
    {
      return context.t;
    }
    unsigned int
    step_number() const
    {
      return context.n_steps;
    }
    double
    last_time_step() const
    {
      return last_dt;
    }
    types::particle_index
    n_removed_particles() const
    {
      return n_removed;
    }

    /// The nodal arrays of the last step (grid output).
    const NodalState<dim> &
    nodal_state() const
    {
      return nodes;
    }

    /// One P2G -> G2P round trip with no time step and no forces: what
    /// the transfer alone does to the points' velocities (rigid rotation
    /// test of APIC).
    void
    transfer_round_trip();

    /// Stable time step of the current state: CFL number times
    /// h / max(c_p + |v_p|). Also checks that every point is finite.
    double
    stable_time_step()
    {
      return limits.stable_time_step();
    }

    /// The length of the explicit steps (substeps) the run starts with and
    /// what sets it, in words that name the parameter (collective): for
    /// the estimate of a run's length before it starts.
    std::pair<double, std::string>
    initial_step()
    {
      return limits.initial_step();
    }

    /// Measure the out-of-balance force at each force update (a stage that
    /// ends at equilibrium).
    void
    measure_out_of_balance()
    {
      grid_update.measure_out_of_balance = true;
    }
    /// The sum over the grid's nodes of the magnitude of the out-of-balance
    /// force at the last force update (GridUpdate::out_of_balance_force();
    /// collective).
    double
    out_of_balance_force() const
    {
      return Utilities::MPI::sum(grid_update.local_out_of_balance,
                                 context.comm);
    }

    /// Called after every substep of a macro step (the progress line of a
    /// macro step that takes long).
    std::function<void()> after_substep;

    /// Put the clock and counters into @p state, or take them back from
    /// it (checkpoint and restart).
    void
    save_state(RunState &state) const;
    void
    restore_state(const RunState &state);

    /// The energy balance's running sums: the external and the absorbed
    /// work, the grid's work.
    const WorkAccount &
    work_account() const
    {
      return work;
    }

    /**
     * APIC: the kinetic energy the points' affine velocity fields hold
     * beyond 1/2 m_p |v_p|^2, sum_p 1/2 m_p sum_{i,d} D_pd C_pid^2, D_pd
     * the basis' second moment sum_I N_I (x_I - x_p)_d^2 at the point (at
     * the stencils the last step began with). It is what the transfer to
     * the grid gives the nodes besides: the energy the transfer keeps or
     * loses is that of v_p + C_p (x - x_p) (Jiang et al. 2017). Deformable
     * bodies only; 0 without an affine field. Collective.
     */
    double
    affine_kinetic_energy() const;

    /**
     * The two sides of the identity that makes the internal forces' work
     * the stress power: for nodal velocities @p w (a function of a node's
     * lattice coordinates, the same for every field),
     * {sum_I f_I . w_I, sum_p V_p sigma_p : L_p(w)}, with the forces and
     * the strain rate as this scene's step computes them from the points'
     * current stresses and positions. Their sum vanishes when the two
     * operators are adjoint. Gravity and loads must be off (they add to
     * f). With F-bar, L_bar(w) of a step of @p f_bar_step (F-bar's volume
     * average is linear in w only as the step goes to 0). Summed over the
     * ranks (collective).
     */
    std::array<double, 2>
    internal_work_and_stress_power(
      const std::function<Tensor<1, dim>(const std::array<unsigned int, dim> &)>
                  &w,
      const double f_bar_step = 1e-9);

  private:
    friend class Substepper<dim>;

    // Components of the interleaved nodal vectors.
    using Layout = NodalLayout<dim>;

    /// One explicit step of @p dt (all that step() does without
    /// substepping).
    void
    explicit_step(const double dt);
    /// The step with basis @p basis, in the order of the update scheme.
    template <typename Basis>
    void
    advance(const Basis &basis, const double dt);
    /// The step's nodal masses, momenta (velocities in v_old) and forces,
    /// with USL's small-mass guard on the forces' side too (see
    /// ParticleToGrid::scatter).
    template <typename Basis>
    void
    scatter_masses_then_forces(const Basis &basis);

    const IntegratorParameters<dim> prm;
    /// The walls acting on the points.
    const std::vector<RigidWall<dim> *> rigid_walls;
    /// The clock, the step's first diagnosis, the timer, the communicator:
    /// what every stage below reads.
    StepContext context;
    /// The nodal arrays and the velocity fields they hold per node.
    NodalState<dim> nodes;
    /// The scene's basis and the loop over the points with it.
    PointLoop<dim> loop;
    /// The energy balance's running sums.
    WorkAccount work;
    /// The scene's parts with the members above, as every stage below sees
    /// them.
    const StepParts<dim> parts;
    /// F-bar, the materials' update and the stress power.
    StressUpdate<dim> stresses;
    /// USF with deformable bodies that touch or friction faces: its
    /// strain rate needs a trial force update (see
    /// GridUpdate::usf_strain_rate_velocities).
    const bool usf_trial_forces;

    /// The small-mass guard's nodal mass (see strain_rate_light_mass in
    /// transfer/strain_rate.h).
    const double          min_nodal_mass;
    double                last_dt   = 0;
    types::particle_index n_removed = 0;
    /// The time step's limits and the check of the points' state.
    TimeStepLimit<dim> limits;
    /// The loads and the external work.
    ExternalLoads<dim> loads;
    /// The stages: P2G, the nodal velocities and their constraints, G2P.
    ParticleToGrid<dim> to_grid;
    GridUpdate<dim>     grid_update;
    GridToParticle<dim> to_points;
    /// The macro steps, if the scene sets a macro time step.
    Substepper<dim> substepper;
  };
} // namespace mpm

#endif
