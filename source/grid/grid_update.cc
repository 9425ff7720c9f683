// The grid stage of the step: the nodal velocities from the scattered
// momenta and forces, and the constraints on them (contact between bodies'
// fields, the grid's faces, the velocity region).
#include <mpm/grid/grid_update.h>

#include <algorithm>
#include <vector>

namespace mpm
{
  namespace
  {
    /**
     * One component of the force update's velocity before the
     * constraints: v_old + dt / m (f + f_d), with Cundall's local damping
     * f_d = -alpha |f| sign(v_old) (none at rest, where sign(v) = 0),
     * times @p damping_factor = 1 / (1 + c dt), the global damping taken
     * implicitly (stable for any c).
     */
    inline double
    damped_velocity(const double v_old,
                    const double dt_m,
                    const double f,
                    const double alpha,
                    const double damping_factor)
    {
      // Without local damping (the common case) f_d is skipped, not
      // computed as zero: this runs for every node and field each step.
      const double f_d =
        alpha > 0 ? -alpha * std::abs(f) * ((v_old > 0) - (v_old < 0)) : 0.;
      return (v_old + dt_m * (f + f_d)) * damping_factor;
    }
  } // namespace


  template <int dim>
  GridUpdate<dim>::GridUpdate(const StepParts<dim> &parts,
                              ExternalLoads<dim>   &loads,
                              const double          light_mass)
    : prm(parts.parameters)
    , grid(parts.grid)
    , nodes(parts.nodes)
    , faces(parts.grid, parts.points.bodies())
    , velocity_region(parts.velocity_region)
    , contact(parts.contact)
    , virtual_fluid(parts.virtual_fluid)
    , loads(loads)
    , work(parts.work)
    , account_grid_work(parts.parameters.energy_residual)
    , light_mass(light_mass)
    , context(parts.context)
  {
  }


  template <int dim>
  void
  GridUpdate<dim>::reinit()
  {
    faces.reinit();
    if (contact && prm.scheme == UpdateScheme::MUSL)
      pressed_nodes.assign(grid.n_locally_owned_nodes(), 0);
  }


  template <int dim>
  void
  GridUpdate<dim>::velocities_from_momentum(const unsigned int slot,
                                            const bool         for_strain_rate)
  {
    TimerOutput::Scope scope(context.timer, "grid update");
    const double      *g       = nodes.sums.get_values();
    double            *u       = nodes.velocities.get_values();
    const double       inertia = prm.mass_scaling;
    // The fields of a node follow each other: one loop over all entries.
    const unsigned int n_slots = nodes.n_owned_slots();
    for (unsigned int i = 0; i < n_slots; ++i)
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
    apply_constraints(slot, 0., for_strain_rate);
    nodes.velocities.update_ghost_values();
  }


