#include <mpm/basis.h>
#include <mpm/parameters.h>
#include <mpm/time_integrator.h>

#include <sstream>

namespace mpm
{
  template <int dim>
  void
  IntegratorParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Simulation");
    prm.declare_entry("constants",
                      "",
                      Patterns::Anything(),
                      "Named constants for every expression of the scene "
                      "(initial velocity, body force, exact solution), as "
                      "'name=value, ...'; pi is always known.");
    prm.declare_entry("end time",
                      "1",
                      Patterns::Anything(),
                      "Simulated time to reach, in s, > 0.");
    prm.declare_entry("CFL number",
                      "0.5",
                      Patterns::Anything(),
                      "Time step = CFL number * h / max_p(c_p + |v_p|), "
                      "re-evaluated every step; in (0, 1].");
    prm.declare_entry("time step",
                      "0",
                      Patterns::Anything(),
                      "A fixed time step in s, or 0 to use the CFL "
                      "condition. A fixed step larger than the CFL-limited "
                      "one is an error.");
    prm.declare_entry("update scheme",
                      "USL",
                      Patterns::Selection("USL|USF|MUSL"),
                      "When stresses are updated: USL (last, from the new "
                      "grid velocity), USF (first) or MUSL (last, from "
                      "particle velocities mapped back to the grid).");
    prm.declare_entry("FLIP fraction",
                      "0.99",
                      Patterns::Anything(),
                      "PIC/FLIP blend alpha in [0, 1]: 0 is PIC (dissipative, "
                      "stable), 1 is FLIP (conserves energy, noisier).");
    prm.declare_entry("gravity",
                      "0",
                      Patterns::Anything(),
                      "Gravitational acceleration in m/s^2, one value per "
                      "dimension (e.g. '0, -9.81').");
    prm.declare_entry("damping",
                      "0",
                      Patterns::Anything(),
                      "Global mass-proportional velocity damping c in 1/s, "
                      ">= 0: grid velocities obey dv/dt = f/m - c v (as in "
                      "cl-mpm), for quasi-static problems.");
    prm.declare_entry("small mass fraction",
                      "0.25",
                      Patterns::Anything(),
                      "Nodes whose mass is below this fraction of the "
                      "smallest point mass are left out of the velocity "
                      "gradient (they keep their momentum update, so "
                      "momentum is conserved), in [0, 1).");
    prm.declare_entry("out of grid",
                      "stop",
                      Patterns::Selection("stop|remove"),
                      "What happens to a material point that leaves the "
                      "grid: stop the run with a message naming it, or "
                      "remove it and count it in the statistics.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  IntegratorParameters<dim>::parse_parameters(ParameterHandler &prm)
  {
    const std::string s = "Simulation";
    prm.enter_subsection(s);
    end_time        = Parse::bounded_double(prm, s, "end time", 0, 1e300, true);
    cfl_number      = Parse::bounded_double(prm, s, "CFL number", 0, 1, true);
    fixed_time_step = Parse::bounded_double(prm, s, "time step", 0, 1e300);
    const std::string scheme_name = prm.get("update scheme");
    scheme                        = scheme_name == "USL"   ? UpdateScheme::USL
                                    : scheme_name == "USF" ? UpdateScheme::USF
                                                           : UpdateScheme::MUSL;
    flip_fraction = Parse::bounded_double(prm, s, "FLIP fraction", 0, 1);
    gravity       = Parse::vector<dim>(prm, s, "gravity");
    damping       = Parse::bounded_double(prm, s, "damping", 0, 1e300);
    small_mass_fraction =
      Parse::bounded_double(prm, s, "small mass fraction", 0, 1, false, true);
    out_of_grid = prm.get("out of grid") == "stop" ? OutOfGridPolicy::stop
                                                   : OutOfGridPolicy::remove;
    prm.leave_subsection();
  }



  namespace
  {
    /**
     * Visit every locally owned point cell by cell, with the nodes of its
     * cell and the basis weights and gradients at its position. Every
     * particle loop of the step goes through here, so the stencil is
     * evaluated the same way everywhere.
     */
    template <int dim, typename Kernel>
    inline void
    for_each_point(const BackgroundGrid<dim>       &grid,
                   Particles::ParticleHandler<dim> &particles,
                   const Kernel                    &kernel)
    {
      using Basis = LinearBasis<dim>;
      std::array<double, Basis::n_nodes>         w;
      std::array<Tensor<1, dim>, Basis::n_nodes> grad;
      const Tensor<1, dim> &inv_h = grid.inverse_cell_size();
      for (const unsigned int index : grid.locally_owned_cells())
        {
          const auto        &cell = grid.cell(index);
          const unsigned int n    = particles.n_particles_in_cell(cell);
          if (n == 0)
            continue;
          const auto &nodes = grid.cell_nodes(index);
          auto        p     = particles.particles_in_cell(cell).begin();
          for (unsigned int i = 0; i < n; ++i, ++p)
            {
              Basis::evaluate(p->get_reference_location(), inv_h, w, grad);
              kernel(p, p->get_properties().data(), nodes, w, grad);
            }
        }
    }
  } // namespace



  template <int dim>
  TimeIntegrator<dim>::TimeIntegrator(
    const IntegratorParameters<dim> &parameters,
    const BackgroundGrid<dim>       &grid,
    MaterialPoints<dim>             &points,
    TimerOutput                     &timer,
    MPI_Comm                         comm)
    : prm(parameters)
    , grid(grid)
    , points(points)
    , timer(timer)
    , comm(comm)
  {
    grid_sums.reinit(grid.make_partitioner(n_sums));
    grid_velocity.reinit(grid.make_partitioner(n_velocities));
    for (const auto &body : points.bodies())
      {
        wave_modulus_of_body.push_back(body.material->p_wave_modulus());
        body_forces.push_back(body.body_force.get());
        has_body_forces = has_body_forces || body.body_force;
      }
    min_nodal_mass = prm.small_mass_fraction * points.min_particle_mass();

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
  }


  template <int dim>
  void
  TimeIntegrator<dim>::step(const double max_dt)
  {
    double dt = stable_time_step();
    if (prm.fixed_time_step > 0)
      {
        if (prm.fixed_time_step > dt * (1 + 1e-12))
          throw RunError("step " + std::to_string(n_steps) +
                         ": the fixed time step " +
                         std::to_string(prm.fixed_time_step) +
                         " exceeds the stability limit " + std::to_string(dt) +
                         " of the current state (points sped up or "
                         "compressed); use a smaller 'Simulation/time step' "
                         "or 0 for the CFL condition");
        dt = prm.fixed_time_step;
      }
    dt = std::min(dt, max_dt);

    switch (prm.scheme)
      {
        case UpdateScheme::USL:
          scatter_to_grid(true, true);
          grid_velocities_from_momentum(v_old);
          grid_velocities_after_forces(dt);
          gather_to_particles(dt, true);
          update_stresses(dt);
          break;
        case UpdateScheme::USF:
          scatter_to_grid(true, false);
          grid_velocities_from_momentum(v_old);
          update_kinematics(dt, v_old);
          update_stresses(dt);
          scatter_to_grid(false, true);
          grid_velocities_after_forces(dt);
          gather_to_particles(dt, false);
          break;
        case UpdateScheme::MUSL:
          scatter_to_grid(true, true);
          grid_velocities_from_momentum(v_old);
          grid_velocities_after_forces(dt);
          gather_to_particles(dt, false);
          scatter_to_grid(true, false);
          grid_velocities_from_momentum(v_new);
          update_kinematics(dt, v_new);
          update_stresses(dt);
          break;
      }
    raise_if_any_failed(failure, comm);

    {
      TimerOutput::Scope scope(timer, "relocate");
      n_removed += points.relocate(prm.out_of_grid);
    }
    t += dt;
    last_dt = dt;
    ++n_steps;
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
        const double                  c2 =
          wave_modulus_of_body[q[l.body]] * q[l.volume] / q[l.mass];
        const double v2 = v.norm_square();
        // One test catches NaN/inf in velocity, stress and volume.
        if (!std::isfinite(c2 + v2 + (s * s)) && failure.empty())
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
    const double max_speed = std::sqrt(Utilities::MPI::max(max_c2, comm)) +
                             std::sqrt(Utilities::MPI::max(max_v2, comm));
    return prm.cfl_number * grid.min_cell_size() / max_speed;
  }


  template <int dim>
  void
  TimeIntegrator<dim>::scatter_to_grid(const bool mass_and_momentum,
                                       const bool forces)
  {
    TimerOutput::Scope scope(timer, "P2G");
    double            *g = grid_sums.get_values();
    const unsigned int n_entries =
      grid_sums.locally_owned_size() +
      grid_sums.get_partitioner()->n_ghost_indices();
    for (unsigned int i = 0; i < n_entries; i += n_sums)
      {
        if (mass_and_momentum)
          for (unsigned int c = mass; c < force; ++c)
            g[i + c] = 0;
        if (forces)
          for (unsigned int c = force; c < n_sums; ++c)
            g[i + c] = 0;
      }

    const FieldLayout   &l       = points.layout();
    const Tensor<1, dim> gravity = prm.gravity;
    for (auto *f : body_forces)
      if (f != nullptr)
        f->set_time(t);
    for_each_point(grid,
                   points.handler(),
                   [&](auto &,
                       const double *q,
                       const auto   &nodes,
                       const auto   &w,
                       const auto   &grad) {
                     const double m = q[l.mass];
                     if (mass_and_momentum)
                       {
                         const Tensor<1, dim> mv =
                           m * Fields::vector<dim>(q + l.velocity);
                         for (unsigned int v = 0; v < nodes.size(); ++v)
                           {
                             double *node = g + n_sums * nodes[v];
                             node[mass] += w[v] * m;
                             for (unsigned int d = 0; d < dim; ++d)
                               node[momentum + d] += w[v] * mv[d];
                           }
                       }
                     if (forces)
                       {
                         // Internal force with the current volume and Cauchy
                         // stress.
                         const SymmetricTensor<2, dim> Vsigma =
                           q[l.volume] * Fields::symmetric<dim>(q + l.stress);
                         const Tensor<1, dim> mg =
                           m * (has_body_forces ? gravity + body_force(q)
                                                : gravity);
                         for (unsigned int v = 0; v < nodes.size(); ++v)
                           {
                             const Tensor<1, dim> f =
                               w[v] * mg - Vsigma * grad[v];
                             double *node = g + n_sums * nodes[v] + force;
                             for (unsigned int d = 0; d < dim; ++d)
                               node[d] += f[d];
                           }
                       }
                   });
    grid_sums.compress(VectorOperation::add);
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
  TimeIntegrator<dim>::grid_velocities_from_momentum(const unsigned int slot)
  {
    TimerOutput::Scope scope(timer, "grid update");
    const double      *g = grid_sums.get_values();
    double            *u = grid_velocity.get_values();
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        const double *node  = g + n_sums * i;
        double       *vel   = u + n_velocities * i;
        const double  inv_m = node[mass] > 0 ? 1. / node[mass] : 0.;
        vel[node_mass]      = node[mass];
        for (unsigned int d = 0; d < dim; ++d)
          vel[slot + d] = node[momentum + d] * inv_m;
      }
    apply_velocity_constraints(slot);
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
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        const double *node = g + n_sums * i;
        double       *vel  = u + n_velocities * i;
        const double  dt_m = node[mass] > 0 ? dt / node[mass] : 0.;
        for (unsigned int d = 0; d < dim; ++d)
          vel[v_new + d] =
            (vel[v_old + d] + dt_m * node[force + d]) * damping_factor;
      }
    apply_velocity_constraints(v_new);
    grid_velocity.update_ghost_values();
  }


