#include <mpm/basis.h>
#include <mpm/parameters.h>
#include <mpm/time_integrator.h>
#include <mpm/time_integrator.templates.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace mpm
{
  template <int dim>
  FieldRequests
  point_fields_needed(const IntegratorParameters<dim>             &integrator,
                      const std::vector<BodyParameters<dim>>      &bodies,
                      const std::vector<RigidWallParameters<dim>> &walls,
                      const bool initial_position)
  {
    FieldRequests fields;
    fields.initial_position = initial_position;
    for (const auto &body : bodies)
      fields.initial_position =
        fields.initial_position || body.body_force || body.is_displaced();
    fields.deformation_gradient = integrator.basis == BasisType::cpgimp;
    fields.affine_velocity      = integrator.transfer == Transfer::apic;
    fields.macro_step           = integrator.macro_time_step > 0;
    for (const auto &body : bodies)
      {
        fields.surface_area = fields.surface_area || body.has_surface_loads();
        fields.surface_offset =
          fields.surface_offset ||
          (body.has_surface_loads() &&
           body.loaded_face != numbers::invalid_unsigned_int);
      }
    for (const auto &wall : walls)
      fields.wall_slips += wall.friction_coefficient > 0;
    fields.point_load = fields.surface_area || !walls.empty();
    return fields;
  }


  template <int dim>
  std::vector<unsigned int>
  wall_slip_slots(const std::vector<RigidWallParameters<dim>> &walls)
  {
    std::vector<unsigned int> slots;
    unsigned int              n_slips = 0;
    for (const auto &wall : walls)
      slots.push_back(wall.friction_coefficient > 0
                        ? n_slips++
                        : numbers::invalid_unsigned_int);
    return slots;
  }


  template <int dim>
  TimeIntegrator<dim>::TimeIntegrator(
    const IntegratorParameters<dim>     &parameters,
    const BackgroundGrid<dim>           &grid,
    MaterialPoints<dim>                 &points,
    VelocityRegion<dim>                 &velocity_region,
    TimerOutput                         &timer,
    MPI_Comm                             comm,
    const std::vector<RigidWall<dim> *> &rigid_walls,
    VirtualFluid<dim>                   *virtual_fluid,
    MultiFieldContact<dim>              *contact)
    : prm(parameters)
    , grid(grid)
    , points(points)
    , velocity_region(velocity_region)
    , rigid_walls(rigid_walls)
    , virtual_fluid(virtual_fluid != nullptr && virtual_fluid->enabled()
                      ? virtual_fluid
                      : nullptr)
    , contact(contact != nullptr && contact->n_fields() > 1 ? contact : nullptr)
    , n_fields(this->contact ? this->contact->n_fields() : 1)
    , usf_contact_rule(prm.scheme == UpdateScheme::USF && this->contact &&
                       this->contact->deformable_bodies_touch())
    , timer(timer)
    , comm(comm)
  {
    setup_nodal_data();
    for (unsigned int b = 0; b < points.bodies().size(); ++b)
      field_of_body.push_back(this->contact ? this->contact->field_of_body(b)
                                            : 0);
    for (const auto &body : points.bodies())
      {
        // A rigid body's material is not used: no wave crosses it.
        wave_modulus_of_body.push_back(
          body.rigid_velocity ? 0. : body.material->p_wave_modulus());
        wave_modulus_pressure_slope_of_body.push_back(
          body.rigid_velocity ? 0.
                              : body.material->wave_modulus_pressure_slope());
        fixed_inverse_density_of_body.push_back(
          body.material->stiffness_is_kirchhoff() ? 1. / body.density : 0.);
        // A rigid body's points keep their volume: no guard.
        density_of_body.push_back(body.rigid_velocity ? 0. : body.density);
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
        body_forces.push_back(body.body_force.get());
        pressures.push_back(body.pressure.get());
        tractions.push_back(body.traction.get());
        has_body_forces = has_body_forces || body.body_force;
        initial_half_width_of_body.push_back(0.5 / body.particles_per_cell);
      }
    // Nodal masses are stored with the mass scaling (see
    // grid_velocities_from_momentum), and so is the guard's threshold.
    min_nodal_mass =
      prm.small_mass_fraction * prm.mass_scaling * points.min_particle_mass();
    const auto &grid_prm = grid.parameters();
    if (std::count(grid_prm.boundary.begin(),
                   grid_prm.boundary.end(),
                   BoundaryType::absorbing) > 0)
      {
        const auto &bodies = points.bodies();
        if (grid_prm.absorbing_body >= bodies.size())
          throw InputError("Grid/absorbing body",
                           std::to_string(grid_prm.absorbing_body),
                           "must be the index of a body, < " +
                             std::to_string(bodies.size()));
        const auto &body = bodies[grid_prm.absorbing_body];
        normal_impedance =
          std::sqrt(body.density * body.material->p_wave_modulus());
        shear_impedance =
          std::sqrt(body.density * body.material->shear_modulus());
      }
    Assert(prm.basis != BasisType::cpgimp ||
             points.layout().deformation_gradient != FieldLayout::absent,
           ExcMessage("cpGIMP needs the deformation gradient"));
    Assert(prm.transfer != Transfer::apic ||
             points.layout().affine_velocity != FieldLayout::absent,
           ExcMessage("APIC needs the affine velocity field"));

    // The cubic B-spline's stencil spans two cells on each side of a
    // point's node; the boundary folding needs a second grid node inside.
    if (prm.basis == BasisType::cubic_bspline)
      for (unsigned int d = 0; d < dim; ++d)
        if (grid.parameters().n_cells[d] < 2)
          throw InputError("Simulation/basis",
                           "cubic B-spline",
                           "needs at least 2 grid cells in every direction "
                           "('Grid/cells')");

    if (prm.fixed_time_step > 0)
      {
        const double limit = stable_time_step();
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
    if (prm.least_squares && n_fields > 1)
      throw InputError("Simulation/macro reconstruction",
                       "least squares",
                       "works on one velocity field; a scene with bodies in "
                       "'Contact/bodies' or rigid bodies needs 'APIC'");
    if (prm.macro_time_step > 0 && prm.substeps > 0)
      {
        const double limit = stable_time_step();
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
  void
  TimeIntegrator<dim>::setup_nodal_data()
  {
    grid_sums.reinit(grid.make_partitioner(n_fields * n_sums));
    grid_velocity.reinit(grid.make_partitioner(n_fields * n_velocities));
    if (contact)
      {
        contact_data.reinit(grid.make_partitioner(
          n_fields * MultiFieldContact<dim>::data_per_field));
        // Only deformable fields press on each other.
        if (prm.scheme == UpdateScheme::MUSL &&
            contact->deformable_bodies_touch())
          pressed_nodes.assign(grid.n_locally_owned_nodes(), 0);
      }
    if (virtual_fluid)
      {
        fluid_volume.reinit(grid.make_partitioner(1));
        fluid_force.reinit(grid.make_partitioner(n_fields * dim));
        support_volume.reinit(grid.make_partitioner(1));
        for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
          support_volume.local_element(i) = grid.node_support_volume(i);
        support_volume.update_ghost_values();
      }
  }


  template <int dim>
  void
  TimeIntegrator<dim>::step(const double max_dt)
  {
    if (prm.macro_time_step > 0)
      macro_step(std::min(prm.macro_time_step, max_dt));
    else
      explicit_step(std::min(explicit_time_step(), max_dt));
  }


  template <int dim>
  double
  TimeIntegrator<dim>::explicit_time_step()
  {
    const double dt = stable_time_step();
    if (prm.fixed_time_step == 0)
      return dt;
    if (prm.fixed_time_step > dt * (1 + 1e-12))
      throw RunError("step " + std::to_string(n_steps) +
                     ": the fixed time step " +
                     std::to_string(prm.fixed_time_step) +
                     " exceeds the stability limit " + std::to_string(dt) +
                     " of the current state (points sped up or "
                     "compressed); use a smaller 'Simulation/time step' "
                     "or 0 for the CFL condition");
    return prm.fixed_time_step;
  }


  template <int dim>
  void
  TimeIntegrator<dim>::keep_points_in_front_of_rigid_walls(const double time)
  {
    const unsigned int n_walls = rigid_walls.size();
    if (n_walls == 0)
      return;
    std::vector<Point<dim>>     position(n_walls);
    std::vector<Tensor<1, dim>> reaction(n_walls);
    std::vector<double>         work_of_wall(n_walls, 0.);
    for (unsigned int w = 0; w < n_walls; ++w)
      position[w] = rigid_walls[w]->position(time);
    // A point put back by one wall may then be behind another. In a corner
    // a few more passes settle it (alternating projections onto the walls'
    // half-spaces converge there: in a 53-degree notch by 0.36 a pass);
    // between walls that close on each other faster than the material can
    // flow away, or meet, nothing does, and the run stops rather than pack
    // points without deforming them (issue 32: two walls at 10 m/s on the
    // soft disks squeezed both into a sheet and ran on through each other).
    const unsigned int max_passes = n_walls == 1 ? 1 : 40;
    const FieldLayout &l          = points.layout();
    for (auto &p : points.handler())
      {
        double moved = 0;
        for (unsigned int pass = 0; pass < max_passes; ++pass)
          {
            moved = 0;
            for (unsigned int w = 0; w < n_walls; ++w)
              moved += rigid_walls[w]->put_back(
                p, l, position[w], reaction[w], work_of_wall[w]);
            if (moved == 0)
              break;
          }
        if (n_walls == 1 || moved == 0 || !failure.empty())
          continue;
        const double size = std::pow(p.get_properties()[l.volume], 1. / dim);
        if (moved > 1e-6 * size)
          {
            std::ostringstream msg;
            msg << "step " << n_steps << ", t = " << time << ": material point "
                << p.get_id() << " of body " << p.get_properties()[l.body]
                << " at (" << p.get_location()
                << ") is pinched between rigid walls: put back by each in "
                << "turn " << max_passes << " times, it still lies more than "
                << "a quarter of its size (" << 0.25 * size
                << " m) behind one of them; the walls close on the material "
                   "faster than it can flow away, or meet";
            failure = msg.str();
          }
      }
    for (unsigned int w = 0; w < n_walls; ++w)
      {
        rigid_walls[w]->add_impulse(reaction[w]);
        work += work_of_wall[w];
        absolute_work += std::abs(work_of_wall[w]);
      }
    // One wall puts every point back in one pass: no pinch to agree on.
    if (n_walls > 1)
      raise_if_any_failed(failure, comm);
  }


  template <int dim>
  void
  TimeIntegrator<dim>::explicit_step(const double dt)
  {
    with_scene_basis([&](const auto &basis) { advance(basis, dt); });
    raise_if_any_failed(failure, comm);
    close_external_work(dt);
    // After the step's loads did their work at the velocities they saw.
    keep_points_in_front_of_rigid_walls(t + dt);

    {
      TimerOutput::Scope scope(timer, "relocate");
      n_removed += points.relocate(prm.out_of_grid);
    }
    t += dt;
    last_dt = dt;
    ++n_steps;
  }


  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::advance(const Basis &basis, const double dt)
  {
    if (points.layout().point_load != FieldLayout::absent)
      make_point_loads(dt);
    const double work_before = step_work; // see USF with cpGIMP
    switch (prm.scheme)
      {
        case UpdateScheme::USL:
          scatter_masses_then_forces(basis);
          grid_velocities_after_forces(dt);
          gather_to_particles(basis, dt, true);
          update_stresses(dt);
          break;
        case UpdateScheme::USF:
          // With deformable bodies in contact, the forces of the stress the
          // step starts from tell where they press on each other (see
          // apply_contact); the updated stress's replace them below.
          scatter_to_grid(basis, true, usf_contact_rule);
          grid_velocities_from_momentum(v_old);
          if (usf_contact_rule)
            strain_rate_velocities_with_contact(dt);
          update_kinematics(basis, dt, usf_contact_rule ? v_new : v_old);
          update_stresses(dt);
          if (prm.basis == BasisType::cpgimp)
            {
              // The domains follow F, which the kinematics just changed:
              // mass, momentum and force must come from the same stencils,
              // or a node that the grown domain reaches gets a force and
              // (almost) no mass (v_notch: a point thrown out of the grid).
              // The first grid velocities only gave the strain rate, and
              // their constraints do no work.
              step_work = work_before;
              scatter_to_grid(basis, true, true);
              grid_velocities_from_momentum(v_old);
            }
          else
            scatter_to_grid(basis, false, true);
          grid_velocities_after_forces(dt);
          gather_to_particles(basis, dt, false);
          break;
        case UpdateScheme::MUSL:
          scatter_masses_then_forces(basis);
          grid_velocities_after_forces(dt);
          gather_to_particles(basis, dt, false);
          scatter_to_grid(basis, true, false);
          grid_velocities_from_momentum(v_new, true);
          update_kinematics(basis, dt, v_new);
          update_stresses(dt);
          break;
      }
  }


  /**
   * USL takes its strain rate from the force-updated velocities, and
   * leaves the light nodes out of it (velocity_gradient). The internal
   * force must then leave them out the same way, or the force's work is
   * no longer the stress power and parting bodies gain energy
   * (light_node_gradients): the masses come first, then the forces with
   * the light nodes known. MUSL and USF take the strain rate from
   * transferred velocities and need no guard: one pass.
   */
  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::scatter_masses_then_forces(const Basis &basis)
  {
    const double light_mass = strain_rate_light_mass<Basis>();
    if (light_mass > 0)
      {
        scatter_to_grid(basis, true, false);
        grid_velocities_from_momentum(v_old);
        scatter_to_grid(basis, false, true, light_mass);
      }
    else
      {
        scatter_to_grid(basis, true, true);
        grid_velocities_from_momentum(v_old);
      }
  }


  template <int dim>
  std::array<double, 2>
  TimeIntegrator<dim>::internal_work_and_stress_power(
    const std::function<Tensor<1, dim>(const std::array<unsigned int, dim> &)>
      &w)
  {
    double work = 0, power = 0;
    with_scene_basis([&](const auto &basis) {
      using Basis = std::decay_t<decltype(basis)>;
      scatter_masses_then_forces(basis);
      double       *u = grid_velocity.get_values();
      const double *g = grid_sums.get_values();
      for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
        {
          const Tensor<1, dim> w_i = w(grid.owned_node_coordinates(i));
          for (unsigned int f = 0; f < n_fields; ++f)
            for (unsigned int d = 0; d < dim; ++d)
              {
                u[n_velocities * slot_of(i, f) + v_new + d] = w_i[d];
                work += g[n_sums * slot_of(i, f) + force + d] * w_i[d];
              }
        }
      grid_velocity.update_ghost_values();
      const FieldLayout &l = points.layout();
      for_each_point(basis, [&](auto &, const double *q, const auto &s) {
        const Tensor<2, dim> L =
          velocity_gradient(s,
                            grid_velocity.get_values() +
                              n_velocities * field_of(q),
                            n_fields * n_velocities,
                            v_new,
                            strain_rate_light_mass<Basis>());
        power +=
          q[l.volume] * scalar_product(Fields::symmetric<dim>(q + l.stress), L);
      });
    });
    return {
      {Utilities::MPI::sum(work, comm), Utilities::MPI::sum(power, comm)}};
  }


  template <int dim>
  void
  TimeIntegrator<dim>::transfer_round_trip()
  {
    with_scene_basis([&](const auto &basis) {
      scatter_to_grid(basis, true, false);
      grid_velocities_from_momentum(v_old);
      // No force, no step: the new grid velocity is the old one.
      grid_velocities_from_momentum(v_new);
      gather_to_particles(basis, 0., false);
    });
    raise_if_any_failed(failure, comm);
  }


  template <int dim>
  double
  TimeIntegrator<dim>::stable_time_step()
  {
    TimerOutput::Scope scope(timer, "check and CFL");
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
        double modulus = wave_modulus_of_body[b];
        if (wave_modulus_pressure_slope_of_body[b] > 0)
          modulus += wave_modulus_pressure_slope_of_body[b] *
                     std::max(-trace(s) / dim, 0.);
        // With mass scaling the waves see s rho.
        const double c2 = modulus *
                          (fixed_inverse_density_of_body[b] > 0
                             ? fixed_inverse_density_of_body[b]
                             : inverse_density) /
                          prm.mass_scaling;
        const double v2 = v.norm_square();
        const double J  = inverse_density * density_of_body[b];
        // J = 0 marks a rigid body's points (no guard there).
        if ((J < prm.J_min && J > 0) || J > prm.J_max)
          if (failure.empty())
            {
              std::ostringstream msg;
              msg << "step " << n_steps << ", t = " << t << ": material point "
                  << p.get_id() << " of body " << b << " at ("
                  << p.get_location() << ") has J = V / V0 = " << J
                  << ", outside 'Simulation/J bounds' [" << prm.J_min << ", "
                  << prm.J_max << "]: it was "
                  << (J < 1 ? "crushed" : "torn apart")
                  << "; the run is unstable (try a smaller CFL number, MUSL, "
                     "a smooth basis) or the bounds are too tight";
              failure = msg.str();
            }
        // One test catches NaN/inf in velocity, stress and volume.
        if (!std::isfinite(c2 + v2 + (s * s) + q[l.volume]) && failure.empty())
          {
            std::ostringstream msg;
            msg << "step " << n_steps << ", t = " << t << ": material point "
                << p.get_id() << " of body " << q[l.body] << " at ("
                << p.get_location() << ") has a non-finite "
                << (!std::isfinite(v2)        ? "velocity"
                    : !std::isfinite((s * s)) ? "stress"
                                              : "density (volume)")
                << "; the run is unstable (try a smaller CFL number, MUSL, "
                   "or damping)";
            failure = msg.str();
          }
        max_c2 = std::max(max_c2, c2);
        max_v2 = std::max(max_v2, v2);
      }
    raise_if_any_failed(failure, comm);
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
        contact->set_time(t);
        for (unsigned int r = 0; r < contact->rigid_bodies().size(); ++r)
          prescribed_speed =
            std::max(prescribed_speed, contact->rigid_velocity_of(r).norm());
      }
    const double max_speed =
      std::sqrt(Utilities::MPI::max(max_c2, comm)) +
      std::max(std::sqrt(Utilities::MPI::max(max_v2, comm)), prescribed_speed) +
      wall_speed;
    // Newmark's gamma > 1/2 shrinks the stable range of omega dt from 2 to
    // sqrt(2 / gamma) (benchmarks/verification/newmark_amplification.py).
    const double newmark_factor =
      prm.newmark_gamma > 0.5 ? std::sqrt(0.5 / prm.newmark_gamma) : 1.;
    return prm.cfl_number * newmark_factor *
           std::min(grid.min_cell_size() / max_speed, viscous_time_step);
  }


  template <int dim>
  std::pair<double, std::string>
  TimeIntegrator<dim>::initial_step()
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
      if (wave_modulus_of_body[b] / body[b].density > fastest)
        fastest = wave_modulus_of_body[b] / body[b].density, b_fastest = b;
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


  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::scatter_to_grid(const Basis &basis,
                                       const bool   mass_and_momentum,
                                       const bool   forces,
                                       const double light_mass)
  {
    TimerOutput::Scope scope(timer, "P2G");
    double            *g         = grid_sums.get_values();
    const unsigned int n_entries = n_local_entries(grid_sums);
    for (unsigned int i = 0; i < n_entries; i += n_sums)
      {
        if (mass_and_momentum)
          for (unsigned int c = mass; c < force; ++c)
            g[i + c] = 0;
        if (forces)
          for (unsigned int c = force; c < n_sums; ++c)
            g[i + c] = 0;
      }
    const bool with_gradients = contact && mass_and_momentum;
    if (with_gradients)
      contact_data = 0.;

    const FieldLayout   &l       = points.layout();
    const Tensor<1, dim> gravity = prm.gravity;
    const bool           apic    = prm.transfer == Transfer::apic;
    // Local copies: the compiler cannot tell that the members do not change
    // while the loop writes the nodal sums through a double *.
    const bool with_body_forces         = has_body_forces;
    double     power                    = 0; // of the body forces
    const bool with_point_loads         = l.point_load != FieldLayout::absent;
    const bool with_surface_loads       = l.load_moment != FieldLayout::absent;
    const unsigned int  fields_per_node = n_fields;
    const unsigned int *fields_of_body  = field_of_body.data();
    // The nodal masses of the guard (light_mass > 0), ghosted.
    const double *velocities = grid_velocity.get_values();
    for (auto *f : body_forces)
      if (f != nullptr)
        f->set_time(t);
    // Compiled once for one field and once for several, so that a scene
    // without contact carries nothing of it.
    // The guard's gradients (light_node_gradients), filled only where a
    // stencil has a light node: scratch kept out of the point loop, which
    // would otherwise zero it for every point.
    std::array<Tensor<1, dim>, Basis::n_nodes> spread;
    auto scatter = [&](auto several_fields) {
      constexpr bool multi_field = decltype(several_fields)::value;
      for_each_point(basis, [&](auto &p, const double *q, const auto &s) {
        const double m     = q[l.mass];
        unsigned int field = 0;
        if constexpr (multi_field)
          field = fields_of_body[static_cast<unsigned int>(q[l.body])];
        // The nodal sums of stencil node v, in this point's field.
        auto sums_of = [&](const unsigned int v) {
          if constexpr (multi_field)
            return g + n_sums * (fields_per_node * s.nodes[v] + field);
          else
            return g + n_sums * s.nodes[v];
        };
        if (mass_and_momentum)
          {
            const Tensor<1, dim> mv = m * Fields::vector<dim>(q + l.velocity);
            // APIC: the point's velocity field v_p + C_p (x - x_p), sampled
            // at the node.
            Tensor<2, dim> mC;
            if (apic)
              mC = m * Fields::tensor<dim>(q + l.affine_velocity);
            for (unsigned int v = 0; v < Basis::n_nodes; ++v)
              {
                double              *node = sums_of(v);
                const Tensor<1, dim> p = apic ? mv + mC * s.node_offset(v) : mv;
                node[mass] += s.weights[v] * m;
                for (unsigned int d = 0; d < dim; ++d)
                  node[momentum + d] += s.weights[v] * p[d];
              }
            // Contact normals of each field, and how many of its points'
            // domains (a box of side V^(1/dim) around each) hold the node:
            // where a body's surface lies on the grid.
            if constexpr (multi_field)
              if (with_gradients)
                {
                  const double half_side =
                    0.5 * (1 + 1e-9) * std::pow(q[l.volume], 1. / dim);
                  // A rigid body's normal is the gradient of its volume,
                  // not of its mass: its density must not change how it
                  // acts (with 1e-300 the products underflowed and the
                  // floor stopped acting).
                  const double weight =
                    density_of_body[static_cast<unsigned int>(q[l.body])] > 0
                      ? m
                      : q[l.volume];
                  for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                    {
                      double *data = contact_data.begin() +
                                     MultiFieldContact<dim>::data_per_field *
                                       slot_of(s.nodes[v], field);
                      for (unsigned int d = 0; d < dim; ++d)
                        data[d] += weight * s.gradients[v][d];
                      const Tensor<1, dim> r      = s.node_offset(v);
                      bool                 inside = true;
                      for (unsigned int d = 0; d < dim; ++d)
                        inside = inside && std::abs(r[d]) <= half_side;
                      data[dim] += inside;
                    }
                }
          }
        if (forces)
          {
            // Internal force with the current volume and Cauchy stress.
            const SymmetricTensor<2, dim> Vsigma =
              q[l.volume] * Fields::symmetric<dim>(q + l.stress);
            const bool guarded =
              light_mass > 0 &&
              light_node_gradients(s,
                                   velocities +
                                     (multi_field ? n_velocities * field : 0),
                                   multi_field ? fields_per_node * n_velocities
                                               : n_velocities,
                                   light_mass,
                                   spread);
            const auto    &gradients = guarded ? spread : s.gradients;
            Tensor<1, dim> mg        = m * gravity;
            if (with_body_forces)
              {
                const Tensor<1, dim> b = body_force(q);
                check_load(b.norm(),
                           q[l.body],
                           "body force",
                           p->get_location());
                const Tensor<1, dim> mb = m * b;
                mg += mb;
                power += mb * Fields::vector<dim>(q + l.velocity);
              }
            if (with_point_loads)
              mg += Fields::vector<dim>(q + l.point_load);
            auto add_forces = [&](const auto &stress_term) {
              for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                {
                  const Tensor<1, dim> f =
                    s.weights[v] * mg - stress_term * gradients[v];
                  double *node = sums_of(v) + force;
                  for (unsigned int d = 0; d < dim; ++d)
                    node[d] += f[d];
                }
            };
            // A surface load F acts at the surface, d from the point:
            // F phi(x + d) = F phi(x) + (F (x) d) grad phi(x) to first
            // order (exact within a cell for the linear basis), so the
            // moment F (x) d joins the stress term; the point load holds
            // F phi(x). The quadratic B-spline takes phi(x + d) itself
            // where its functions reach x + d as one piece each
            // (Basis::weights_at): to first order its node beyond the
            // surface, which holds 1/16 of a point's mass, is 1/32 F out of
            // balance with the top points' stress, and pure FLIP let that
            // grow until the energy guard stopped the loaded column; exact,
            // it balances (0.028-0.064 over the schemes and transfers).
            // The other bases measure better to first order (cubic
            // B-spline 0.040-0.047 against 0.046-0.126; uGIMP 0.020 against
            // 0.034, whose weight averages over the point's domain).
            if (with_surface_loads)
              {
                const Tensor<2, dim> moment =
                  Fields::tensor<dim>(q + l.load_moment);
                const Tensor<1, dim> d =
                  Fields::vector<dim>(q + l.surface_offset);
                std::array<double, Basis::n_nodes> at_surface;
                if (moment.norm_square() > 0 &&
                    basis.weights_at(s, d, at_surface))
                  {
                    // moment = F (x) d
                    const Tensor<1, dim> F = moment * d / (d * d);
                    for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                      {
                        double *node = sums_of(v) + force;
                        for (unsigned int c = 0; c < dim; ++c)
                          node[c] += (at_surface[v] - s.weights[v]) * F[c];
                      }
                    add_forces(Vsigma);
                  }
                else if (!guarded)
                  add_forces(Tensor<2, dim>(Vsigma) - moment);
                else
                  {
                    // The load's moment is no stress: the basis' gradients.
                    add_forces(Vsigma);
                    for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                      {
                        const Tensor<1, dim> f    = moment * s.gradients[v];
                        double              *node = sums_of(v) + force;
                        for (unsigned int d = 0; d < dim; ++d)
                          node[d] += f[d];
                      }
                  }
              }
            else
              add_forces(Vsigma);
          }
      });
    };
    if (n_fields > 1)
      scatter(std::true_type());
    else
      scatter(std::false_type());
    if (forces)
      body_force_power = power;
    grid_sums.compress(VectorOperation::add);
    if (with_gradients)
      contact_data.compress(VectorOperation::add);
    if (forces && virtual_fluid)
      add_fluid_forces(basis);
  }


  /**
   * The virtual stress method (cl-mpm): the force of a pressure p on the
   * surface of a body, f_I = -int_dOmega p n phi_I dA, is by the divergence
   * theorem -int_Omega (p grad phi_I + phi_I grad p) dV, an integral over
   * the body that the points evaluate like the internal force, with the
   * "virtual stress" -p I. It needs no surface: the surface is wherever
   * the points end. For a node whose support lies inside the body the exact
   * integral vanishes, so only nodes whose support the wetted bodies do
   * not fill (to 0.1 %) get it; inside, the point quadrature would only
   * add its error, which the pressure's kink at the fluid's level makes
   * large. The threshold must be tight: a node just inside the surface
   * has its support's edge outside, a sliver of little volume but a
   * share of the surface force that is not small, most of all with the
   * quadratic B-spline (uncovered volume ~ d^3 / 6, weight on the surface
   * ~ d^2 / 2, d the sliver's width in cells). A point lattice that is
   * undisturbed covers an inner node's support exactly (the midpoint rule
   * integrates each piece of the basis, the errors cancel), so 0.1 %
   * leaves only distortion to tell apart. Floating block, draft error at
   * 16 / 32 cells: quadratic B-spline 0.50 % / 0.11 % with this mask
   * (7.3 % / 4.4 % with 1 %, 8.4 % / 0.74 % with every node); linear
   * 0.05 %, uGIMP (32) 0.08 %, as with 1 %; 19 % with a 10 % threshold.
   */
  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::add_fluid_forces(const Basis &basis)
  {
    TimerOutput::Scope scope(timer, "virtual fluid");
    const FieldLayout &l = points.layout();
    fluid_volume         = 0.;
    for_each_point(basis, [&](auto &, const double *q, const auto &s) {
      if (virtual_fluid->wets(q[l.body]))
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          fluid_volume.local_element(s.nodes[v]) += s.weights[v] * q[l.volume];
    });
    fluid_volume.compress(VectorOperation::add);
    fluid_volume.update_ghost_values();

    auto on_surface = [&](const unsigned int node) {
      return fluid_volume.local_element(node) <
             (1. - 1e-3) * support_volume.local_element(node);
    };
    fluid_force = 0.;
    virtual_fluid->set_time(t);
    for_each_point(basis, [&](auto &p, const double *q, const auto &s) {
      if (!virtual_fluid->wets(q[l.body]))
        return;
      bool near_surface = false;
      for (unsigned int v = 0; v < Basis::n_nodes; ++v)
        near_surface = near_surface || on_surface(s.nodes[v]);
      if (!near_surface)
        return;
      Tensor<1, dim> grad_p;
      const double   pressure =
        virtual_fluid->pressure(p->get_location(), grad_p);
      if (pressure == 0 && grad_p.norm_square() == 0)
        return;
      const double V = q[l.volume];
      for (unsigned int v = 0; v < Basis::n_nodes; ++v)
        if (on_surface(s.nodes[v]))
          {
            const Tensor<1, dim> f =
              -V * (pressure * s.gradients[v] + s.weights[v] * grad_p);
            for (unsigned int d = 0; d < dim; ++d)
              fluid_force.local_element(dim * slot_of(s.nodes[v], field_of(q)) +
                                        d) += f[d];
          }
    });
    fluid_force.compress(VectorOperation::add);

    double *g         = grid_sums.get_values();
    fluid_force_total = Tensor<1, dim>();
    for (unsigned int i = 0; i < n_fields * grid.n_locally_owned_nodes(); ++i)
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double f = fluid_force.local_element(dim * i + d);
          g[n_sums * i + force + d] += f;
          fluid_force_total[d] += f;
        }
  }


  template <int dim>
  void
  TimeIntegrator<dim>::make_point_loads(const double dt)
  {
    const FieldLayout &l = points.layout();
    for (const auto &loads : {pressures, tractions})
      for (auto *f : loads)
        if (f != nullptr)
          f->set_time(t);
    for (auto &p : points.handler())
      {
        double *q = p.get_properties().data();
        Fields::store(Tensor<1, dim>(), q + l.point_load);
        if (l.surface_area == FieldLayout::absent)
          continue;
        const bool with_moment = l.load_moment != FieldLayout::absent;
        if (with_moment)
          Fields::store(Tensor<2, dim>(), q + l.load_moment);
        const unsigned int b = q[l.body];
        if (pressures[b] == nullptr && tractions[b] == nullptr)
          continue;
        // Most points of a loaded body lie inside it: skip the parsers.
        const Tensor<1, dim> area = Fields::vector<dim>(q + l.surface_area);
        if (area.norm_square() == 0)
          continue;
        Tensor<1, dim> load;
        if (pressures[b] != nullptr)
          {
            const double pressure = pressures[b]->value(p.get_location());
            check_load(std::abs(pressure), b, "pressure", p.get_location());
            load -= pressure * area;
          }
        if (tractions[b] != nullptr)
          {
            Tensor<1, dim> traction;
            for (unsigned int d = 0; d < dim; ++d)
              traction[d] = tractions[b]->value(p.get_location(), d);
            check_load(traction.norm(), b, "traction", p.get_location());
            load += traction * area.norm();
          }
        Fields::store(load, q + l.point_load);
        if (with_moment)
          Fields::store(
            outer_product(load, Fields::vector<dim>(q + l.surface_offset)),
            q + l.load_moment);
      }
    for (auto *wall : rigid_walls)
      wall->act_on_points(points.handler(), l, wave_modulus_of_body, t, dt);
    add_point_load_work(0.5 * dt);
  }


  /**
   * End the step's account of external work: the second halves of the
   * trapezoidal rules (point loads and body forces at the new velocities;
   * the first halves were taken at the start), then the totals. Extra
   * passes over the points only in scenes with such loads.
   */
  template <int dim>
  void
  TimeIntegrator<dim>::close_external_work(const double dt)
  {
    const FieldLayout &l = points.layout();
    if (l.point_load != FieldLayout::absent)
      add_point_load_work(0.5 * dt);
    if (has_body_forces)
      {
        TimerOutput::Scope scope(timer, "external work");
        for (auto *f : body_forces)
          if (f != nullptr)
            f->set_time(t + dt);
        for (const auto &p : points.handler())
          {
            const double *q = p.get_properties().data();
            body_force_power +=
              q[l.mass] * (body_force(q) * Fields::vector<dim>(q + l.velocity));
          }
      }
    step_work += 0.5 * dt * body_force_power;
    work += step_work;
    absolute_work += std::abs(step_work);
    step_work        = 0;
    body_force_power = 0;
  }


  /**
   * The work of the point loads (surface loads, penalty walls) over the
   * step, by the trapezoidal rule: half of it at the points' velocities
   * before the step, half after. At the start velocity alone, a load
   * applied to a body at rest did no work in its first step, and the
   * energy guard stopped a loaded column at t = 1e-4 (found by the fuzzer).
   */
  template <int dim>
  void
  TimeIntegrator<dim>::add_point_load_work(const double weight)
  {
    TimerOutput::Scope scope(timer, "external work");
    const FieldLayout &l = points.layout();
    // A surface load acts at the surface, d from the point, where the
    // velocity is v + L d: its power is F . v + (F (x) d) : L.
    const bool at_surface = l.load_moment != FieldLayout::absent;
    for (const auto &p : points.handler())
      {
        const double *q     = p.get_properties().data();
        double        power = Fields::vector<dim>(q + l.point_load) *
                       Fields::vector<dim>(q + l.velocity);
        if (at_surface)
          power += scalar_product(Fields::tensor<dim>(q + l.load_moment),
                                  Fields::tensor<dim>(q + l.velocity_gradient));
        step_work += weight * power;
      }
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
  TimeIntegrator<dim>::check_load(const double       magnitude,
                                  const unsigned int body,
                                  const char        *name,
                                  const Point<dim>  &x)
  {
    if (magnitude <= largest_input || !failure.empty())
      return;
    std::ostringstream msg;
    msg << "step " << n_steps << ", t = " << t << ": parameter '"
        << points.bodies()[body].name << "/" << name << "' is " << magnitude
        << " in magnitude at (" << x << "): a load must be finite and at most "
        << largest_input << " in magnitude (Pa, or m/s^2 for a body force)";
    failure = msg.str();
  }


  template <int dim>
  inline Tensor<1, dim>
  TimeIntegrator<dim>::body_force(const double *q) const
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


  template <int dim>
  void
  TimeIntegrator<dim>::grid_velocities_from_momentum(const unsigned int slot,
                                                     const bool for_strain_rate)
  {
    TimerOutput::Scope scope(timer, "grid update");
    const double      *g       = grid_sums.get_values();
    double            *u       = grid_velocity.get_values();
    const double       inertia = prm.mass_scaling;
    // The fields of a node follow each other: one loop over all entries.
    for (unsigned int i = 0; i < n_fields * grid.n_locally_owned_nodes(); ++i)
      {
        const double *node  = g + n_sums * i;
        double       *vel   = u + n_velocities * i;
        const double  inv_m = node[mass] > 0 ? 1. / node[mass] : 0.;
        // The inertia of the momentum balance: s m (mass scaling), which
        // every use of the nodal mass (force update, reactions, dashpots,
        // guard) then sees.
        vel[node_mass] = inertia * node[mass];
        for (unsigned int d = 0; d < dim; ++d)
          vel[slot + d] = node[momentum + d] * inv_m;
      }
    apply_velocity_constraints(slot, 0., for_strain_rate);
    grid_velocity.update_ghost_values();
  }


  template <int dim>
  void
  TimeIntegrator<dim>::grid_velocities_after_forces(const double dt)
  {
    TimerOutput::Scope scope(timer, "grid update");
    const double      *g = grid_sums.get_values();
    double            *u = grid_velocity.get_values();
    // Implicit in the damping term: unconditionally stable for any c.
    const double damping_factor = 1. / (1. + prm.damping * dt);
    const double alpha          = prm.local_damping;
    // Newmark (see gather_to_particles): v_new is the velocity that moves
    // the points, v_old + (gamma + 1/2) dt a.
    const bool   newmark       = prm.newmark_gamma != 0.5;
    const double motion_factor = prm.newmark_gamma + 0.5;
    for (unsigned int i = 0; i < n_fields * grid.n_locally_owned_nodes(); ++i)
      {
        const double *node = g + n_sums * i;
        double       *vel  = u + n_velocities * i;
        // vel[node_mass] is the scaled inertia (mass scaling).
        const double dt_m = vel[node_mass] > 0 ? dt / vel[node_mass] : 0.;
        for (unsigned int d = 0; d < dim; ++d)
          {
            double f = node[force + d];
            // Cundall: the unbalanced force loses alpha |f| against the
            // motion (none at rest, where sign(v) = 0).
            if (alpha > 0)
              f -= alpha * std::abs(f) *
                   ((vel[v_old + d] > 0) - (vel[v_old + d] < 0));
            vel[v_new + d] = (vel[v_old + d] + dt_m * f) * damping_factor;
          }
      }
    // A loop of its own, so that the plain step's stays as it was.
    if (newmark)
      for (unsigned int i = 0; i < n_fields * grid.n_locally_owned_nodes(); ++i)
        {
          double *vel = u + n_velocities * i;
          for (unsigned int d = 0; d < dim; ++d)
            vel[v_new + d] = vel[v_old + d] +
                             motion_factor * (vel[v_new + d] - vel[v_old + d]);
        }
    apply_velocity_constraints(v_new, dt);
    grid_velocity.update_ghost_values();
    if (virtual_fluid)
      {
        virtual_fluid->add_impulse(dt * fluid_force_total);
        for (unsigned int i = 0; i < n_fields * grid.n_locally_owned_nodes();
             ++i)
          for (unsigned int d = 0; d < dim; ++d)
            step_work += 0.5 * dt * fluid_force.local_element(dim * i + d) *
                         (u[n_velocities * i + v_old + d] +
                          u[n_velocities * i + v_new + d]);
      }
  }


  template <int dim>
  void
  TimeIntegrator<dim>::apply_velocity_constraints(const unsigned int slot,
                                                  const double       dt,
                                                  const bool for_strain_rate)
  {
    if (contact)
      apply_contact(slot, dt, for_strain_rate);
    // Grid faces and the velocity region act on every field alike.
    double *u = grid_velocity.get_values();
    for (const auto &[i, mask] : grid.constrained_nodes())
      for (unsigned int f = 0; f < n_fields; ++f)
        for (unsigned int d = 0; d < dim; ++d)
          if (mask & (1u << d))
            u[n_velocities * slot_of(i, f) + slot + d] = 0;
    const double mu = grid.parameters().friction_coefficient;
    for (const auto &[i, faces] : grid.friction_nodes())
      for (unsigned int f = 0; f < n_fields; ++f)
        for (unsigned int face = 0; face < 2 * dim; ++face)
          if (faces & (1u << face))
            apply_coulomb_contact(u + n_velocities * slot_of(i, f) + slot,
                                  face,
                                  mu);
    if (dt > 0 && !grid.absorbing_nodes().empty())
      apply_dashpots(slot, dt);
    if (velocity_region.enabled())
      for (unsigned int f = 0; f < n_fields; ++f)
        step_work += velocity_region.enforce(u + n_velocities * f,
                                             n_fields * n_velocities,
                                             slot,
                                             dt);
  }


  /**
   * MUSL takes the strain rate from velocities transferred again after
   * the force update, not from the force update's own (USL does). Where
   * two bodies press on each other, the force update moves a field's
   * surface node, light there but pushed by its body's stress, into the
   * other body, and the contact gives its momentum to the other field at
   * the other's velocity; the strain rate's velocities, transferred anew
   * and not corrected where the surfaces part, saw the node at its own.
   * While the bodies part, the work done on the other body then exceeds
   * the strain energy the pushing body gives up: two disks (uGIMP) lost
   * energy until they were at rest against each other and gained it back
   * and more as they parted, to 1.075 of the initial energy with FLIP and
   * 0.975 with PIC (one field: 1.004, 0.570). So at the strain rate's
   * velocities the fields do not part along the normal where they pressed
   * on each other at this step's force update: the strain rate sees the
   * constraint the contact force acted through (now 1.000 and 0.577; every
   * basis in benchmarks/contact/README.md). USF, whose strain rate comes
   * from the velocities before the force update, gained the same way
   * (1.088 with FLIP, 1.001 with PIC). It has no force update before its
   * strain rate, so it tries one with the forces of the stress the step
   * starts from (strain_rate_velocities_with_contact): now 1.018 and 0.610
   * (one field: 1.027, 0.630). The state is made in the step it is used,
   * so nothing carries over from one step to the next, which a
   * repartition (load balance, between steps) would lose.
   */
  template <int dim>
  void
  TimeIntegrator<dim>::apply_contact(const unsigned int slot,
                                     const double       dt,
                                     const bool         for_strain_rate)
  {
    double       *u    = grid_velocity.get_values();
    const double *data = contact_data.get_values();
    contact->set_time(t);
    std::vector<Tensor<1, dim>> impulse(contact->rigid_bodies().size());
    // Only MUSL with deformable bodies in contact keeps pressed_nodes.
    const bool record = dt > 0 && !pressed_nodes.empty();
    const bool hold   = for_strain_rate && !pressed_nodes.empty();
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        const bool pressed =
          contact->correct_node(u + n_velocities * slot_of(i, 0),
                                n_velocities,
                                slot,
                                data + MultiFieldContact<dim>::data_per_field *
                                         slot_of(i, 0),
                                min_nodal_mass,
                                hold && pressed_nodes[i],
                                impulse);
        if (record)
          pressed_nodes[i] = pressed;
      }
    if (dt > 0)
      contact->add_rigid_impulses(impulse);
    // The rigid body's reaction works at its velocity (an upper bound:
    // friction's share is dissipated), at both velocity updates.
    for (unsigned int r = 0; r < impulse.size(); ++r)
      step_work += impulse[r] * contact->rigid_velocity_of(r);
  }


  template <int dim>
  void
  TimeIntegrator<dim>::strain_rate_velocities_with_contact(const double dt)
  {
    TimerOutput::Scope scope(timer, "grid update");
    const double      *g    = grid_sums.get_values();
    const double      *data = contact_data.get_values();
    double            *u    = grid_velocity.get_values();
    contact->set_time(t);
    // A node's fields, to try the force update on: only the sign of the
    // approach matters, so damping and Newmark's factor are left out, and
    // no reaction is measured.
    std::vector<double>         trial(n_fields * n_velocities);
    std::vector<Tensor<1, dim>> impulse(contact->rigid_bodies().size());
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        double      *node      = u + n_velocities * slot_of(i, 0);
        unsigned int n_present = 0;
        for (unsigned int f = 0; f < n_fields; ++f)
          {
            double *vel = node + n_velocities * f;
            for (unsigned int d = 0; d < dim; ++d)
              vel[v_new + d] = vel[v_old + d];
            n_present += vel[node_mass] > 0;
          }
        if (n_present < 2)
          continue;
        std::copy(node, node + n_fields * n_velocities, trial.begin());
        for (unsigned int f = 0; f < n_fields; ++f)
          {
            const double *sums = g + n_sums * slot_of(i, f);
            double       *vel  = trial.data() + n_velocities * f;
            const double  dt_m = vel[node_mass] > 0 ? dt / vel[node_mass] : 0.;
            for (unsigned int d = 0; d < dim; ++d)
              vel[v_new + d] += dt_m * sums[force + d];
          }
        const double *node_data =
          data + MultiFieldContact<dim>::data_per_field * slot_of(i, 0);
        if (contact->correct_node(trial.data(),
                                  n_velocities,
                                  v_new,
                                  node_data,
                                  min_nodal_mass,
                                  false,
                                  impulse))
          contact->correct_node(node,
                                n_velocities,
                                v_new,
                                node_data,
                                min_nodal_mass,
                                true,
                                impulse);
      }
    grid_velocity.update_ghost_values();
  }


  template <int dim>
  double
  TimeIntegrator<dim>::nodal_mass(const unsigned int i) const
  {
    double m = 0;
    for (unsigned int f = 0; f < n_fields; ++f)
      m +=
        grid_velocity.local_element(n_velocities * slot_of(i, f) + node_mass);
    return m / prm.mass_scaling; // the true mass
  }


  template <int dim>
  double
  TimeIntegrator<dim>::nodal_velocity(const unsigned int i,
                                      const unsigned int d) const
  {
    double m = 0, p = 0;
    for (unsigned int f = 0; f < n_fields; ++f)
      {
        const double *node =
          grid_velocity.begin() + n_velocities * slot_of(i, f);
        m += node[node_mass];
        p += node[node_mass] * node[v_new + d];
      }
    return m > 0 ? p / m : 0.;
  }


  template <int dim>
  void
  TimeIntegrator<dim>::apply_dashpots(const unsigned int slot, const double dt)
  {
    // The dashpot force -A Z v (Z = rho c_p on the normal, rho c_s on the
    // tangential components) taken implicitly in the force update,
    // m (v - v*) = -dt A Z v, so v = v* / (1 + dt A Z / m): stable for any
    // nodal mass, and a light node is simply held.
    double *u = grid_velocity.get_values();
    for (const AbsorbingNode &a : grid.absorbing_nodes())
      for (unsigned int f = 0; f < n_fields; ++f)
        {
          double      *node = u + n_velocities * slot_of(a.node, f);
          const double m    = node[node_mass];
          if (!(m > 0))
            continue;
          const double normal = 1. / (1. + dt * a.area * normal_impedance / m);
          const double shear  = 1. / (1. + dt * a.area * shear_impedance / m);
          for (unsigned int d = 0; d < dim; ++d)
            node[slot + d] *= (d == a.face / 2) ? normal : shear;
        }
  }


  template <int dim>
  void
  TimeIntegrator<dim>::apply_coulomb_contact(double            *v,
                                             const unsigned int face,
                                             const double       mu)
  {
    // The face's outward normal is +-e_axis. Only a velocity into the face
    // is in contact; its removal is the normal impulse (per unit mass), and
    // friction takes at most mu times that from the tangential velocity.
    const unsigned int axis   = face / 2;
    const double       sign   = (face % 2 == 0) ? -1. : 1.;
    const double       inward = sign * v[axis];
    if (!(inward > 0))
      return;
    v[axis]              = 0;
    double tangential_sq = 0;
    for (unsigned int d = 0; d < dim; ++d)
      if (d != axis)
        tangential_sq += v[d] * v[d];
    if (tangential_sq == 0)
      return;
    const double tangential = std::sqrt(tangential_sq);
    const double scale      = std::max(0., 1. - mu * inward / tangential);
    for (unsigned int d = 0; d < dim; ++d)
      if (d != axis)
        v[d] *= scale;
  }


  template <int dim>
  template <typename Stencil>
  inline Tensor<2, dim>
  TimeIntegrator<dim>::velocity_gradient(const Stencil     &s,
                                         const double      *u,
                                         const unsigned int stride,
                                         const unsigned int slot,
                                         const double       light_mass) const
  {
    Tensor<1, dim> v_point;
    for (unsigned int v = 0; v < s.weights.size(); ++v)
      v_point +=
        s.weights[v] * Fields::vector<dim>(u + stride * s.nodes[v] + slot);
    // Sum of (v_I - v_point) grad phi_I: equal to sum v_I grad phi_I, since
    // the gradients sum to zero, but light nodes can now be left out. With
    // USL and the linear basis they must be: a node that only the edge of
    // a point's support reaches has a tiny mass phi m_p but a full force
    // V sigma grad phi, so its force-updated velocity grows as 1 / phi; in
    // the point's velocity it counts with phi, here with grad phi. The
    // internal force then leaves them out too (light_node_gradients).
    // Massless nodes (light_mass 0) have no velocity at all; they lie in
    // a stencil only where a point lies on a cell face, weight 0.
    Tensor<2, dim> L;
    for (unsigned int v = 0; v < s.weights.size(); ++v)
      {
        const double *node = u + stride * s.nodes[v];
        if (node[node_mass] > light_mass)
          L += outer_product(Fields::vector<dim>(node + slot) - v_point,
                             s.gradients[v]);
      }
    return L;
  }


  /**
   * The strain rate with the guard, L(w) = sum_{I heavy} (w_I - w_p) (x)
   * grad phi_I with w_p = sum_J phi_J w_J over all nodes, is linear in
   * the nodal velocities w. Its adjoint, the force whose work
   * sum_J f_J . w_J is -V sigma : L(w) for every w, gives node J the
   * stress term V sigma with the gradient
   *   grad phi_J [J heavy] + phi_J G,   G = sum_{K light} grad phi_K:
   * the light nodes' gradients spread over the stencil by the weights.
   * These still sum to zero (the gradients of all nodes do, and the
   * weights sum to one), so momentum is kept; and a light node's force
   * now scales with phi_J, as its mass does, so its force-updated
   * velocity stays bounded. The basis' gradients with the guard on the
   * strain rate's side only gave parting bodies energy: two disks +5 %
   * (MUSL) and +9 % (USF), before the guard was kept to USL.
   */
  template <int dim>
  template <typename Stencil, std::size_t n_nodes>
  inline bool
  TimeIntegrator<dim>::light_node_gradients(
    const Stencil                       &s,
    const double                        *u,
    const unsigned int                   stride,
    const double                         light_mass,
    std::array<Tensor<1, dim>, n_nodes> &spread) const
  {
    std::array<bool, n_nodes> light;
    Tensor<1, dim>            light_gradients;
    bool                      any_light = false;
    for (unsigned int v = 0; v < n_nodes; ++v)
      {
        light[v] = u[stride * s.nodes[v] + node_mass] <= light_mass;
        if (light[v])
          {
            light_gradients += s.gradients[v];
            any_light = true;
          }
      }
    if (!any_light)
      return false;
    for (unsigned int v = 0; v < n_nodes; ++v)
      spread[v] = s.weights[v] * light_gradients +
                  (light[v] ? Tensor<1, dim>() : s.gradients[v]);
    return true;
  }


  /**
   * A node that only the edge of a point's support reaches has a tiny
   * mass phi m_p but the full force V sigma grad phi, so the force update
   * gives it an increment dt f / m that grows as 1 / phi. In v_p it counts
   * with phi (a bounded share: momentum), but in APIC's C_p with the
   * affine weight a_I, which for the linear basis is grad phi and does not
   * vanish with phi. The next transfer then spreads m_p C_p (x_I - x_p)
   * from wherever the point has moved: the linear basis with APIC gained
   * energy until the energy guard stopped it, or not, depending on where
   * the output times cut the steps (two disks; benchmarks/contact).
   * At a node lighter than the small-mass threshold the point's own
   * increment @p dv_point = sum_I phi_I dv_I (the gather's FLIP
   * increment) stands in for the node's: C_p still
   * reproduces any affine transferred field and any uniform acceleration,
   * and v_p is unchanged, so momentum is too. A node without mass has no
   * velocity at all, yet it is in the stencil of a point that lies on its
   * cell's face (weight 0, gradient full): there the point's own velocity
   * @p v_point stands in (without this, the points on a translating disk's
   * edge got |C_p| = 2 |v| / h whenever a step ended with them on a node
   * line). Smooth bases do not need it (a_I vanishes with phi there;
   * measured: the rule would only take 0.4-1.3 % of the two disks'
   * energy).
   */
  template <int dim>
  template <typename Stencil, std::size_t n_nodes>
  inline void
  TimeIntegrator<dim>::discount_light_node_increments(
    const Stencil                             &s,
    const double                              *u,
    const unsigned int                         stride,
    const std::array<Tensor<1, dim>, n_nodes> &affine,
    const Tensor<1, dim>                      &v_point,
    const Tensor<1, dim>                      &dv_point,
    Tensor<2, dim>                            &C) const
  {
    for (unsigned int v = 0; v < n_nodes; ++v)
      {
        const double *node = u + stride * s.nodes[v];
        if (!is_light(node))
          continue;
        const Tensor<1, dim> v_I = Fields::vector<dim>(node + v_new);
        C -=
          outer_product(node[node_mass] == 0
                          ? v_I - v_point
                          : v_I - Fields::vector<dim>(node + v_old) - dv_point,
                        affine[v]);
      }
  }


  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::gather_to_particles(const Basis &basis,
                                           const double dt,
                                           const bool   kinematics)
  {
    TimerOutput::Scope scope(timer, "G2P");
    const FieldLayout &l     = points.layout();
    const double      *u_all = grid_velocity.get_values();
    const double       alpha = prm.flip_fraction;
    // Newmark's gamma (USL, FLIP): see grid_velocities_after_forces.
    const bool   newmark          = kinematics && prm.newmark_gamma != 0.5;
    const double increment_factor = 1. / (prm.newmark_gamma + 0.5);
    std::array<Tensor<1, dim>, Basis::n_nodes> affine;
    const unsigned int                         fields_per_node = n_fields;
    const unsigned int *fields_of_body = field_of_body.data();
    // Compiled once for each transfer and for one or several fields, so
    // that the PIC/FLIP loop carries nothing of APIC's, nor a scene
    // without contact anything of it.
    auto gather = [&](auto apic, auto several_fields) {
      constexpr bool     multi_field = decltype(several_fields)::value;
      const unsigned int stride =
        multi_field ? fields_per_node * n_velocities : n_velocities;
      for_each_point(basis, [&](auto &p, double *q, const auto &s) {
        const double *u = u_all;
        if constexpr (multi_field)
          u +=
            n_velocities * fields_of_body[static_cast<unsigned int>(q[l.body])];
        Tensor<1, dim> v_grid, dv_grid;
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          {
            const double        *node = u + stride * s.nodes[v];
            const Tensor<1, dim> b    = Fields::vector<dim>(node + v_new);
            v_grid += s.weights[v] * b;
            // FLIP's velocity increment; APIC uses it only for the light
            // nodes of the linear basis (discount_light_node_increments).
            if constexpr (!decltype(apic)::value ||
                          !Basis::gradient_vanishes_with_weight)
              dv_grid += s.weights[v] * (b - Fields::vector<dim>(node + v_old));
          }
        if constexpr (decltype(apic)::value)
          {
            // v_p is the grid velocity at the point; C_p = B_p D_p^{-1}.
            Fields::store(v_grid, q + l.velocity);
            Tensor<2, dim> C =
              apic_velocity_gradient<dim>(basis, s, u, stride, v_new, affine);
            if constexpr (!Basis::gradient_vanishes_with_weight)
              discount_light_node_increments(
                s, u, stride, affine, v_grid, dv_grid, C);
            Fields::store(advected_affine_velocity(C, dt),
                          q + l.affine_velocity);
          }
        else if (newmark)
          {
            // The nodes hold v_old + (gamma + 1/2) dt a: the velocity
            // update is dt a of it.
            const Tensor<1, dim> v_p = Fields::vector<dim>(q + l.velocity);
            const Tensor<1, dim> dv  = increment_factor * dv_grid;
            Fields::store(Tensor<1, dim>(alpha * (v_p + dv) +
                                         (1. - alpha) *
                                           (v_grid - dv_grid + dv)),
                          q + l.velocity);
          }
        else
          {
            const Tensor<1, dim> v_p = Fields::vector<dim>(q + l.velocity);
            Fields::store(Tensor<1, dim>(alpha * (v_p + dv_grid) +
                                         (1. - alpha) * v_grid),
                          q + l.velocity);
          }
        p->set_location(p->get_location() + dt * v_grid);
        if (kinematics)
          apply_velocity_gradient(
            p,
            q,
            velocity_gradient(
              s, u, stride, v_new, strain_rate_light_mass<Basis>()),
            dt);
      });
    };
    const bool apic = prm.transfer == Transfer::apic;
    if (n_fields > 1)
      {
        if (apic)
          gather(std::true_type(), std::true_type());
        else
          gather(std::false_type(), std::true_type());
      }
    else if (apic)
      gather(std::true_type(), std::false_type());
    else
      gather(std::false_type(), std::false_type());
  }


  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::update_kinematics(const Basis       &basis,
                                         const double       dt,
                                         const unsigned int slot)
  {
    TimerOutput::Scope scope(timer, "G2P");
    for_each_point(basis, [&](auto &p, double *q, const auto &s) {
      apply_velocity_gradient(p,
                              q,
                              velocity_gradient(s,
                                                grid_velocity.get_values() +
                                                  n_velocities * field_of(q),
                                                n_fields * n_velocities,
                                                slot,
                                                0.),
                              dt);
    });
  }


  template <int dim>
  template <typename Iterator>
  inline void
  TimeIntegrator<dim>::apply_velocity_gradient(const Iterator       &p,
                                               double               *q,
                                               const Tensor<2, dim> &L,
                                               const double          dt)
  {
    const FieldLayout &l = points.layout();
    Fields::store(L, q + l.velocity_gradient);
    Tensor<2, dim> dF = dt * L;
    for (unsigned int d = 0; d < dim; ++d)
      dF[d][d] += 1.;
    const double det_dF = determinant(dF);
    if (!(det_dF > 0) && failure.empty())
      {
        std::ostringstream msg;
        msg << "step " << n_steps << ", t = " << t << ": material point "
            << p->get_id() << " of body " << q[l.body] << " at ("
            << p->get_location() << ") would invert: det(I + dt L) = " << det_dF
            << " <= 0 (J = det F would be "
            << (l.deformation_gradient != FieldLayout::absent
                  ? determinant(
                      Fields::tensor<dim>(q + l.deformation_gradient)) *
                      det_dF
                  : det_dF)
            << "); the run is unstable (try a smaller CFL number, MUSL, or "
               "damping)";
        failure = msg.str();
      }
    q[l.volume] *= det_dF;
    if (l.deformation_gradient != FieldLayout::absent)
      Fields::store(Tensor<2, dim>(
                      dF * Fields::tensor<dim>(q + l.deformation_gradient)),
                    q + l.deformation_gradient);
  }


  template <int dim>
  void
  TimeIntegrator<dim>::update_stresses(const double dt)
  {
    if (prm.f_bar)
      average_volume_change_over_cells(dt);
    if (prm.energy_residual)
      add_stress_power(dt, true);
    {
      TimerOutput::Scope scope(timer, "stress");
      for (unsigned int b = 0; b < points.bodies().size(); ++b)
        if (!points.bodies()[b].rigid_velocity) // a rigid body has no stress
          points.bodies()[b].material->update_stresses(
            points.handler(), points.layout(), b, dt, comm);
    }
    if (prm.energy_residual)
      add_stress_power(dt, false);
    if (points.layout().macro_step != FieldLayout::absent)
      accumulate_macro_increment(dt);
  }


  /**
   * With the linear basis a cell's nodes can follow far fewer volume
   * changes than it holds points, so a nearly incompressible body locks:
   * each point's J is a constraint. F-bar (de Souza Neto et al. 1996; for
   * MPM Coombs et al. 2018) gives every point the J of its cell,
   *
   *   J_cell = sum V_p / sum V0_p   over the cell's points of one body,
   *
   * and keeps its isochoric deformation: the step's increment becomes
   * dF_bar = (J_cell / J_p)^(1/dim) dF. Averaging the total J, not the
   * step's increment, matters: with increments alone, points that arrive
   * from other cells carry their own J, and at K / mu = 500 those
   * differences are the pressure noise F-bar is meant to remove (the
   * settling block of tests/block_settling.prm at nu = 0.499: stress error
   * 0.129 by increments, 0.103 by the total J; 1.37 without F-bar). Bodies that
   * share a cell are not mixed, the volume is conserved per cell, and V, F and
   * L stay consistent (V = V0 det F, I + dt L = dF_bar). In 2D (plane strain)
   * the exponent 1/2 acts in the plane, where all the volume change happens.
   */
  template <int dim>
  void
  TimeIntegrator<dim>::average_volume_change_over_cells(const double dt)
  {
    TimerOutput::Scope               scope(timer, "F-bar");
    const FieldLayout               &l         = points.layout();
    Particles::ParticleHandler<dim> &particles = points.handler();
    const unsigned int               n_bodies  = density_of_body.size();
    const unsigned int cells_of_tile = Utilities::pow(grid.tile_size(), dim);
    // Per cell of the tile and body: the current and the reference volume
    // of its points, and per cell the number of points.
    std::vector<std::array<double, 2>> volumes(cells_of_tile * n_bodies);
    std::vector<unsigned int>          n_in_cell(cells_of_tile);
    // The tile's points of deformable bodies with their (cell, body) bin,
    // visited twice: deal.II's particle iterator is walked once.
    std::vector<std::pair<double *, unsigned int>> deformable;
    const auto                                     body = [&](const double *q) {
      return static_cast<unsigned int>(q[l.body]);
    };
    const auto reference_volume = [&](const double *q) {
      return q[l.mass] / density_of_body[body(q)];
    };
    for (const unsigned int index : grid.locally_owned_tiles())
      {
        const auto        &tile = grid.tile(index);
        const unsigned int n    = particles.n_particles_in_cell(tile);
        if (n < 2)
          continue;
        std::fill(volumes.begin(), volumes.end(), std::array<double, 2>{});
        std::fill(n_in_cell.begin(), n_in_cell.end(), 0u);
        deformable.clear();
        const auto first = grid.first_cell_of_tile(index);
        auto       p     = particles.particles_in_cell(tile).begin();
        for (unsigned int i = 0; i < n; ++i, ++p)
          {
            typename BackgroundGrid<dim>::CellCoordinates cell;
            Point<dim>                                    xi;
            grid.cell_in_tile(first, p->get_reference_location(), cell, xi);
            unsigned int c = 0;
            for (int d = dim - 1; d >= 0; --d)
              c = c * grid.tile_size() + (cell[d] - first[d]);
            ++n_in_cell[c];
            double *const q = p->get_properties().data();
            if (density_of_body[body(q)] > 0) // not a rigid body
              {
                const unsigned int bin = c * n_bodies + body(q);
                volumes[bin][0] += q[l.volume];
                volumes[bin][1] += reference_volume(q);
                deformable.emplace_back(q, bin);
              }
          }
        for (const auto &[q, bin] : deformable)
          {
            // A point alone in its cell keeps its own J.
            if (n_in_cell[bin / n_bodies] < 2)
              continue;
            const double J_cell = volumes[bin][0] / volumes[bin][1];
            const double V0     = reference_volume(q);
            const double ratio  = J_cell * V0 / q[l.volume];
            const double scale  = dim == 1   ? ratio
                                  : dim == 2 ? std::sqrt(ratio)
                                             : std::cbrt(ratio);
            // I + dt L_bar = scale (I + dt L).
            Tensor<2, dim> L =
              scale * Fields::tensor<dim>(q + l.velocity_gradient);
            for (unsigned int d = 0; d < dim; ++d)
              L[d][d] += (scale - 1.) / dt;
            Fields::store(L, q + l.velocity_gradient);
            q[l.volume] = J_cell * V0;
            if (l.deformation_gradient != FieldLayout::absent)
              Fields::store(Tensor<2, dim>(
                              scale *
                              Fields::tensor<dim>(q + l.deformation_gradient)),
                            q + l.deformation_gradient);
          }
      }
  }


  /**
   * The work the points' stresses absorbed over the step, V sigma : L dt
   * with the strain rate their update used, by the trapezoidal rule over
   * the update: half at the stress before (and the volume the step started
   * from), half after. Elastic, its sum is the change of strain energy to
   * the order of the rule; plastic, it also holds what plasticity
   * dissipated (see EnergyGuard: the energy residual).
   */
  template <int dim>
  void
  TimeIntegrator<dim>::add_stress_power(const double dt, const bool before)
  {
    TimerOutput::Scope scope(timer, "energy residual");
    const FieldLayout &l     = points.layout();
    double             power = 0;
    for (const auto &p : points.handler())
      {
        const double        *q = p.get_properties().data();
        const Tensor<2, dim> L = Fields::tensor<dim>(q + l.velocity_gradient);
        double               V = q[l.volume];
        if (before)
          {
            // The volume the step started from: V = V_n det(I + dt L).
            Tensor<2, dim> dF = dt * L;
            for (unsigned int d = 0; d < dim; ++d)
              dF[d][d] += 1.;
            V /= determinant(dF);
          }
        power += V * scalar_product(Fields::symmetric<dim>(q + l.stress), L);
      }
    absorbed_work += 0.5 * dt * power;
  }


  template <int dim>
  double
  TimeIntegrator<dim>::stress_work() const
  {
    return Utilities::MPI::sum(absorbed_work, comm);
  }


  template <int dim>
  std::array<double, 2>
  TimeIntegrator<dim>::external_work() const
  {
    return {{Utilities::MPI::sum(work, comm),
             Utilities::MPI::sum(absolute_work, comm)}};
  }


  template <int dim>
  void
  TimeIntegrator<dim>::save_state(RunState &state) const
  {
    // Sums over the ranks: a restart on another number of ranks keeps them
    // on its first.
    const auto [w, a]              = external_work();
    state.values["external_work"]  = w;
    state.values["absolute_work"]  = a;
    state.values["time"]           = t;
    state.values["last_dt"]        = last_dt;
    state.values["steps"]          = n_steps;
    state.values["removed_points"] = n_removed;
    state.values["stress_work"]    = stress_work();
    if (prm.macro_time_step > 0)
      {
        state.values["macro_steps"]          = n_macro_steps;
        state.values["macro_mismatch"]       = macro_mismatch;
        state.values["macro_kinetic_energy"] = macro_kinetic_energy;
      }
  }


  template <int dim>
  void
  TimeIntegrator<dim>::restore_state(const RunState &state)
  {
    t                = state.get("time");
    last_dt          = state.get("last_dt");
    n_steps          = state.get("steps");
    n_removed        = state.get("removed_points");
    const bool first = Utilities::MPI::this_mpi_process(comm) == 0;
    work             = first ? state.get("external_work") : 0.;
    absolute_work    = first ? state.get("absolute_work") : 0.;
    if (prm.energy_residual)
      absorbed_work = first ? state.get("stress_work") : 0.;
    if (prm.macro_time_step > 0)
      {
        n_macro_steps        = state.get("macro_steps");
        macro_mismatch       = state.get("macro_mismatch");
        macro_kinetic_energy = state.get("macro_kinetic_energy");
      }
  }


  template class TimeIntegrator<1>;
  template class TimeIntegrator<2>;
  template class TimeIntegrator<3>;
  template FieldRequests
  point_fields_needed<1>(const IntegratorParameters<1> &,
                         const std::vector<BodyParameters<1>> &,
                         const std::vector<RigidWallParameters<1>> &,
                         const bool);
  template std::vector<unsigned int>
  wall_slip_slots<1>(const std::vector<RigidWallParameters<1>> &);
  template FieldRequests
  point_fields_needed<2>(const IntegratorParameters<2> &,
                         const std::vector<BodyParameters<2>> &,
                         const std::vector<RigidWallParameters<2>> &,
                         const bool);
  template std::vector<unsigned int>
  wall_slip_slots<2>(const std::vector<RigidWallParameters<2>> &);
  template FieldRequests
  point_fields_needed<3>(const IntegratorParameters<3> &,
                         const std::vector<BodyParameters<3>> &,
                         const std::vector<RigidWallParameters<3>> &,
                         const bool);
  template std::vector<unsigned int>
  wall_slip_slots<3>(const std::vector<RigidWallParameters<3>> &);
} // namespace mpm
