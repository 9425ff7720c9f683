// Substepping (seed 003): the macro step's grid velocity reconstruction.
//  1. An affine secant motion v*_p = a + B x_p, C*_p = B (B a rotation
//     generator, then a pure shear) is reconstructed exactly at every node
//     with mass, partly covered boundary nodes included, with every basis,
//     by the closed form and by the least-squares system (whose minimum it
//     is: both residuals vanish), the latter solved to 1e-12; for a curved
//     motion the least-squares v_k give seed 003's functional (2) a lower
//     value than the closed form's (evaluated from the basis here).
//  2. With no external force, the reconstructed grid state of a spinning,
//     drifting elastic disk after a macro step of 12 substeps carries the
//     points' linear momentum, and the APIC angular momentum of the secant
//     state (x_p^n, v*_p, C*_p), to round-off. How far the latter is from
//     the points' angular momentum after the substeps is printed (the
//     secant state is the macro step's mean motion, not its end state).
//  3. One substep per macro step reproduces the plain explicit step: a
//     block settling under gravity, 40 steps, every point's position,
//     velocity and stress to round-off.
// The program prints what it measured and exits non-zero if a bound is
// exceeded.
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <mpm/simulation.h>

#include <iomanip>
#include <iostream>
#include <map>
#include <memory>

#include "checks.h"
#include "scene.h"

using namespace dealii;
using namespace checks;
using tests::Scene;