  template <int dim>
  void
  TimeIntegrator<dim>::apply_velocity_constraints(const unsigned int slot)
  {
    double *u = grid_velocity.get_values();
    for (const auto &[i, mask] : grid.constrained_nodes())
      for (unsigned int d = 0; d < dim; ++d)
        if (mask & (1u << d))
          u[n_velocities * i + slot + d] = 0;
  }


  template <int dim>
  template <typename Nodes, typename Weights, typename Gradients>
  inline Tensor<2, dim>
  TimeIntegrator<dim>::velocity_gradient(const Nodes       &nodes,
                                         const Weights     &w,
                                         const Gradients   &grad,
                                         const unsigned int slot) const
  {
    const double  *u = grid_velocity.get_values();
    Tensor<1, dim> v_point;
    for (unsigned int v = 0; v < nodes.size(); ++v)
      v_point += w[v] * Fields::vector<dim>(u + n_velocities * nodes[v] + slot);
    // Sum of (v_I - v_point) grad phi_I: equal to sum v_I grad phi_I, since
    // the gradients sum to zero, but light nodes can now be left out.
    Tensor<2, dim> L;
    for (unsigned int v = 0; v < nodes.size(); ++v)
      {
        const double *node = u + n_velocities * nodes[v];
        if (node[node_mass] > min_nodal_mass)
          L +=
            outer_product(Fields::vector<dim>(node + slot) - v_point, grad[v]);
      }
    return L;
  }


