#include <mpm/energy_guard.h>
#include <mpm/parameters.h>

#include <sstream>

namespace mpm
{
  template <int dim>
  EnergyGuard<dim>::EnergyGuard(const double               bound,
                                const bool                 with_residual,
                                const MaterialPoints<dim> &points,
                                MPI_Comm                   comm)
    : bound(bound)
    , with_residual(with_residual)
    , points(points)
    , comm(comm)
  {
  }


  template <int dim>
  std::array<double, 3>
  EnergyGuard<dim>::check(const Statistics<dim> &s,
                          const WorkAccount     &sums,
                          const double           t,
                          const double           affine_energy)
  {
    const double work          = sums.external;
    const double absolute_work = sums.absolute_external;
    const double stress_work   = sums.absorbed;
    const double grid_work =
      sums.face_friction + sums.face_constraint + sums.damping + sums.contact;
    const double gravity =
      s.gravitational_energy - s.rigid_gravitational_energy;
    const double energy =
      s.kinetic_energy - s.rigid_kinetic_energy + s.strain_energy + gravity;
    if (!have_initial_state)
      {
        initial_energy     = energy;
        initial_motion     = energy - gravity;
        initial_gravity    = gravity;
        initial_strain     = s.strain_energy;
        initial_affine     = affine_energy;
        have_initial_state = true;
      }
    largest_release     = std::max(largest_release, initial_gravity - gravity);
    const double put_in = initial_motion + largest_release + absolute_work;
    const double gain   = energy - initial_energy - work;
    const double dissipation =
      with_residual ? stress_work - s.strain_energy + initial_strain : 0.;
    const double residual = with_residual ? gain + dissipation - grid_work +
                                              affine_energy - initial_affine
                                          : 0.;
    if (bound == 0)
      return {{put_in, residual, dissipation}};
    // Round-off of the sums (the gravitational energy is measured from the
    // origin, and can be far larger than any change of it).
    const double noise =
      1e-10 * (std::abs(initial_gravity) + std::abs(initial_motion));
    // Both balances stop the run with the same tail: how much of the
    // energy put in, the bound, the fastest point and what to try.
    const auto stop =
      [&](std::ostringstream &msg, const double excess, const char *verdict) {
        msg << (put_in > 0 ? excess / put_in : 0.) << " of the energy put in ("
            << put_in
            << " J), more than 'Simulation/energy growth bound' = " << bound
            << verdict << " (the fastest point: " << fastest_point()
            << "; try a smaller CFL number, a FLIP fraction below 1, or MUSL)";
        throw RunError(msg.str());
      };
    if (!(gain <= bound * put_in + noise))
      {
        std::ostringstream msg;
        msg << "t = " << t << ": the energy of the bodies grew by " << gain
            << " J beyond the work done on them (energy " << initial_energy
            << " -> " << energy << " J, work " << work << " J), ";
        stop(msg, gain, "; the run is unstable");
      }
    if (!(residual <= bound * put_in + noise))
      {
        std::ostringstream msg;
        msg << "t = " << t << ": the energy residual is " << residual
            << " J (the bodies' kinetic and gravitational energy plus the "
               "work their stresses absorbed, "
            << stress_work
            << " J of it, beyond their initial energy and the work done on "
               "them"
            << (grid_work != 0 ? " and taken out by the grid's faces, the "
                                 "damping and contact with rigid bodies"
                               : "")
            << "), ";
        stop(msg,
             residual,
             ": the numerics create energy, which plasticity hides in the "
             "total energy");
      }
    return {{put_in, residual, dissipation}};
  }


  template <int dim>
  std::string
  EnergyGuard<dim>::fastest_point() const
  {
    const FieldLayout &l       = points.layout();
    double             fastest = -1;
    std::string        description;
    for (const auto &p : points.handler())
      {
        const double *q     = p.get_properties().data();
        const double  speed = Fields::vector<dim>(q + l.velocity).norm();
        if (speed > fastest)
          {
            fastest = speed;
            std::ostringstream d;
            d << "material point " << p.get_id() << " of body " << q[l.body]
              << " at (" << p.get_location() << ") with speed " << speed
              << " m/s";
            description = d.str();
          }
      }
    const double       overall = Utilities::MPI::max(fastest, comm);
    const unsigned int owner =
      Utilities::MPI::min(fastest == overall
                            ? Utilities::MPI::this_mpi_process(comm)
                            : Utilities::MPI::n_mpi_processes(comm),
                          comm);
    return Utilities::MPI::broadcast(comm, description, owner);
  }


  template <int dim>
  void
  EnergyGuard<dim>::save_state(RunState &state) const
  {
    state.values["energy_guard_have_initial_state"] = have_initial_state;
    state.values["energy_guard_initial_energy"]     = initial_energy;
    state.values["energy_guard_initial_motion"]     = initial_motion;
    state.values["energy_guard_initial_gravity"]    = initial_gravity;
    state.values["energy_guard_initial_strain"]     = initial_strain;
    state.values["energy_guard_largest_release"]    = largest_release;
    state.values["energy_guard_initial_affine"]     = initial_affine;
  }


  template <int dim>
  void
  EnergyGuard<dim>::restore_state(const RunState &state)
  {
    have_initial_state = state.get("energy_guard_have_initial_state") != 0;
    initial_energy     = state.get("energy_guard_initial_energy");
    initial_motion     = state.get("energy_guard_initial_motion");
    initial_gravity    = state.get("energy_guard_initial_gravity");
    if (with_residual)
      initial_strain = state.get("energy_guard_initial_strain");
    largest_release = state.get("energy_guard_largest_release");
    // Not in checkpoints written before the affine fields were counted.
    if (state.values.count("energy_guard_initial_affine") != 0)
      initial_affine = state.get("energy_guard_initial_affine");
  }


  template class EnergyGuard<1>;
  template class EnergyGuard<2>;
  template class EnergyGuard<3>;
} // namespace mpm
