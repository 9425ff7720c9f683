#ifndef mpm_energy_guard_h
#define mpm_energy_guard_h

#include <mpm/checkpoint.h>
#include <mpm/material_points.h>
#include <mpm/output.h>

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
   * naming the fastest point (where a blow-up shows first). The balance is
   * checked at output times, where the statistics are summed anyway; the
   * J guard and the non-finite checks catch faster blow-ups every step.
   * Rigid bodies are boundary conditions: their own energy is left out.
   */
  template <int dim>
  class EnergyGuard
  {
  public:
    /// @p bound: allowed gain over E_in; 0 switches the guard off.
    EnergyGuard(const double               bound,
                const MaterialPoints<dim> &points,
                MPI_Comm                   comm);

    /**
     * Check the balance at time @p t with the statistics @p s and the
     * external work @p work (and its absolute sum @p absolute_work) done
     * since the start; collective. Throws RunError with a diagnosis.
     */
    void
    check(const Statistics<dim> &s,
          const double           work,
          const double           absolute_work,
          const double           t);

    void
    save_state(RunState &state) const;
    void
    restore_state(const RunState &state);

  private:
    /// "material point N of body b at (x) with speed |v|", collective.
    std::string
    fastest_point() const;

    const double               bound;
    const MaterialPoints<dim> &points;
    MPI_Comm                   comm;
    bool                       have_initial_state = false;
    double                     initial_energy     = 0;
    double                     initial_motion     = 0; ///< kinetic + strain
    double                     initial_gravity    = 0;
    double                     largest_release    = 0;
  };
} // namespace mpm

#endif
