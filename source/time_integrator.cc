#include <mpm/basis.h>
#include <mpm/parameters.h>
#include <mpm/time_integrator.h>
#include <mpm/transfer/deformation_increment.h>
#include <mpm/transfer/f_bar.h>
#include <mpm/transfer/strain_rate.h>

#include <algorithm>
#include <sstream>

namespace mpm
{
  namespace
  {
    /// The contact if it acts (a body has a velocity field of its own),
    /// else null.
    template <int dim>
    MultiFieldContact<dim> *
    acting(MultiFieldContact<dim> *contact)
    {
      return contact != nullptr && contact->n_fields() > 1 ? contact : nullptr;
    }

    /// The fluid if it acts (is enabled), else null.
    template <int dim>
    VirtualFluid<dim> *
    acting(VirtualFluid<dim> *fluid)
    {
      return fluid != nullptr && fluid->enabled() ? fluid : nullptr;
    }

    /// The nodal state for the points' bodies: a velocity field for each
    /// of @p contact's fields (one shared field without it), with the
    /// contact's data and @p fluid's forces if they act.
    template <int dim>
    NodalState<dim>
    nodal_state_for(const MaterialPoints<dim>    &points,
                    const MultiFieldContact<dim> *contact,
                    const VirtualFluid<dim>      *fluid,
                    const double                  mass_scaling)
    {
      std::vector<unsigned int> field_of_body(points.bodies().size(), 0);
      if (contact)
        for (unsigned int b = 0; b < field_of_body.size(); ++b)
          field_of_body[b] = contact->field_of_body(b);
      return NodalState<dim>(contact ? contact->n_fields() : 1,
                             field_of_body,
                             points.layout().body,
                             mass_scaling,
                             contact ? MultiFieldContact<dim>::data_per_field
                                     : 0,
                             fluid != nullptr);
    }
  } // namespace


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
    , rigid_walls(rigid_walls)
    , context(timer, comm)
    , nodes(nodal_state_for(points,
                            acting(contact),
                            acting(virtual_fluid),
                            prm.mass_scaling))
    , loop(grid, points, prm.basis)
    , parts{prm,
            grid,
            points,
            velocity_region,
            this->rigid_walls,
            acting(virtual_fluid),
            acting(contact),
            context,
            nodes,
            loop,
            work}
    , stresses(parts)
    , usf_trial_forces(
        prm.scheme == UpdateScheme::USF &&
        (parts.contact != nullptr ||
         GridFaces<dim>::has_unilateral_face(parts.grid.parameters())))
    // Nodal masses are stored with the mass scaling (see
    // GridUpdate::velocities_from_momentum), and so is the guard's
    // threshold.
    , min_nodal_mass(prm.small_mass_fraction * prm.mass_scaling *
                     points.min_particle_mass())
    , limits(parts)
    , loads(parts, limits.wave_modulus_of_body())
    , to_grid(parts, loads)
    , grid_update(parts, loads, min_nodal_mass)
    , to_points(parts, min_nodal_mass)
    , substepper(*this)
  {
    setup_nodal_data();
    Assert(prm.basis != BasisType::cpgimp ||
             parts.points.layout().deformation_gradient != FieldLayout::absent,
           ExcMessage("cpGIMP needs the deformation gradient"));
    Assert(!with_transfer(prm.transfer,
                          [](auto c) { return c.stores_affine_velocity; }) ||
             parts.points.layout().affine_velocity != FieldLayout::absent,
           ExcMessage("APIC needs the affine velocity field"));

    limits.check_requested_steps();
  }


  template <int dim>
  void
  TimeIntegrator<dim>::setup_nodal_data()
  {
    nodes.reinit(parts.grid);
    to_grid.reinit();
    grid_update.reinit();
  }


  template <int dim>
  void
  TimeIntegrator<dim>::step(const double max_dt)
  {
    if (prm.macro_time_step > 0)
      substepper.macro_step(std::min(prm.macro_time_step, max_dt));
    else
      explicit_step(std::min(limits.explicit_time_step(), max_dt));
  }


