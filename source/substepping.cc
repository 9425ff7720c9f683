// Substepping the explicit step (seed 003, Jiang): a macro step Dt made of
// S explicit substeps, after which the grid velocity on the start-of-step
// configuration is reconstructed from what the points did, so that an
// operation that needs a large step (a projection, a coupling with another
// solver, dynamic relaxation) can act once per macro step on a grid
// velocity that stands for the whole of it.
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <mpm/checkpoint.h>
#include <mpm/parameters.h>
#include <mpm/substepping.h>
#include <mpm/time_integrator.h>
#include <mpm/transfer/deformation_increment.h>
#include <mpm/transfer/point_loop.h>

#include <cmath>
#include <sstream>

namespace mpm
{
  namespace
  {
    /**
     * Seed 003's secant targets (its equation (1)) of a point at x^n whose
     * 'macro step' field @p macro holds x^(n+1) and F^(n+1) (F^n)^-1:
     * Dt v* = x^(n+1) - x^n and Dt C* = F^(n+1) (F^n)^-1 - I.
     */
    template <int dim>
    struct SecantTargets
    {
      SecantTargets(const Point<dim> &x, const double *macro, const double Dt)
        : velocity((Fields::vector<dim>(macro) - Tensor<1, dim>(x)) / Dt)
        , gradient((Fields::tensor<dim>(macro + dim) -
                    Tensor<2, dim>(unit_symmetric_tensor<dim>())) /
                   Dt)
      {
      }

      Tensor<1, dim> velocity;
      Tensor<2, dim> gradient;
    };
  } // namespace


  template <int dim>
  Substepper<dim>::Substepper(TimeIntegrator<dim> &integrator)
    : integrator(integrator)
    , prm(integrator.prm)
    , grid(integrator.parts.grid)
    , points(integrator.parts.points)
    , nodes(integrator.nodes)
    , context(integrator.context)
  {
    if (prm.least_squares && nodes.n_fields > 1)
      throw InputError("Simulation/macro reconstruction",
                       "least squares",
                       "works on one velocity field; a scene with bodies in "
                       "'Contact/bodies' or rigid bodies needs 'APIC'");
  }


  template <int dim>
  template <typename Function>
  void
  Substepper<dim>::for_each_macro_field(const Function &f)
  {
    TimerOutput::Scope scope(context.timer, "macro step");
    const unsigned int macro_step = points.layout().macro_step;
    for (auto &p : points.handler())
      {
        double *q = p.get_properties().data();
        f(p, q, q + macro_step);
      }
  }


  template <int dim>
  template <typename Basis, typename Function>
  void
  Substepper<dim>::for_each_secant_target(const Basis    &basis,
                                          const double    Dt,
                                          const Function &f)
  {
    const FieldLayout &l = points.layout();
    integrator.loop.for_each_point(
      basis, [&](auto &p, const double *q, const auto &s) {
        f(q,
          s,
          q[l.mass],
          SecantTargets<dim>(p->get_location(), q + l.macro_step, Dt));
      });
  }


  template <int dim>
  void
  Substepper<dim>::save_state(RunState &state) const
  {
    state.values["macro_steps"]          = n_macro_steps;
    state.values["macro_mismatch"]       = mismatch;
    state.values["macro_kinetic_energy"] = macro_kinetic_energy;
  }


  template <int dim>
  void
  Substepper<dim>::restore_state(const RunState &state)
  {
    n_macro_steps        = state.get("macro_steps");
    mismatch             = state.get("macro_mismatch");
    macro_kinetic_energy = state.get("macro_kinetic_energy");
  }


  /**
   * The substeps are plain explicit steps: the points' state after them is
   * the macro step's result (S = 1 is the plain step, to the bit), and the
   * reconstruction only serves the operations. A substep never exceeds the
   * CFL limit: with S given, a substep beyond it stops the run; with S = 0
   * the remaining interval is split into as many equal substeps as the
   * current limit needs, re-evaluated at every substep.
   */
  template <int dim>
  void
  Substepper<dim>::macro_step(const double Dt)
  {
    begin();
    const double t_end = context.t + Dt;
    for (unsigned int s = 0;; ++s)
      {
        const double remaining = t_end - context.t;
        const double limit     = integrator.stable_time_step();
        if (prm.substeps > 0)
          {
            const bool   last = s + 1 == prm.substeps;
            const double dt   = last ? remaining : Dt / prm.substeps;
            if (dt > limit * (1 + 1e-12))
              {
                std::ostringstream msg;
                msg << "macro step " << n_macro_steps << ", t = " << context.t
                    << ": the substep Dt / S = " << dt
                    << " exceeds the stability limit " << limit
                    << " of the current state; set 'Simulation/substeps' to "
                       "at least "
                    << std::ceil(Dt / limit) << ", or to 0 to follow the "
                    << "CFL condition";
                throw RunError(msg.str());
              }
            substep(dt);
            if (last)
              break;
          }
        else
          {
            const double n_left =
              std::max(1., std::ceil(remaining / limit * (1 - 1e-12)));
            substep(remaining / n_left);
            if (n_left == 1)
              break;
          }
      }
    context.t = t_end;
    end(Dt);
  }


