#ifndef mpm_work_account_h
#define mpm_work_account_h

#include <deal.II/base/mpi.h>

namespace mpm
{
  struct RunState;

  /**
   * The work of an impulse m (v_after - v_before) on one velocity
   * component of a node at the force update (a face's, the damping's, the
   * contact's): at the mean of the node's velocity at the step's start,
   * @p v_old, and at its end, @p v_end. So split, the works of all the
   * forces on a node (its stress, the loads, the damping, the faces, the
   * contact) add up to its change of kinetic energy, and a node a face
   * holds at rest takes its support without work (not the energy of the
   * velocity it would have had).
   */
  inline double
  impulse_work(const double m,
               const double v_before,
               const double v_after,
               const double v_old,
               const double v_end)
  {
    return m * (v_after - v_before) * 0.5 * (v_old + v_end);
  }

  /**
   * The running sums of the energy balance (see EnergyGuard), kept in one
   * place: the work done on the bodies from outside (ExternalLoads closes
   * each step's into it), the sum of that work's absolute step increments,
   * the work the bodies' stresses absorbed (StressUpdate), and, with
   * 'Simulation/energy residual', the work of what takes energy out at
   * the grid (GridUpdate): friction on the grid's friction faces, the
   * other face rules, the damping, and contact with rigid bodies. Each rank
   * holds its share; the totals are sums over the ranks. A checkpoint keeps the
   * totals, and a restart, which may run on another number of ranks, gives them
   * to the first.
   */
  struct WorkAccount
  {
    double external          = 0;
    double absolute_external = 0;
    double absorbed          = 0;
    /// Coulomb friction of the grid's friction faces (<= 0).
    double face_friction = 0;
    /// The other face rules: the velocity into fixed, slip and friction
    /// faces taken out, fixed faces' tangential hold, the absorbing
    /// faces' dashpots (mostly <= 0; of either sign at O(dt) where nodes
    /// lift off and land within a step).
    double face_constraint = 0;
    /// Global and local (Cundall) damping (<= 0).
    double damping = 0;
    /// Contact with rigid bodies: the work of its impulses on the
    /// deformable bodies' fields where a rigid body takes part, less the
    /// rigid bodies' own work (external): what the inelastic closing and
    /// the friction against them take out (<= 0). Contact between
    /// deformable bodies stays in the energy residual.
    double contact = 0;

    /// Every sum over the ranks (collective).
    WorkAccount
    totals(const MPI_Comm comm) const;

    /// Put the totals into @p state (collective), or take them back.
    void
    save_state(RunState &state, const MPI_Comm comm) const;
    void
    restore_state(const RunState &state, const MPI_Comm comm);
  };
} // namespace mpm

#endif