namespace
{
  // -------------------------------------------------------------------------
  // 1. Affine secant motion.
  void
  affine_reconstruction(const std::string &basis,
                        const std::string &reconstruction,
                        const std::string &preconditioner = "Jacobi")
  {
    // The body fills part of the grid and touches its x min face, so that
    // nodes at the wall (folded B-splines) and at the body's free surface
    // (partly covered stencils) take part.
    Scene              scene(R"(
subsection Simulation
  set dimension = 2
  set macro time step = 0.1
end
subsection Grid
  set cells = 8
  set boundary x min = free
  set boundary x max = free
  set boundary y min = free
  set boundary y max = free
end
subsection Bodies
  subsection Body 0
    set shape = box
    set lower corner = 0, 0.3
    set upper corner = 0.45, 0.8
    set particles per cell = 3
  end
end
)",
                {"Simulation/basis=" + basis,
                              "Simulation/macro reconstruction=" + reconstruction,
                              "Simulation/least-squares preconditioner=" + preconditioner});
    const double       Dt = 0.1;
    const Tensor<1, 2> a({0.3, -0.2});
    for (const auto &[name, B] :
         {std::pair<std::string, Tensor<2, 2>>{
            "rotation", Tensor<2, 2>({{0, -0.5}, {0.5, 0}})},
          {"pure shear", Tensor<2, 2>({{0.2, 0.4}, {0.4, -0.2}})}})
      {
        const auto &l = scene.points->layout();
        for (auto &p : scene.points->handler())
          {
            double      *m = p.get_properties().data() + l.macro_step;
            const auto   x = p.get_location();
            Tensor<2, 2> G = Dt * B;
            G[0][0] += 1;
            G[1][1] += 1;
            mpm::Fields::store(Tensor<1, 2>(x + Dt * (a + B * x)), m);
            mpm::Fields::store(G, m + 2);
          }
        scene.integrator->substepping().reconstruct_grid_velocity(Dt);
        double       error = 0;
        unsigned int nodes = 0;
        scene.for_each_node_with_mass(
          [&](const Point<2> &x, const unsigned int k) {
            error =
              std::max(error, (scene.nodal_velocity(k) - (a + B * x)).norm());
            ++nodes;
          });
        error = Utilities::MPI::max(error, scene.comm);
        nodes = Utilities::MPI::sum(nodes, scene.comm);
        check(basis + ", " + reconstruction +
                (reconstruction == "APIC" ? "" : " (" + preconditioner + ")") +
                ", affine " + name + ": max |v_k - (a + B x_k)| over " +
                std::to_string(nodes) + " nodes",
              error,
              reconstruction == "APIC" ? 1e-13 : 1e-10);
      }
  }


  // -------------------------------------------------------------------------
  // 1b. A curved secant motion: the least-squares v_k minimise seed 003's
  //     functional (2), so it is smaller than at the closed form's v_k.
  //     J is evaluated here from the basis itself, independently of the
  //     integrator's assembly.
  double
  least_squares_functional(const Scene &scene,
                           const double Dt,
                           const double lambda)
  {
    const mpm::QuadraticBSplineBasis<2>    basis(scene.grid_parameters.n_cells,
                                              scene.grid->cell_size());
    mpm::QuadraticBSplineBasis<2>::Stencil s;
    std::array<unsigned int, mpm::QuadraticBSplineBasis<2>::n_nodes> nodes;
    const auto &l = scene.points->layout();
    double      J = 0;
    for (const auto &p : scene.points->handler())
      {
        const double                           *q = p.get_properties().data();
        Point<2>                                xi;
        mpm::BackgroundGrid<2>::CellCoordinates cell;
        scene.grid->locate(p.get_location(), cell, xi);
        basis.evaluate(cell, xi, {}, s);
        basis.node_pattern(cell, s, nodes, [&](const auto &node) {
          return scene.grid->local_node(cell, node);
        });
        Tensor<1, 2> v;
        Tensor<2, 2> grad_v;
        for (unsigned int k = 0; k < nodes.size(); ++k)
          {
            const Tensor<1, 2> v_k = scene.nodal_velocity(nodes[k]);
            v += s.weights[k] * v_k;
            grad_v += outer_product(v_k, s.gradients[k]);
          }
        const Tensor<1, 2> v_star = (mpm::Fields::vector<2>(q + l.macro_step) -
                                     Tensor<1, 2>(p.get_location())) /
                                    Dt;
        const Tensor<2, 2> C_star =
          (mpm::Fields::tensor<2>(q + l.macro_step + 2) -
           Tensor<2, 2>(unit_symmetric_tensor<2>())) /
          Dt;
        J += q[l.mass] * ((v - v_star).norm_square() +
                          lambda * (grad_v - C_star).norm_square());
      }
    return J;
  }

  void
  least_squares_minimises()
  {
    std::array<double, 2> J;
    unsigned int          iterations = 0;
    for (const unsigned int least_squares : {0, 1})
      {
        Scene        scene(tests::disk_scene(8,
                                      "  set basis = quadratic B-spline\n"
                                             "  set macro time step = 0.1\n"),
                    {std::string("Simulation/macro reconstruction=") +
                            (least_squares ? "least squares" : "APIC")});
        const double Dt = 0.1;
        const auto  &l  = scene.points->layout();
        for (auto &p : scene.points->handler())
          {
            double    *m = p.get_properties().data() + l.macro_step;
            const auto x = p.get_location();
            // v* = (sin 5x, x cos 4y), C* its gradient.
            const Tensor<1, 2> v(
              {std::sin(5 * x[0]), x[0] * std::cos(4 * x[1])});
            Tensor<2, 2> G(
              {{5 * std::cos(5 * x[0]), 0},
               {std::cos(4 * x[1]), -4 * x[0] * std::sin(4 * x[1])}});
            G *= Dt;
            G[0][0] += 1;
            G[1][1] += 1;
            mpm::Fields::store(Tensor<1, 2>(x + Dt * v), m);
            mpm::Fields::store(G, m + 2);
          }
        scene.integrator->substepping().reconstruct_grid_velocity(Dt);
        if (least_squares)
          iterations =
            scene.integrator->substepping().last_least_squares_iterations();
        J[least_squares] = least_squares_functional(
          scene, Dt, 0.25 * std::pow(scene.grid->cell_size()[0], 2));
      }
    std::cout << "  curved motion: functional (2) at the closed form " << J[0]
              << ", at the least-squares solution " << J[1] << " ("
              << iterations << " CG iterations)" << std::endl;
    check_true("least squares: J below the closed form's, after CG "
               "iterations",
               J[1] < J[0] * (1 - 1e-6) && iterations > 0);
  }


  // -------------------------------------------------------------------------
  // 2. Momentum of the reconstructed grid state.
  void
  momentum_of_reconstruction()
  {
    Scene scene(
      tests::disk_scene(32,
                        "  set basis = quadratic B-spline\n"
                        "  set constants = omega=2\n"
                        "  set macro time step = 0.005\n",
                        "",
                        "    set initial velocity = 0.3 - omega*(y-0.5); "
                        "0.1 + omega*(x-0.5)\n"
                        "    set material = neo-Hookean\n"
                        "    subsection neo-Hookean\n"
                        "      set Young's modulus = 1e6\n"
                        "    end\n",
                        0.2),
      {});
    const double Dt = 0.005;
    // Substeps from the CFL condition: the macro step is about 12 of them.
    scene.integrator->step(Dt);
    const auto  &l = scene.points->layout();
    const double d = std::pow(scene.grid->cell_size()[0], 2) / 4; // h^2/4
    Tensor<1, 2> P_points, P_grid;
    double       L_points = 0, L_secant = 0, L_grid = 0;
    for (const auto &p : scene.points->handler())
      {
        const double  *q  = p.get_properties().data();
        const double   m  = q[l.mass];
        const Point<2> x  = p.get_location();
        const Point<2> xn = Point<2>(mpm::Fields::vector<2>(q + l.macro_step));
        const Tensor<1, 2> v  = mpm::Fields::vector<2>(q + l.velocity);
        const Tensor<1, 2> vs = (x - xn) / Dt;
        const Tensor<2, 2> Cs = (mpm::Fields::tensor<2>(q + l.macro_step + 2) -
                                 Tensor<2, 2>(unit_symmetric_tensor<2>())) /
                                Dt;
        P_points += m * v;
        L_points += m * (x[0] * v[1] - x[1] * v[0]);
        // APIC's angular momentum of a point: x x m v plus the spin of its
        // affine field over the stencil, m D (C_yx - C_xy).
        L_secant +=
          m * (xn[0] * vs[1] - xn[1] * vs[0] + d * (Cs[1][0] - Cs[0][1]));
      }
    scene.for_each_node_with_mass([&](const Point<2> &x, const unsigned int k) {
      const double       m = scene.integrator->nodal_state().mass(k);
      const Tensor<1, 2> v = scene.nodal_velocity(k);
      P_grid += m * v;
      L_grid += m * (x[0] * v[1] - x[1] * v[0]);
    });
    for (unsigned int c = 0; c < 2; ++c)
      {
        P_points[c] = Utilities::MPI::sum(P_points[c], scene.comm);
        P_grid[c]   = Utilities::MPI::sum(P_grid[c], scene.comm);
      }
    L_points = Utilities::MPI::sum(L_points, scene.comm);
    L_secant = Utilities::MPI::sum(L_secant, scene.comm);
    L_grid   = Utilities::MPI::sum(L_grid, scene.comm);
    std::cout << "  macro step of " << scene.integrator->step_number()
              << " substeps" << std::endl;
    check("grid momentum - points' momentum after the substeps, relative",
          (P_grid - P_points).norm() / P_points.norm(),
          1e-13);
    check("grid angular momentum - APIC angular momentum of the secant "
          "state, relative",
          (L_grid - L_secant) / L_secant,
          1e-12);
    std::cout << "  (secant against the points' angular momentum after the "
                 "substeps, relative: "
              << (L_secant - L_points) / L_points
              << "; the secant state is the macro step's mean motion, not its "
                 "end state)"
              << std::endl;
  }


  // -------------------------------------------------------------------------
  // 3. S = 1 is the plain step.
  std::map<types::particle_index, std::vector<double>>
  settle(const bool substepping)
  {
    const std::string dt = "1e-3";
    Scene             scene(R"(
subsection Simulation
  set dimension = 2
  set gravity = 0, -9.81
  set basis = quadratic B-spline
end
subsection Grid
  set cells = 16
end
subsection Bodies
  subsection Body 0
    set shape = box
    set lower corner = 0.25, 0
    set upper corner = 0.75, 0.5
    set particles per cell = 2
    subsection linear elastic
      set Young's modulus = 1e5
    end
  end
end
)",
                substepping
                              ? std::vector<std::string>{"Simulation/macro time step=" + dt,
                                                         "Simulation/substeps=1"}
                              : std::vector<std::string>{"Simulation/time step=" + dt});
    for (unsigned int i = 0; i < 40; ++i)
      scene.integrator->step(1);
    const auto &l = scene.points->layout();
    std::map<types::particle_index, std::vector<double>> state;
    for (const auto &p : scene.points->handler())
      {
        const double *q = p.get_properties().data();
        auto         &s = state[p.get_id()];
        for (unsigned int d = 0; d < 2; ++d)
          s.push_back(p.get_location()[d]);
        for (unsigned int c = 0; c < 2; ++c)
          s.push_back(q[l.velocity + c]);
        for (unsigned int c = 0; c < 3; ++c)
          s.push_back(q[l.stress + c]);
      }
    return state;
  }

  void
  one_substep_is_the_plain_step()
  {
    const auto plain = settle(false), macro = settle(true);
    // Scales: position 1 m, velocity and stress from the plain run.
    std::array<double, 3> scale{{1, 0, 0}}, difference{{0, 0, 0}};
    for (const auto &[id, s] : plain)
      for (unsigned int c = 0; c < s.size(); ++c)
        {
          const unsigned int kind = c < 2 ? 0 : c < 4 ? 1 : 2;
          scale[kind]             = std::max(scale[kind], std::abs(s[c]));
          difference[kind] =
            std::max(difference[kind], std::abs(s[c] - macro.at(id)[c]));
        }
    check_true("S = 1: the same points", plain.size() == macro.size());
    const char *names[] = {"position", "velocity", "stress"};
    for (unsigned int k = 0; k < 3; ++k)
      check(std::string("S = 1 against the plain step after 40 steps: max "
                        "difference in ") +
              names[k] + ", relative",
            difference[k] / scale[k],
            1e-12);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  std::cout << std::scientific << std::setprecision(2);
  for (const std::string basis :
       {"linear", "uGIMP", "cpGIMP", "quadratic B-spline", "cubic B-spline"})
    for (const std::string reconstruction : {"APIC", "least squares"})
      affine_reconstruction(basis, reconstruction);
  affine_reconstruction("quadratic B-spline", "least squares", "AMG");
  least_squares_minimises();
  momentum_of_reconstruction();
  one_substep_is_the_plain_step();
  std::cout << (all_ok ? "passed" : "FAILED") << std::endl;
  return all_ok ? 0 : 1;
}