  template <int dim>
  void
  Substepper<dim>::begin()
  {
    for_each_macro_field([](auto &p, double *, double *m) {
      Fields::store(Tensor<1, dim>(p.get_location()), m);
      Fields::store(Tensor<2, dim>(unit_symmetric_tensor<dim>()), m + dim);
    });
  }


  template <int dim>
  void
  Substepper<dim>::substep(const double dt)
  {
    integrator.explicit_step(dt);
    accumulate_increment(dt);
    if (integrator.after_substep)
      integrator.after_substep();
  }


  /**
   * dF = I + dt L is each substep's increment of F (taken after the step:
   * the points keep the L the stress update saw, after F-bar, until the
   * next step's kinematics), and the product of the increments is
   * F^(n+1) (F^n)^-1 exactly, for every point, whether or not its material
   * stores F.
   */
  template <int dim>
  void
  Substepper<dim>::accumulate_increment(const double dt)
  {
    const unsigned int L = points.layout().velocity_gradient;
    for_each_macro_field([&](auto &, double *q, double *m) {
      const Tensor<2, dim> dF =
        deformation_increment(Fields::tensor<dim>(q + L), dt);
      Fields::store(Tensor<2, dim>(dF * Fields::tensor<dim>(m + dim)), m + dim);
    });
  }


  /**
   * The reconstruction weighs each point at x^n, in the cell (and on the
   * rank) that held it there, while the points have moved on: they are
   * put back for it and forward again, through the relocation every step
   * uses. That costs two relocations per macro step instead of a stencil
   * that reaches beyond the ghost layer.
   */
  template <int dim>
  void
  Substepper<dim>::swap_positions()
  {
    for_each_macro_field([](auto &p, double *, double *m) {
      const Point<dim> other = Point<dim>(Fields::vector<dim>(m));
      Fields::store(Tensor<1, dim>(p.get_location()), m);
      p.set_location(other);
    });
    TimerOutput::Scope scope(context.timer, "relocate");
    integrator.n_removed += points.relocate(prm.out_of_grid);
  }


  template <int dim>
  template <typename Basis>
  void
  Substepper<dim>::scatter_targets(const Basis &basis, const double Dt)
  {
    TimerOutput::Scope scope(context.timer, "macro step");
    double            *g         = nodes.sums.get_values();
    const unsigned int n_entries = n_local_entries(nodes.sums);
    for (unsigned int i = 0; i < n_entries; ++i)
      g[i] = 0;
    for_each_secant_target(basis,
                           Dt,
                           [&](const double             *q,
                               const auto               &s,
                               const double              m,
                               const SecantTargets<dim> &target) {
                             const Tensor<1, dim> mv    = m * target.velocity;
                             const Tensor<2, dim> mC    = m * target.gradient;
                             const unsigned int   field = nodes.field_of(q);
                             for (unsigned int v = 0; v < Basis::n_nodes; ++v)
                               {
                                 double *node =
                                   g + Layout::n_sums *
                                         nodes.slot_of(s.nodes[v], field);
                                 const Tensor<1, dim> pk =
                                   mv + mC * s.node_offset(v);
                                 node[Layout::mass] += s.weights[v] * m;
                                 for (unsigned int d = 0; d < dim; ++d)
                                   node[Layout::momentum + d] +=
                                     s.weights[v] * pk[d];
                               }
                           });
    nodes.sums.compress(VectorOperation::add);
  }


  template <int dim>
  void
  Substepper<dim>::reconstruct_grid_velocity(const double Dt)
  {
    integrator.loop.with_scene_basis([&](const auto &basis) {
      scatter_targets(basis, Dt);
      // Divided by the mass (and the least-squares system solved from
      // there), then projected on the boundary conditions like any grid
      // velocity. The projection is no work done on the bodies: the
      // substeps counted that already.
      const double work_so_far = integrator.loads.step_work_so_far();
      integrator.grid_update.velocities_from_momentum(Layout::v_new);
      if (prm.least_squares)
        {
          solve_least_squares_reconstruction(basis, Dt);
          integrator.grid_update.apply_constraints(Layout::v_new);
          nodes.velocities.update_ghost_values();
        }
      integrator.loads.set_step_work(work_so_far);
    });
    // v_old keeps the reconstruction as it was, v_new is what the
    // operations make of it.
    double            *u         = nodes.velocities.get_values();
    const unsigned int n_entries = n_local_entries(nodes.velocities);
    for (unsigned int i = 0; i < n_entries; i += Layout::n_velocities)
      for (unsigned int d = 0; d < dim; ++d)
        u[i + Layout::v_old + d] = u[i + Layout::v_new + d];
  }