  template <int dim>
  void
  TimeIntegrator<dim>::explicit_step(const double dt)
  {
    loop.with_scene_basis([&](const auto &basis) { advance(basis, dt); });
    context.raise_if_failed();
    loads.close_step(dt);
    // After the step's loads did their work at the velocities they saw.
    loads.keep_points_in_front_of_rigid_walls(context.t + dt);

    {
      TimerOutput::Scope scope(context.timer, "relocate");
      n_removed += parts.points.relocate(prm.out_of_grid);
    }
    context.t += dt;
    last_dt = dt;
    ++context.n_steps;
  }


  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::advance(const Basis &basis, const double dt)
  {
    if (parts.points.layout().point_load != FieldLayout::absent)
      loads.make_point_loads(dt);
    // See USF with cpGIMP.
    const double work_before = loads.step_work_so_far();
    switch (prm.scheme)
      {
        case UpdateScheme::USL:
          scatter_masses_then_forces(basis);
          grid_update.velocities_after_forces(dt);
          to_points.gather(basis, dt, true);
          stresses.update(dt);
          break;
        case UpdateScheme::USF:
          // With deformable bodies in contact or friction faces, the forces
          // of the stress the step starts from tell where the bodies press
          // on each other or on a face (see
          // GridUpdate::usf_strain_rate_velocities); the updated stress's
          // replace them below.
          to_grid.scatter(basis, true, usf_trial_forces);
          grid_update.velocities_from_momentum(Layout::v_old);
          if (usf_trial_forces)
            grid_update.usf_strain_rate_velocities(dt);
          to_points.update_kinematics(
            basis, dt, usf_trial_forces ? Layout::v_new : Layout::v_old);
          stresses.update(dt);
          if (prm.basis == BasisType::cpgimp)
            {
              // The domains follow F, which the kinematics just changed:
              // mass, momentum and force must come from the same stencils,
              // or a node that the grown domain reaches gets a force and
              // (almost) no mass (v_notch: a point thrown out of the grid).
              // The first grid velocities only gave the strain rate, and
              // their constraints do no work.
              loads.set_step_work(work_before);
              to_grid.scatter(basis, true, true);
              grid_update.velocities_from_momentum(Layout::v_old);
            }
          else
            to_grid.scatter(basis, false, true);
          grid_update.velocities_after_forces(dt);
          to_points.gather(basis, dt, false);
          break;
        case UpdateScheme::MUSL:
          scatter_masses_then_forces(basis);
          grid_update.velocities_after_forces(dt);
          to_points.gather(basis, dt, false);
          to_grid.scatter(basis, true, false);
          grid_update.velocities_from_momentum(Layout::v_new, true);
          to_points.update_kinematics(basis, dt, Layout::v_new);
          stresses.update(dt);
          break;
      }
  }


  /**
   * USL takes its strain rate from the force-updated velocities, and
   * leaves the light nodes out of it (velocity_gradient). The internal
   * force must then leave them out the same way, or the force's work is
   * no longer the stress power and parting bodies gain energy
   * (ParticleToGrid::scatter): the masses come first, then the forces with
   * the light nodes known. MUSL and USF take the strain rate from
   * transferred velocities and need no guard: one pass.
   */
  template <int dim>
  template <typename Basis>
  void
  TimeIntegrator<dim>::scatter_masses_then_forces(const Basis &basis)
  {
    const double light_mass =
      strain_rate_light_mass<Basis>(prm.scheme, min_nodal_mass);
    if (light_mass > 0)
      {
        to_grid.scatter(basis, true, false);
        grid_update.velocities_from_momentum(Layout::v_old);
        to_grid.scatter(basis, false, true, light_mass);
      }
    else
      {
        to_grid.scatter(basis, true, true);
        grid_update.velocities_from_momentum(Layout::v_old);
      }
  }