  template <int dim>
  void
  GridUpdate<dim>::velocities_after_forces(const double dt)
  {
    TimerOutput::Scope scope(context.timer, "grid update");
    const double      *g = nodes.sums.get_values();
    double            *u = nodes.velocities.get_values();
    // Implicit in the damping term: unconditionally stable for any c.
    const double damping_factor = 1. / (1. + prm.damping * dt);
    const double alpha          = prm.local_damping;
    // Newmark (see GatherState): v_new is the velocity
    // that moves the points, v_old + (gamma + 1/2) dt a.
    const bool         newmark       = prm.newmark_gamma != 0.5;
    const double       motion_factor = prm.newmark_gamma + 0.5;
    const unsigned int n_slots       = nodes.n_owned_slots();
    for (unsigned int i = 0; i < n_slots; ++i)
      {
        const double *node = g + n_sums * i;
        double       *vel  = u + n_velocities * i;
        // vel[node_mass] is the scaled inertia (mass scaling).
        const double dt_m = vel[node_mass] > 0 ? dt / vel[node_mass] : 0.;
        for (unsigned int d = 0; d < dim; ++d)
          vel[v_new + d] = damped_velocity(
            vel[v_old + d], dt_m, node[force + d], alpha, damping_factor);
      }
    // A loop of its own, so that the plain step's stays as it was.
    if (newmark)
      for (unsigned int i = 0; i < n_slots; ++i)
        {
          double *vel = u + n_velocities * i;
          for (unsigned int d = 0; d < dim; ++d)
            vel[v_new + d] = vel[v_old + d] +
                             motion_factor * (vel[v_new + d] - vel[v_old + d]);
        }
    apply_constraints(v_new, dt);
    if (account_grid_work && (prm.damping > 0 || alpha > 0))
      work.damping += damping_work(dt);
    if (measure_out_of_balance)
      local_out_of_balance = out_of_balance_force(dt);
    nodes.velocities.update_ghost_values();
    if (virtual_fluid)
      {
        virtual_fluid->add_impulse(dt * nodes.fluid_force_total);
        for (unsigned int i = 0; i < n_slots; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            loads.add_work(0.5 * dt *
                           nodes.fluid_force.local_element(dim * i + d) *
                           (u[n_velocities * i + v_old + d] +
                            u[n_velocities * i + v_new + d]));
      }
  }


  /**
   * The force update set v_new = (v_old + dt (f + f_d) / m) / (1 + c dt)
   * (then Newmark's factor), f_d the local damping's -alpha |f| sign(v_old);
   * the constraints then changed v_new. Taken back from the constrained
   * v_new without the damping, m ((1 + c dt) v_new - v_old) / dt - f_d is f
   * where nothing constrains the node and the part of f the constraints
   * did not take elsewhere: zero on a fixed node and along a slip face's
   * normal (v_old, v_new and f_d vanish there), the whole force where a
   * node moves freely.
   *
   * Where a constraint changed a component, the damping force did not act
   * on the motion and is not taken out: the momentum change alone is the
   * imbalance there. A node held by a friction face can keep a velocity
   * of round-off size off the face after the transfer, and sign(v_old)
   * then made f_d 0.7 of the weight it rests under: a slope at rest on a
   * friction base read 0.16 of its weight out of balance (issue 33).
   */
  template <int dim>
  double
  GridUpdate<dim>::out_of_balance_force(const double dt) const
  {
    const double      *g              = nodes.sums.get_values();
    const double      *u              = nodes.velocities.get_values();
    const double       c_dt           = prm.damping * dt;
    const double       alpha          = prm.local_damping;
    const double       motion         = prm.newmark_gamma + 0.5;
    const unsigned int n_fields       = nodes.n_fields;
    double             sum            = 0;
    const double       damping_factor = 1. / (1. + c_dt);
    for (unsigned int n = 0; n < nodes.n_owned_slots() / n_fields; ++n)
      {
        Tensor<1, dim> node_force;
        for (unsigned int f = 0; f < n_fields; ++f)
          {
            const unsigned int i     = nodes.slot_of(n, f);
            const double      *vel   = u + n_velocities * i;
            const double      *sum_i = g + n_sums * i;
            const double dt_m = vel[node_mass] > 0 ? dt / vel[node_mass] : 0.;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double v_old_d = vel[v_old + d];
                const double v_new_d =
                  v_old_d + (vel[v_new + d] - v_old_d) / motion;
                const double f_d = -alpha * std::abs(sum_i[force + d]) *
                                   ((v_old_d > 0) - (v_old_d < 0));
                // v_new as the force update made it, before the
                // constraints.
                const double free_v_new = damped_velocity(
                  v_old_d, dt_m, sum_i[force + d], alpha, damping_factor);
                const bool constrained =
                  std::abs(v_new_d - free_v_new) >
                  1e-12 * (std::abs(free_v_new) + std::abs(v_old_d)) + 1e-300;
                node_force[d] +=
                  vel[node_mass] * ((1 + c_dt) * v_new_d - v_old_d) / dt -
                  (constrained ? 0. : f_d);
              }
          }
        sum += node_force.norm();
      }
    return sum;
  }


