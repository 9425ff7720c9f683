#ifndef mpm_energy_guard_h
#define mpm_energy_guard_h

#include <mpm/checkpoint.h>
#include <mpm/material_points.h>
#include <mpm/statistics.h>
#include <mpm/work_account.h>

#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * Run-health guard on the energy balance. Between the start and any
   * output, the energy of the deformable bodies (kinetic, strain and
   * gravitational) can grow by no more than the work the scene does on
   * them: loads, body forces, walls, moving rigid bodies, velocity regions
   * and the virtual fluid (TimeIntegrator::external_work()). Damping,
   * friction, plasticity, absorbing faces and PIC only remove energy. What
   * is left, the gain
   *
   *   E(t) - E(0) - W(t),
   *
   * is made by the numerics. A run stops when the gain exceeds the bound
   * times the energy the scene has put in,
   *
   *   E_in(t) = kinetic + strain energy at the start
   *             + the most gravitational energy released so far
   *             + the work done so far, counted positive both ways,
   *
   * naming the fastest point (where a blow-up shows first).
   *
   * Plasticity can hide energy the numerics made: what it dissipates
   * offsets a gain. The energy residual ('Simulation/energy residual')
   * takes the work the stresses absorbed, summed step by step
   * (WorkAccount::absorbed), in place of the change of strain
   * energy:
   *
   *   R(t) = E(t) - Psi(t) + Psi(0) + W_sigma(t) - E(0) - W(t),
   *
   * which plasticity cannot offset (elastic, W_sigma = Psi(t) - Psi(0) to
   * the order of its quadrature). The work the grid takes out on purpose,
   * W_g(t) (friction and the other rules of the grid's faces, damping,
   * contact with rigid bodies: WorkAccount::face_friction,
   * face_constraint, damping, contact), is taken out of it too, so that R
   * is the numerics' share: the transfer's, contact between deformable
   * bodies', and what the time stepping makes. It is
   * held to the same bound.
   *
   * The balance is
   * checked at output times, where the statistics are summed anyway; the
   * J guard and the non-finite checks catch faster blow-ups every step.
   * Rigid bodies are boundary conditions: their own energy is left out.
   */
  template <int dim>
  class EnergyGuard
  {
  public:
    /// @p bound: allowed gain over E_in; 0 switches the guard off.
    /// @p with_residual: the energy residual is asked for.
    EnergyGuard(const double               bound,
                const bool                 with_residual,
                const MaterialPoints<dim> &points,
                MPI_Comm                   comm);

    /**
     * Check the balance at time @p t with the statistics @p s and the
     * sums of @p work since the start (WorkAccount::totals(): the external
     * work W and its absolute sum); collective. With the energy residual,
     * also the balance in which the work the stresses absorbed replaces
     * the change of strain energy and the grid's work W_g is taken out.
     * Throws RunError with a diagnosis. Returns E_in(t), the energy
     * residual R(t) and the dissipation W_sigma(t) - Psi(t) + Psi(0), the
     * work the stresses absorbed and do not store (plastic, viscous,
     * damage; both 0 without the residual), also when the guard is off.
     * Then E(t) - E(0) = W(t) - D(t) + W_g(t) + R(t). With APIC, the
     * residual's kinetic energy includes the points' affine fields',
     * @p affine_energy (TimeIntegrator::affine_kinetic_energy()).
     */
    std::array<double, 3>
    check(const Statistics<dim> &s,
          const WorkAccount     &work,
          const double           t,
          const double           affine_energy = 0);

    void
    save_state(RunState &state) const;
    void
    restore_state(const RunState &state);

  private:
    /// "material point N of body b at (x) with speed |v|", collective.
    std::string
    fastest_point() const;

    const double               bound;
    const bool                 with_residual;
    const MaterialPoints<dim> &points;
    MPI_Comm                   comm;
    bool                       have_initial_state = false;
    double                     initial_energy     = 0;
    double                     initial_motion     = 0; ///< kinetic + strain
    double                     initial_strain     = 0;
    double                     initial_gravity    = 0;
    double                     initial_affine     = 0;
    double                     largest_release    = 0;
  };
} // namespace mpm

#endif
