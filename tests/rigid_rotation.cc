// The transfer test of Jiang et al. (2015): a disk (r = 0.3, in a unit box
// of 32 x 32 cells, 2 x 2 points per cell) rotates rigidly at omega = 0.4;
// 100 round trips P2G -> G2P with no time step and no force must leave
// its angular momentum and kinetic energy alone. APIC keeps both to 1e-12
// relative with every basis (the points start with C_p = grad v, which
// the transfer then maps to itself). PIC smooths the velocity on every
// trip and loses both; the program prints how much, and fails if APIC
// drifts by more than 1e-12 or if PIC does not lose at least 1e-3 (the
// test would then not tell the two apart).
#include <iomanip>
#include <iostream>

#include "scene.h"

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
  tests::Scene scene(
    tests::disk_scene(32,
                      "  set constants = omega=0.4\n"
                      "  set FLIP fraction = 0\n",
                      "",
                      "    set initial velocity = -omega*(y-0.5); "
                      "omega*(x-0.5)\n"),
    {"Simulation/basis=" + basis, "Simulation/transfer=" + transfer});
  const auto &points     = *scene.points;
  auto       &integrator = *scene.integrator;

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