  /**
   * The damping's impulse on a node, m (v_damped - v_old - dt f / m), works
   * at the mean of the node's velocities at the step's start and end (as
   * the faces' impulses do, see GridFaces::apply()): after the
   * constraints, so that a node a face holds at rest takes no damping
   * work either. Exact for Newmark's gamma = 1/2, where v_new is the
   * step's end velocity.
   */
  template <int dim>
  double
  GridUpdate<dim>::damping_work(const double dt) const
  {
    const double *g              = nodes.sums.get_values();
    const double *u              = nodes.velocities.get_values();
    const double  damping_factor = 1. / (1. + prm.damping * dt);
    double        sum            = 0;
    for (unsigned int i = 0; i < nodes.n_owned_slots(); ++i)
      {
        const double *node = g + n_sums * i;
        const double *vel  = u + n_velocities * i;
        const double  m    = vel[node_mass];
        if (!(m > 0))
          continue;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double v_0 = vel[v_old + d], f = node[force + d];
            const double damped = damped_velocity(
              v_0, dt / m, f, prm.local_damping, damping_factor);
            sum +=
              impulse_work(m, v_0 + dt / m * f, damped, v_0, vel[v_new + d]);
          }
      }
    return sum;
  }


  template <int dim>
  void
  GridUpdate<dim>::apply_constraints(const unsigned int slot,
                                     const double       dt,
                                     const bool         for_strain_rate)
  {
    // The work of prescribed motion (rigid bodies, the velocity region)
    // counts at both velocity updates, where the first sets a body at
    // rest moving (see VelocityRegion::enforce()), but not at MUSL's
    // strain-rate velocities, whose corrections move no point: counted
    // there, a rigid footing pushed with MUSL and pure FLIP read an energy
    // residual of -18 % of the work at t = 2.6 s, -10 % without.
    double prescribed_work = 0;
    if (contact)
      prescribed_work += apply_contact(slot, dt, for_strain_rate);
    // Grid faces and the velocity region act on every field alike.
    double *u = nodes.velocities.get_values();
    // Only the force update's corrections are the faces' work: after a
    // transfer to the grid, FLIP's points keep what the faces take from
    // the nodes (their increment is v_new - v_old), and what the other
    // transfers lose there is the transfer's (the energy residual).
    faces.apply(u,
                nodes.n_fields,
                slot,
                dt,
                account_grid_work && dt > 0 ? &work : nullptr,
                for_strain_rate);
    if (velocity_region.enabled())
      for (unsigned int f = 0; f < nodes.n_fields; ++f)
        prescribed_work += velocity_region.enforce(
          u + n_velocities * f, nodes.n_fields * n_velocities, slot, dt);
    if (!for_strain_rate)
      loads.add_work(prescribed_work);
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
   * starts from (usf_strain_rate_velocities): now 1.018 and 0.610
   * (one field: 1.027, 0.630). Against a rigid body the same holds: a
   * lone point dropped with MUSL (USF) onto a rigid floor ended with 0.89
   * (1.18) of the energy put in more than it started with, its stress
   * never relaxing while the floor threw it up
   * (tests/lone_point_bounce_rigid.prm; a friction face did the same, see
   * GridFaces::apply()). The state is made in the step it is used,
   * so nothing carries over from one step to the next, which a
   * repartition (load balance, between steps) would lose.
   */
  template <int dim>
  double
  GridUpdate<dim>::apply_contact(const unsigned int slot,
                                 const double       dt,
                                 const bool         for_strain_rate)
  {
    double *u = nodes.velocities.get_values();
    // Each call after a transfer again: the projection does not change
    // what it has projected.
    faces.keep_contact_normals_in_faces(nodes.contact_data.get_values(),
                                        nodes.n_fields,
                                        MultiFieldContact<dim>::data_per_field);
    const double *data = nodes.contact_data.get_values();
    contact->set_time(context.t);
    std::vector<Tensor<1, dim>> impulse(contact->rigid_bodies().size());
    // Only MUSL with contact keeps pressed_nodes.
    const bool          record  = dt > 0 && !pressed_nodes.empty();
    const bool          hold    = for_strain_rate && !pressed_nodes.empty();
    const bool          account = dt > 0 && account_grid_work;
    const unsigned int  width   = nodes.n_fields * n_velocities;
    std::vector<double> before(account ? width : 0);
    double              deformable_work = 0;
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        double *node = u + n_velocities * nodes.slot_of(i, 0);
        if (account)
          std::copy(node, node + width, before.begin());
        const bool pressed =
          contact->correct_node(node,
                                n_velocities,
                                slot,
                                data + MultiFieldContact<dim>::data_per_field *
                                         nodes.slot_of(i, 0),
                                light_mass,
                                hold && pressed_nodes[i],
                                impulse);
        if (record)
          pressed_nodes[i] = pressed;
        if (account)
          deformable_work += contact_work_on_deformable_fields(before, node);
      }
    if (dt > 0)
      contact->add_rigid_impulses(impulse);
    // The rigid body's reaction works at its velocity (an upper bound:
    // friction's share is dissipated; apply_constraints() counts it).
    double rigid_work = 0;
    for (unsigned int r = 0; r < impulse.size(); ++r)
      rigid_work += impulse[r] * contact->rigid_velocity_of(r);
    // What the contact with rigid bodies took from the deformable fields
    // beyond what the rigid bodies did on them (external work) is its own:
    // the inelastic closing and the friction against them.
    if (account)
      work.contact += deformable_work - rigid_work;
    return rigid_work;
  }


  /**
   * The work of the contact's impulses m (v_after - v_before) on a node's
   * deformable fields at the force update where a rigid body takes part,
   * at the mean of each field's velocities at the step's start and end
   * (as the faces', see GridFaces::apply()). @p before: the node's fields
   * as they were.
   */
  template <int dim>
  double
  GridUpdate<dim>::contact_work_on_deformable_fields(
    const std::vector<double> &before,
    const double              *node) const
  {
    // Between deformable bodies the rule also holds light fields to the
    // others (see MultiFieldContact::correct_node), whose velocities, of
    // order dt f / m, are not the material's: there the nodes' work is not
    // the contact's (two disks: +3 % of their energy while they part), and
    // it stays in the energy residual.
    bool rigid_here = false;
    for (unsigned int f = 0; f < nodes.n_fields; ++f)
      rigid_here = rigid_here || (contact->is_rigid_field(f) &&
                                  node[n_velocities * f + node_mass] > 0);
    if (!rigid_here)
      return 0;
    double sum = 0;
    for (unsigned int f = 0; f < nodes.n_fields; ++f)
      {
        const double *field = node + n_velocities * f;
        if (contact->is_rigid_field(f) || !(field[node_mass] > 0))
          continue;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double v_after = field[v_new + d];
            sum += impulse_work(field[node_mass],
                                before[n_velocities * f + v_new + d],
                                v_after,
                                field[v_old + d],
                                v_after);
          }
      }
    return sum;
  }


  /**
   * USF's strain rate comes from the velocities transferred at the step's
   * start, before any force update, and a unilateral constraint decides
   * there on the transferred velocity alone. What the constraint will
   * hold is what the stress pushes into it at the force update: try one,
   * with the forces of the stress the step starts from, and hold the
   * strain rate's velocities where it presses (the same rules as MUSL's,
   * apply_contact() and GridFaces::apply()). Only the sign of the
   * approach matters, so damping and Newmark's factor are left out, and
   * no work is accounted.
   */
  template <int dim>
  void
  GridUpdate<dim>::usf_strain_rate_velocities(const double dt)
  {
    TimerOutput::Scope scope(context.timer, "grid update");
    const double      *g        = nodes.sums.get_values();
    double            *u        = nodes.velocities.get_values();
    const unsigned int n_slots  = nodes.n_owned_slots();
    const bool unilateral_faces = faces.has_unilateral_face(grid.parameters());
    // The trial force update, into v_new.
    for (unsigned int i = 0; i < n_slots; ++i)
      {
        double      *vel  = u + n_velocities * i;
        const double dt_m = vel[node_mass] > 0 ? dt / vel[node_mass] : 0.;
        for (unsigned int d = 0; d < dim; ++d)
          vel[v_new + d] = vel[v_old + d] + dt_m * g[n_sums * i + force + d];
      }
    // Where it presses, in apply_constraints()'s order: contact, faces.
    const std::vector<unsigned int> pressed =
      contact ? nodes_pressed_in_contact() : std::vector<unsigned int>();
    if (unilateral_faces)
      faces.apply(u, nodes.n_fields, v_new, dt);
    // The transferred velocities, held there.
    for (unsigned int i = 0; i < n_slots; ++i)
      for (unsigned int d = 0; d < dim; ++d)
        u[n_velocities * i + v_new + d] = u[n_velocities * i + v_old + d];
    if (contact)
      {
        const double               *data = nodes.contact_data.get_values();
        std::vector<Tensor<1, dim>> impulse(contact->rigid_bodies().size());
        for (const unsigned int i : pressed)
          contact->correct_node(u + n_velocities * nodes.slot_of(i, 0),
                                n_velocities,
                                v_new,
                                data + MultiFieldContact<dim>::data_per_field *
                                         nodes.slot_of(i, 0),
                                light_mass,
                                true,
                                impulse);
      }
    if (unilateral_faces)
      faces.apply(u, nodes.n_fields, v_new, 0., nullptr, true);
    nodes.velocities.update_ghost_values();
  }


  template <int dim>
  std::vector<unsigned int>
  GridUpdate<dim>::nodes_pressed_in_contact() const
  {
    const double *data = nodes.contact_data.get_values();
    const double *u    = nodes.velocities.get_values();
    contact->set_time(context.t);
    // A node's fields, to correct without changing them.
    std::vector<double>         trial(nodes.n_fields * n_velocities);
    std::vector<Tensor<1, dim>> impulse(contact->rigid_bodies().size());
    std::vector<unsigned int>   pressed;
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        const double *node = u + n_velocities * nodes.slot_of(i, 0);
        std::copy(node, node + nodes.n_fields * n_velocities, trial.begin());
        if (contact->correct_node(trial.data(),
                                  n_velocities,
                                  v_new,
                                  data +
                                    MultiFieldContact<dim>::data_per_field *
                                      nodes.slot_of(i, 0),
                                  light_mass,
                                  false,
                                  impulse))
          pressed.push_back(i);
      }
    return pressed;
  }


  template class GridUpdate<1>;
  template class GridUpdate<2>;
  template class GridUpdate<3>;
} // namespace mpm
