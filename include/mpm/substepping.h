#ifndef mpm_substepping_h
#define mpm_substepping_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <mpm/grid/nodal_layout.h>
#include <mpm/step_context.h>

namespace mpm
{
  using namespace dealii;

  template <int dim>
  class TimeIntegrator;
  template <int dim>
  class NodalState;
  template <int dim>
  class MaterialPoints;
  template <int dim>
  class BackgroundGrid;
  template <int dim>
  struct IntegratorParameters;
  struct RunState;

  /**
   * Substepping (seed 003): a macro step Dt made of S explicit substeps of
   * the integrator, after which the grid velocity on the start-of-step
   * configuration is reconstructed from what the points did, so that an
   * operation that needs a large step (a projection, a coupling with
   * another solver, dynamic relaxation) can act once per macro step on a
   * grid velocity that stands for the whole of it. It drives the
   * integrator's explicit step and shares its nodal state and point loop,
   * whose friend it is.
   */
  template <int dim>
  class Substepper
  {
  public:
    explicit Substepper(TimeIntegrator<dim> &integrator);

    /// S substeps and the macro step's reconstruction and operations.
    void
    macro_step(const double Dt);

    /**
     * The grid velocity on the start-of-step configuration from the
     * points' secant motion over a macro step of length @p Dt (seed 003,
     * the closed-form APIC reconstruction),
     *   m_k v_k = sum_p m_p w_kp(x_p^n) (v*_p + C*_p (x_k - x_p^n)),
     *   Dt v*_p = x_p^(n+1) - x_p^n,   Dt C*_p = F_p^(n+1) (F_p^n)^-1 - I,
     * then divided by m_k and projected on the boundary conditions.
     * Expects the points at x_p^n, with x_p^(n+1) and the substeps'
     * deformation increment in their 'macro step' field (as end() leaves
     * them; public for the tests). NodalState::velocity() then reads v_k.
     */
    void
    reconstruct_grid_velocity(const double Dt);

    /// Macro steps taken so far (0 without substepping).
    unsigned int
    macro_step_number() const
    {
      return n_macro_steps;
    }

    /**
     * The largest distance, over all points and macro steps so far, between
     * a point's substepped position and where the reconstructed grid
     * velocity carries it, |x_p^(n+1) - x_p^n - Dt sum_k w_kp v_k|, in
     * units of the smallest cell size: how faithfully the macro step's grid
     * velocity stands for the substeps (seed 003's consistency).
     */
    double
    largest_mismatch() const
    {
      return mismatch;
    }

    /// Least-squares reconstruction: conjugate-gradient iterations of the
    /// last macro step, summed over the components.
    unsigned int
    last_least_squares_iterations() const
    {
      return least_squares_iterations;
    }

    /// Put the counters into @p state, or take them back from it.
    void
    save_state(RunState &state) const;
    void
    restore_state(const RunState &state);

  private:
    using Layout = NodalLayout<dim>;

    /// Record x_p^n and start each point's deformation increment at I.
    void
    begin();
    /// One explicit substep of @p dt and its deformation increment.
    void
    substep(const double dt);
    /// Multiply each point's deformation increment by this substep's
    /// I + dt L (after F-bar: the increment the stress update used, which
    /// the points keep until the next step's kinematics).
    void
    accumulate_increment(const double dt);
    /// Swap each point's position with the one in its 'macro step' field
    /// (x^(n+1) <-> x^n) and put the points in their cells again.
    void
    swap_positions();
    /// The reconstruction, the operations on v_k and their transfer back
    /// to the points (see reconstruct_grid_velocity()).
    void
    end(const double Dt);
    template <typename Basis>
    void
    scatter_targets(const Basis &basis, const double Dt);
    /// Seed 003's system (4) for v_k, solved from the closed form's v_k.
    template <typename Basis>
    void
    solve_least_squares_reconstruction(const Basis &basis, const double Dt);
    /**
     * The hook where operations that need the whole macro step act on the
     * reconstructed grid velocity v_k (a projection, a coupling with a
     * large-step solver). Returns true if an operation reset v_k, so that
     * the points must take their velocities from it.
     */
    bool
    apply_operations();
    /// The points take the grid velocity (after a reset by an operation),
    /// and the macro step's mismatch is measured.
    template <typename Basis>
    void
    gather_velocity(const Basis &basis, const double Dt, const bool reset);

    /// Call @p f(p, q, m) for each point p of this rank, with q its data
    /// and m its 'macro step' field in it (x^n or x^(n+1), then the
    /// substeps' deformation increment), timed as the macro step.
    template <typename Function>
    void
    for_each_macro_field(const Function &f);
    /// Call @p f(q, s, m, target) for each point with its data, stencil,
    /// mass and secant targets over the macro step @p Dt (the points at
    /// x^n, as end() leaves them).
    template <typename Basis, typename Function>
    void
    for_each_secant_target(const Basis    &basis,
                           const double    Dt,
                           const Function &f);

    TimeIntegrator<dim> &integrator;
    /// The integrator's parts the macro step reads most, named as there.
    const IntegratorParameters<dim> &prm;
    const BackgroundGrid<dim>       &grid;
    MaterialPoints<dim>             &points;
    NodalState<dim>                 &nodes;
    StepContext                     &context;

    /// Macro steps taken, the largest mismatch (see largest_mismatch()),
    /// and the grid's kinetic energy at the last macro step (kinetic
    /// damping).
    unsigned int n_macro_steps        = 0;
    double       mismatch             = 0;
    double       macro_kinetic_energy = 0;
    /// Least squares: CG iterations of the last macro step (all components).
    unsigned int least_squares_iterations = 0;
  };
} // namespace mpm

#endif
