// The transfer test of Jiang et al. (2015): a disk (r = 0.3, in a unit box
// of 32 x 32 cells, 2 x 2 points per cell) rotates rigidly at omega = 0.4;
// 100 round trips P2G -> G2P with no time step and no force must leave
// its angular momentum and kinetic energy alone. APIC keeps both to 1e-12
// relative with every basis (the points start with C_p = grad v, which
// the transfer then maps to itself). PIC smooths the velocity on every
// trip and loses both; the program prints how much, and fails if APIC
// drifts by more than 1e-12 or if PIC does not lose at least 1e-3 (the
// test would then not tell the two apart).
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <mpm/simulation.h>

#include <iomanip>
#include <iostream>

using namespace dealii;

struct Moments
{
  double angular_momentum = 0, kinetic_energy = 0;
};

Moments
measure(const mpm::MaterialPoints<2> &points)
{
  const auto &l = points.layout();
  Moments     m;
  for (const auto &p : points.handler())
    {
      const double      *q = p.get_properties().data();
      const Tensor<1, 2> x = p.get_location() - Point<2>(0.5, 0.5);
      const Tensor<1, 2> v = mpm::Fields::vector<2>(q + l.velocity);
      m.angular_momentum += q[l.mass] * (x[0] * v[1] - x[1] * v[0]);
      m.kinetic_energy += 0.5 * q[l.mass] * v.norm_square();
    }
  return m;
}

bool
round_trips(const std::string &basis, const std::string &transfer)
{
  ParameterHandler prm;
  mpm::declare_scene_parameters(prm, 1);
  prm.parse_input_from_string(R"(
subsection Simulation
  set dimension = 2
  set constants = omega=0.4
  set FLIP fraction = 0
end
subsection Grid
  set cells = 32
end
subsection Bodies
  subsection Body 0
    set shape = ball
    set center = 0.5
    set radius = 0.3
    set particles per cell = 2
    set initial velocity = -omega*(y-0.5); omega*(x-0.5)
  end
end
)");
  prm.enter_subsection("Simulation");
  prm.set("basis", basis);
  prm.set("transfer", transfer);
  prm.leave_subsection();

  const MPI_Comm                      comm = MPI_COMM_WORLD;
  mpm::GridParameters<2>              grid_parameters;
  mpm::IntegratorParameters<2>        integrator_parameters;
  std::vector<mpm::BodyParameters<2>> bodies(1);
  grid_parameters.parse_parameters(prm);
  integrator_parameters.parse_parameters(prm);
  bodies[0].parse_parameters(prm, 0, grid_parameters);

  mpm::BackgroundGrid<2> grid(grid_parameters, comm);
  mpm::FieldRequests     fields;
  fields.affine_velocity      = transfer == "APIC";
  fields.deformation_gradient = basis == "cpGIMP";
  mpm::MaterialPoints<2> points(grid, bodies, fields, comm);
  points.generate();
  TimerOutput            timer(comm,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  mpm::VelocityRegion<2> no_region(mpm::VelocityRegionParameters<2>(), grid);
  mpm::TimeIntegrator<2> integrator(
    integrator_parameters, grid, points, no_region, timer, comm);

  const Moments before = measure(points);
  for (unsigned int i = 0; i < 100; ++i)
    integrator.transfer_round_trip();
  const Moments after = measure(points);
  const double  dL =
    std::abs(after.angular_momentum / before.angular_momentum - 1);
  const double dK = std::abs(after.kinetic_energy / before.kinetic_energy - 1);
  const bool   apic = transfer == "APIC";
  const bool   ok   = apic ? dL < 1e-12 && dK < 1e-12 : dL > 1e-3 && dK > 1e-3;
  std::cout << std::left << std::setw(20) << basis << std::setw(6)
            << (apic ? "APIC" : "PIC") << std::scientific
            << std::setprecision(2) << " relative change of L " << dL
            << ", of kinetic energy " << dK << (ok ? "" : "  FAILED")
            << std::endl;
  return ok;
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  bool                             ok = true;
  for (const std::string basis :
       {"linear", "uGIMP", "cpGIMP", "quadratic B-spline", "cubic B-spline"})
    for (const std::string transfer : {"APIC", "FLIP"})
      ok = round_trips(basis, transfer) && ok;
  std::cout << (ok ? "passed" : "FAILED") << std::endl;
  return ok ? 0 : 1;
}