  /**
   * Seed 003's least-squares fit before its simplifications: v_k minimises
   *   sum_p m_p |v_p(v) - v*_p|^2 + lambda sum_p m_p |grad v_p(v) - C*_p|^2,
   * that is, per velocity component, the SPD system
   *   sum_j [sum_p m_p w_kp w_jp + lambda sum_p m_p grad w_kp . grad w_jp] v_j
   *     = sum_p m_p w_kp v*_p + lambda sum_p m_p C*_p grad w_kp,
   * with the consistent mass and the exact gradients (the closed form lumps
   * the one, drops the stiffness and approximates the other). It is
   * assembled point by point into a Trilinos matrix over the grid's nodes
   * (rows of ghost nodes are sent to their owners) and solved by
   * conjugate gradients from the closed form's v_k, which is close.
   * Nodes with no mass have no velocity equation: their diagonal gets 1.
   */
  template <int dim>
  template <typename Basis>
  void
  Substepper<dim>::solve_least_squares_reconstruction(const Basis &basis,
                                                      const double Dt)
  {
    TimerOutput::Scope scope(context.timer, "macro least squares");
    const Utilities::MPI::Partitioner &partition = grid.node_partitioner();
    const IndexSet                    &owned = partition.locally_owned_range();
    IndexSet                           relevant = owned;
    relevant.add_indices(partition.ghost_indices());
    const unsigned int n_local =
      owned.n_elements() + partition.n_ghost_indices();
    std::vector<types::global_dof_index> global(n_local);
    for (unsigned int i = 0; i < n_local; ++i)
      global[i] = partition.local_to_global(i);

    const double lambda = prm.least_squares_weight *
                          Utilities::fixed_power<2>(grid.min_cell_size());
    // The couplings: every pair of nodes of a point's stencil.
    TrilinosWrappers::SparsityPattern                   pattern(owned,
                                              owned,
                                              relevant,
                                              context.comm);
    std::array<types::global_dof_index, Basis::n_nodes> stencil;
    integrator.loop.for_each_point(
      basis, [&](auto &, const double *, const auto &s) {
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          stencil[v] = global[s.nodes[v]];
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          pattern.add_entries(stencil[v], stencil.begin(), stencil.end());
      });
    const double             *u = nodes.velocities.get_values();
    std::vector<unsigned int> massless;
    for (unsigned int i = 0; i < owned.n_elements(); ++i)
      if (!(u[Layout::n_velocities * i + Layout::node_mass] > 0))
        massless.push_back(i);
    for (const unsigned int i : massless)
      pattern.add(global[i], global[i]);
    pattern.compress();

    TrilinosWrappers::SparseMatrix                 A(pattern);
    std::array<TrilinosWrappers::MPI::Vector, dim> rhs, solution;
    for (unsigned int d = 0; d < dim; ++d)
      {
        rhs[d].reinit(owned, relevant, context.comm, true);
        solution[d].reinit(owned, context.comm);
      }
    std::array<double, Basis::n_nodes> row;
    for_each_secant_target(
      basis,
      Dt,
      [&](const double *,
          const auto               &s,
          const double              m,
          const SecantTargets<dim> &target) {
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          stencil[v] = global[s.nodes[v]];
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          {
            for (unsigned int w = 0; w < Basis::n_nodes; ++w)
              row[w] = m * (s.weights[v] * s.weights[w] +
                            lambda * (s.gradients[v] * s.gradients[w]));
            A.add(stencil[v], Basis::n_nodes, stencil.data(), row.data());
            const Tensor<1, dim> b =
              m * (s.weights[v] * target.velocity +
                   lambda * (target.gradient * s.gradients[v]));
            for (unsigned int d = 0; d < dim; ++d)
              rhs[d](stencil[v]) += b[d];
          }
      });
    for (const unsigned int i : massless)
      A.add(global[i], global[i], 1.);
    A.compress(VectorOperation::add);
    for (unsigned int d = 0; d < dim; ++d)
      rhs[d].compress(VectorOperation::add);

    TrilinosWrappers::PreconditionJacobi jacobi;
    TrilinosWrappers::PreconditionAMG    amg;
    if (prm.least_squares_amg)
      amg.initialize(A);
    else
      jacobi.initialize(A);
    double *v_grid           = nodes.velocities.get_values();
    least_squares_iterations = 0;
    for (unsigned int d = 0; d < dim; ++d)
      {
        for (unsigned int i = 0; i < owned.n_elements(); ++i)
          solution[d](global[i]) =
            v_grid[Layout::n_velocities * i + Layout::v_new + d];
        solution[d].compress(VectorOperation::insert);
        SolverControl control(1000, 1e-12 * rhs[d].l2_norm());
        SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
        try
          {
            if (prm.least_squares_amg)
              cg.solve(A, solution[d], rhs[d], amg);
            else
              cg.solve(A, solution[d], rhs[d], jacobi);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            std::ostringstream msg;
            msg << "macro step " << n_macro_steps
                << ": the least-squares reconstruction did not converge in "
                << e.last_step << " conjugate-gradient iterations (residual "
                << e.last_residual << "); try 'Simulation/least-squares "
                << "preconditioner = AMG' or 'Simulation/macro "
                   "reconstruction = APIC'";
            throw RunError(msg.str());
          }
        least_squares_iterations += control.last_step();
        for (unsigned int i = 0; i < owned.n_elements(); ++i)
          v_grid[Layout::n_velocities * i + Layout::v_new + d] =
            solution[d](global[i]);
      }
  }


