// The size of the step (see TimeStepLimit); initial_step says which limit
// sets the first step, for the log.
#include <mpm/parameters.h>
#include <mpm/time_step_limit.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mpm
{
  template <int dim>
  TimeStepLimit<dim>::TimeStepLimit(const StepParts<dim> &parts)
    : prm(parts.parameters)
    , grid(parts.grid)
    , points(parts.points)
    , rigid_walls(parts.rigid_walls)
    , velocity_region(parts.velocity_region)
    , contact(parts.contact)
    , context(parts.context)
    , density(deformable_densities(points.bodies()))
  {
    for (const auto &body : points.bodies())
      {
        // A rigid body's material is not used: no wave crosses it.
        wave_modulus.push_back(
          body.rigid_velocity ? 0. : body.material->p_wave_modulus());
        wave_modulus_pressure_slope.push_back(
          body.rigid_velocity ? 0.
                              : body.material->wave_modulus_pressure_slope());
        fixed_inverse_density.push_back(
          body.material->stiffness_is_kirchhoff() ? 1. / body.density : 0.);
        if (!body.rigid_velocity && body.material->viscosity() > 0)
          {
            const double limit =
              prm.mass_scaling * body.density *
              Utilities::fixed_power<2>(grid.min_cell_size()) /
              (2. * dim * body.material->viscosity());
            if (limit < viscous_time_step)
              {
                viscous_time_step = limit;
                viscous_body      = &body - points.bodies().data();
              }
          }
      }
  }


  template <int dim>
  double
  TimeStepLimit<dim>::stable_time_step()
  {
    TimerOutput::Scope scope(context.timer, "check and CFL");
    const FieldLayout &l = points.layout();
    // max(c_p + |v_p|) <= max c_p + max |v_p|: the bound costs no square
    // root per point and gives a time step that is, if anything, smaller.
    double max_c2 = 0, max_v2 = 0;
    for (const auto &p : points.handler())
      {
        const double                 *q = p.get_properties().data();
        const Tensor<1, dim>          v = Fields::vector<dim>(q + l.velocity);
        const SymmetricTensor<2, dim> s = Fields::symmetric<dim>(q + l.stress);
        const unsigned int            b = q[l.body];
        const double                  inverse_density = q[l.volume] / q[l.mass];
        // A stiffness that grows with the pressure (the Tait fluid) counts
        // the point's pressure; under tension the modulus at rest bounds
        // it from above. Only such bodies pay for it (a branch the same
        // for a body's points).
        double modulus = wave_modulus[b];
        if (wave_modulus_pressure_slope[b] > 0)
          modulus +=
            wave_modulus_pressure_slope[b] * std::max(-trace(s) / dim, 0.);
        // With mass scaling the waves see s rho.
        const double c2 =
          modulus *
          (fixed_inverse_density[b] > 0 ? fixed_inverse_density[b]
                                        : inverse_density) /
          prm.mass_scaling;
        const double v2 = v.norm_square();
        const double J  = inverse_density * density[b];
        // J = 0 marks a rigid body's points (no guard there).
        if ((J < prm.J_min && J > 0) || J > prm.J_max)
          if (!context.failed())
            {
              std::ostringstream msg;
              msg << context.when() << ": material point " << p.get_id()
                  << " of body " << b << " at (" << p.get_location()
                  << ") has J = V / V0 = " << J
                  << ", outside 'Simulation/J bounds' [" << prm.J_min << ", "
                  << prm.J_max << "]: it was "
                  << (J < 1 ? "crushed" : "torn apart")
                  << "; the run is unstable (try a smaller CFL number, MUSL, "
                     "a smooth basis) or the bounds are too tight";
              context.fail(msg.str());
            }
        // One test catches NaN/inf in velocity, stress and volume.
        if (!std::isfinite(c2 + v2 + (s * s) + q[l.volume]) &&
            !context.failed())
          {
            std::ostringstream msg;
            msg << context.when() << ": material point " << p.get_id()
                << " of body " << q[l.body] << " at (" << p.get_location()
                << ") has a non-finite "
                << (!std::isfinite(v2)        ? "velocity"
                    : !std::isfinite((s * s)) ? "stress"
                                              : "density (volume)")
                << "; the run is unstable (try a smaller CFL number, MUSL, "
                   "or damping)";
            context.fail(msg.str());
          }
        max_c2 = std::max(max_c2, c2);
        max_v2 = std::max(max_v2, v2);
      }
    context.raise_if_failed();
    // A moving rigid wall meets the material at its own speed plus the
    // material's: a step that lets the wall pass a cell puts points deep
    // inside it, whose penalty force then throws them out (a wall at
    // 10 m/s through the two disks moved 2 cells a step).
    double wall_speed = 0;
    for (const RigidWall<dim> *wall : rigid_walls)
      wall_speed = std::max(wall_speed, wall->speed());
    // A velocity region drives the material it holds at its speed, and a
    // rigid body moves at its prescribed one: from the first step on,
    // before the points have them (a rigid body's points start at its
    // 'initial velocity').
    double prescribed_speed = velocity_region.speed();
    if (contact)
      {
        contact->set_time(context.t);
        for (unsigned int r = 0; r < contact->rigid_bodies().size(); ++r)
          prescribed_speed =
            std::max(prescribed_speed, contact->rigid_velocity_of(r).norm());
      }
    const double max_speed =
      std::sqrt(Utilities::MPI::max(max_c2, context.comm)) +
      std::max(std::sqrt(Utilities::MPI::max(max_v2, context.comm)),
               prescribed_speed) +
      wall_speed;
    // Newmark's gamma > 1/2 shrinks the stable range of omega dt from 2 to
    // sqrt(2 / gamma) (benchmarks/verification/newmark_amplification.py).
    const double newmark_factor =
      prm.newmark_gamma > 0.5 ? std::sqrt(0.5 / prm.newmark_gamma) : 1.;
    return prm.cfl_number * newmark_factor *
           std::min(grid.min_cell_size() / max_speed, viscous_time_step);
  }


  template <int dim>
  void
  TimeStepLimit<dim>::check_requested_steps()
  {
    const bool fixed    = prm.fixed_time_step > 0;
    const bool substeps = prm.macro_time_step > 0 && prm.substeps > 0;
    if (!fixed && !substeps)
      return;
    // One pass over the points (collective) serves both checks.
    const double limit = stable_time_step();
    if (fixed)
      {
        if (prm.fixed_time_step > limit)
          {
            std::ostringstream allowed;
            allowed << "exceeds the stability limit CFL number * h / "
                       "max(c_p + |v_p|) = "
                    << limit
                    << " of the initial state; use a smaller step or 0";
            std::ostringstream value;
            value << prm.fixed_time_step;
            throw InputError("Simulation/time step",
                             value.str(),
                             allowed.str());
          }
      }
    if (substeps)
      {
        if (prm.macro_time_step / prm.substeps > limit * (1 + 1e-12))
          {
            std::ostringstream allowed;
            allowed << "gives substeps of "
                    << prm.macro_time_step / prm.substeps
                    << " s, beyond the stability limit " << limit
                    << " of the initial state; use at least "
                    << std::ceil(prm.macro_time_step / limit)
                    << ", or 0 to follow the CFL condition";
            throw InputError("Simulation/substeps",
                             std::to_string(prm.substeps),
                             allowed.str());
          }
      }
  }


  template <int dim>
  double
  TimeStepLimit<dim>::explicit_time_step()
  {
    const double dt = stable_time_step();
    if (prm.fixed_time_step == 0)
      return dt;
    if (prm.fixed_time_step > dt * (1 + 1e-12))
      throw RunError("step " + std::to_string(context.n_steps) +
                     ": the fixed time step " +
                     std::to_string(prm.fixed_time_step) +
                     " exceeds the stability limit " + std::to_string(dt) +
                     " of the current state (points sped up or "
                     "compressed); use a smaller 'Simulation/time step' "
                     "or 0 for the CFL condition");
    return prm.fixed_time_step;
  }


  template <int dim>
  std::pair<double, std::string>
  TimeStepLimit<dim>::initial_step()
  {
    std::ostringstream why;
    if (prm.macro_time_step > 0 && prm.substeps > 0)
      {
        why << "'Simulation/macro time step' = " << prm.macro_time_step
            << " s over 'Simulation/substeps' = " << prm.substeps;
        return {prm.macro_time_step / prm.substeps, why.str()};
      }
    const double limit = stable_time_step();
    if (prm.fixed_time_step > 0)
      return {prm.fixed_time_step, "'Simulation/time step'"};
    if (prm.macro_time_step > 0 && prm.macro_time_step < limit)
      return {prm.macro_time_step, "'Simulation/macro time step'"};
    const auto &body = points.bodies();
    if (prm.cfl_number * viscous_time_step <= limit * (1 + 1e-12))
      {
        const unsigned int b = viscous_body;
        why << "the viscous limit rho h^2 / (2 dim eta) of " << body[b].name
            << " ('" << body[b].material_name << "', viscosity "
            << body[b].material->viscosity()
            << " Pa s, 'density' = " << body[b].density << ")";
        return {limit, why.str()};
      }
    // The CFL condition: name the body whose waves are fastest at rest
    // (a huge initial speed shows in the speed itself).
    unsigned int b_fastest = 0;
    double       fastest   = 0;
    for (unsigned int b = 0; b < body.size(); ++b)
      if (wave_modulus[b] / body[b].density > fastest)
        fastest = wave_modulus[b] / body[b].density, b_fastest = b;
    const auto &b = body[b_fastest];
    why << "the CFL condition 'Simulation/CFL number' * h / max(c_p + |v_p|) "
           "with h = "
        << grid.min_cell_size() << " m; the fastest waves at rest, "
        << std::sqrt(fastest) << " m/s, are those of " << b.name << " ('"
        << b.material_name << "'"
        << (b.material->stiffness_parameters().empty()
              ? ""
              : ", " + b.material->stiffness_parameters())
        << ", 'density' = " << b.density << ")";
    return {prm.macro_time_step > 0 ? std::min(prm.macro_time_step, limit)
                                    : limit,
            why.str()};
  }


  template class TimeStepLimit<1>;
  template class TimeStepLimit<2>;
  template class TimeStepLimit<3>;
} // namespace mpm