  template <int dim>
  std::array<double, 2>
  TimeIntegrator<dim>::internal_work_and_stress_power(
    const std::function<Tensor<1, dim>(const std::array<unsigned int, dim> &)>
                &w,
    const double f_bar_step)
  {
    double work = 0, power = 0;
    loop.with_scene_basis([&](const auto &basis) {
      using Basis = std::decay_t<decltype(basis)>;
      scatter_masses_then_forces(basis);
      double       *u = nodes.velocities.get_values();
      const double *g = nodes.sums.get_values();
      for (unsigned int i = 0; i < parts.grid.n_locally_owned_nodes(); ++i)
        {
          const Tensor<1, dim> w_i = w(parts.grid.owned_node_coordinates(i));
          for (unsigned int f = 0; f < nodes.n_fields; ++f)
            for (unsigned int d = 0; d < dim; ++d)
              {
                u[Layout::n_velocities * nodes.slot_of(i, f) + Layout::v_new +
                  d] = w_i[d];
                work +=
                  g[Layout::n_sums * nodes.slot_of(i, f) + Layout::force + d] *
                  w_i[d];
              }
        }
      nodes.velocities.update_ghost_values();
      const FieldLayout &l = parts.points.layout();
      loop.for_each_point(basis, [&](auto &p, const double *q, const auto &s) {
        const Tensor<2, dim> L =
          velocity_gradient<dim>(s,
                                 nodes.velocities.get_values() +
                                   Layout::n_velocities * nodes.field_of(q),
                                 nodes.n_fields * Layout::n_velocities,
                                 Layout::v_new,
                                 strain_rate_light_mass<Basis>(prm.scheme,
                                                               min_nodal_mass));
        if (!prm.f_bar)
          power += q[l.volume] *
                   scalar_product(Fields::symmetric<dim>(q + l.stress), L);
        else
          {
            // The kinematics of a short step, for F-bar below.
            double *const x = p->get_properties().data();
            Fields::store(L, x + l.velocity_gradient);
            x[l.volume] *= determinant(deformation_increment(L, f_bar_step));
          }
      });
      if (prm.f_bar)
        {
          // The stress power with F-bar's strain rate L_bar, at the
          // volumes the step started from, which are put back.
          FBar<dim>(parts.grid, parts.points).average_volume_change(f_bar_step);
          for (auto &p : parts.points.handler())
            {
              double *const        x = p.get_properties().data();
              const Tensor<2, dim> L_bar =
                Fields::tensor<dim>(x + l.velocity_gradient);
              x[l.volume] /=
                determinant(deformation_increment(L_bar, f_bar_step));
              power +=
                x[l.volume] *
                scalar_product(Fields::symmetric<dim>(x + l.stress), L_bar);
            }
        }
    });
    return {{Utilities::MPI::sum(work, context.comm),
             Utilities::MPI::sum(power, context.comm)}};
  }


  template <int dim>
  void
  TimeIntegrator<dim>::transfer_round_trip()
  {
    loop.with_scene_basis([&](const auto &basis) {
      to_grid.scatter(basis, true, false);
      grid_update.velocities_from_momentum(Layout::v_old);
      // No force, no step: the new grid velocity is the old one.
      grid_update.velocities_from_momentum(Layout::v_new);
      to_points.gather(basis, 0., false);
    });
    context.raise_if_failed();
  }


  template <int dim>
  void
  TimeIntegrator<dim>::save_state(RunState &state) const
  {
    work.save_state(state, context.comm);
    state.values["time"]           = context.t;
    state.values["last_dt"]        = last_dt;
    state.values["steps"]          = context.n_steps;
    state.values["removed_points"] = n_removed;
    if (prm.macro_time_step > 0)
      substepper.save_state(state);
  }


  template <int dim>
  void
  TimeIntegrator<dim>::restore_state(const RunState &state)
  {
    context.t       = state.get("time");
    last_dt         = state.get("last_dt");
    context.n_steps = state.get("steps");
    n_removed       = state.get("removed_points");
    work.restore_state(state, context.comm);
    if (prm.macro_time_step > 0)
      substepper.restore_state(state);
  }


  template <int dim>
  double
  TimeIntegrator<dim>::affine_kinetic_energy() const
  {
    const FieldLayout &l      = parts.points.layout();
    double             energy = 0;
    if (l.affine_velocity != FieldLayout::absent)
      loop.with_scene_basis([&](const auto &basis) {
        loop.for_each_point(basis, [&](auto &, const double *q, const auto &s) {
          if (parts.points.bodies()[q[l.body]].rigid_velocity)
            return;
          const double *C = q + l.affine_velocity;
          double        e = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              double D = 0;
              for (unsigned int k = 0; k < std::size(s.w1[d]); ++k)
                D += s.w1[d][k] * s.offset1(d, k) * s.offset1(d, k);
              for (unsigned int i = 0; i < dim; ++i)
                e += D * C[i * dim + d] * C[i * dim + d];
            }
          energy += 0.5 * q[l.mass] * e;
        });
      });
    return Utilities::MPI::sum(energy, context.comm);
  }


  template class TimeIntegrator<1>;
  template class TimeIntegrator<2>;
  template class TimeIntegrator<3>;
} // namespace mpm