  /**
   * Kinetic damping (dynamic relaxation; Cundall 1987, Underwood 1983):
   * a body settling into its static state oscillates about it; where its
   * kinetic energy peaks it passes the static state, and setting every
   * velocity to zero there removes the oscillation's energy at once. The
   * peak is judged once per macro step, on the reconstructed grid
   * velocity: over one explicit step the kinetic energy is noisy (FLIP,
   * points crossing cells), over a macro step it is the body's.
   */
  template <int dim>
  bool
  Substepper<dim>::apply_operations()
  {
    bool reset = false;
    if (prm.kinetic_damping)
      {
        const double *u      = nodes.velocities.get_values();
        double        energy = 0;
        for (unsigned int i = 0; i < nodes.n_owned_slots(); ++i)
          energy +=
            0.5 * u[Layout::n_velocities * i + Layout::node_mass] *
            Fields::vector<dim>(u + Layout::n_velocities * i + Layout::v_new)
              .norm_square();
        energy = Utilities::MPI::sum(energy, context.comm);
        if (energy < macro_kinetic_energy)
          {
            double            *w         = nodes.velocities.get_values();
            const unsigned int n_entries = n_local_entries(nodes.velocities);
            for (unsigned int i = 0; i < n_entries; i += Layout::n_velocities)
              for (unsigned int d = 0; d < dim; ++d)
                w[i + Layout::v_new + d] = 0;
            reset  = true;
            energy = 0;
          }
        macro_kinetic_energy = energy;
      }
    return reset;
  }


  template <int dim>
  template <typename Basis>
  void
  Substepper<dim>::gather_velocity(const Basis &basis,
                                   const double Dt,
                                   const bool   reset)
  {
    TimerOutput::Scope scope(context.timer, "macro step");
    const FieldLayout &l      = points.layout();
    const double      *u_all  = nodes.velocities.get_values();
    const bool         apic   = l.affine_velocity != FieldLayout::absent;
    const unsigned int stride = nodes.n_fields * Layout::n_velocities;
    std::array<Tensor<1, dim>, Basis::n_nodes> affine;
    double                                     largest_here = 0;
    integrator.loop.for_each_point(
      basis, [&](auto &p, double *q, const auto &s) {
        const double  *u = u_all + Layout::n_velocities * nodes.field_of(q);
        Tensor<1, dim> v_reconstructed, v_reset;
        for (unsigned int v = 0; v < Basis::n_nodes; ++v)
          {
            const double *node = u + stride * s.nodes[v];
            v_reconstructed +=
              s.weights[v] * Fields::vector<dim>(node + Layout::v_old);
            v_reset += s.weights[v] * Fields::vector<dim>(node + Layout::v_new);
          }
        const SecantTargets<dim> target(p->get_location(),
                                        q + l.macro_step,
                                        Dt);
        largest_here =
          std::max(largest_here,
                   Dt * (target.velocity - v_reconstructed).norm());
        if (reset)
          {
            Fields::store(v_reset, q + l.velocity);
            if (apic)
              Fields::store(apic_velocity_gradient<dim>(
                              basis, s, u, stride, Layout::v_new, affine),
                            q + l.affine_velocity);
          }
      });
    mismatch = std::max(mismatch,
                        Utilities::MPI::max(largest_here, context.comm) /
                          grid.min_cell_size());
  }


  template <int dim>
  void
  Substepper<dim>::end(const double Dt)
  {
    swap_positions(); // the points at x^n, x^(n+1) in their field
    reconstruct_grid_velocity(Dt);
    const bool reset = apply_operations();
    integrator.loop.with_scene_basis(
      [&](const auto &basis) { gather_velocity(basis, Dt, reset); });
    swap_positions(); // and back at x^(n+1)
    ++n_macro_steps;
  }


  template class Substepper<1>;
  template class Substepper<2>;
  template class Substepper<3>;
} // namespace mpm