  template <int dim>
  void
  TimeIntegrator<dim>::gather_to_particles(const double dt,
                                           const bool   kinematics)
  {
    TimerOutput::Scope scope(timer, "G2P");
    const FieldLayout &l     = points.layout();
    const double      *u     = grid_velocity.get_values();
    const double       alpha = prm.flip_fraction;
    for_each_point(grid,
                   points.handler(),
                   [&](auto       &p,
                       double     *q,
                       const auto &nodes,
                       const auto &w,
                       const auto &grad) {
                     Tensor<1, dim> v_grid, dv_grid;
                     for (unsigned int v = 0; v < nodes.size(); ++v)
                       {
                         const Tensor<1, dim> a = Fields::vector<dim>(
                           u + n_velocities * nodes[v] + v_old);
                         const Tensor<1, dim> b = Fields::vector<dim>(
                           u + n_velocities * nodes[v] + v_new);
                         v_grid += w[v] * b;
                         dv_grid += w[v] * (b - a);
                       }
                     const Tensor<1, dim> v_p =
                       Fields::vector<dim>(q + l.velocity);
                     const Tensor<1, dim> v_new_p =
                       alpha * (v_p + dv_grid) + (1. - alpha) * v_grid;
                     Fields::store(v_new_p, q + l.velocity);
                     p->set_location(p->get_location() + dt * v_grid);
                     if (kinematics)
                       apply_velocity_gradient(
                         p, q, velocity_gradient(nodes, w, grad, v_new), dt);
                   });
  }


  template <int dim>
  void
  TimeIntegrator<dim>::update_kinematics(const double       dt,
                                         const unsigned int slot)
  {
    TimerOutput::Scope scope(timer, "G2P");
    for_each_point(grid,
                   points.handler(),
                   [&](auto       &p,
                       double     *q,
                       const auto &nodes,
                       const auto &w,
                       const auto &grad) {
                     apply_velocity_gradient(
                       p, q, velocity_gradient(nodes, w, grad, slot), dt);
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
    TimerOutput::Scope scope(timer, "stress");
    for (unsigned int b = 0; b < points.bodies().size(); ++b)
      points.bodies()[b].material->update_stresses(points.handler(),
                                                   points.layout(),
                                                   b,
                                                   dt);
  }


  template struct IntegratorParameters<1>;
  template struct IntegratorParameters<2>;
  template struct IntegratorParameters<3>;
  template class TimeIntegrator<1>;
  template class TimeIntegrator<2>;
  template class TimeIntegrator<3>;
} // namespace mpm
