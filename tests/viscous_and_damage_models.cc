// Single material points (no grid) of the rate-dependent models against
// closed forms: Maxwell relaxation at any time step, objectivity of the
// viscoelastic update under a rigid spin, the steady shear stress of
// Glen's law, the Newtonian fluid's stress, and the damage laws (delayed
// evolution at a held strain, the instantaneous law, the tension split).
// The program prints what it measured and exits non-zero if a bound is
// exceeded.
#include <mpm/materials/log_strain.h>
#include <mpm/materials/nonlocal_average.h>

#include <cmath>
#include <iostream>

#include "checks.h"
#include "single_point.h"

using namespace dealii;
using namespace mpm;

namespace
{
  using namespace checks;
  using single_point::Point;

  const double E = 1e7, nu = 0.3, G = E / (2 * (1 + nu));


  /// L of a simple shear at rate @p rate, velocity x along y.
  template <int dim>
  Tensor<2, dim>
  shear_rate(const double rate)
  {
    Tensor<2, dim> L;
    L[0][1] = rate;
    return L;
  }


  /// Rotation by @p angle about z, as a dim x dim block.
  template <int dim>
  Tensor<2, dim>
  rotation(const double angle)
  {
    Tensor<2, dim> R = unit_symmetric_tensor<dim>();
    R[0][0] = R[1][1] = std::cos(angle);
    R[0][1]           = -std::sin(angle);
    R[1][0]           = std::sin(angle);
    return R;
  }


  std::vector<std::pair<std::string, std::string>>
  maxwell(const double eta)
  {
    return {{"Young's modulus", std::to_string(E)},
            {"Poisson's ratio", std::to_string(nu)},
            {"viscosity", std::to_string(eta)}};
  }


  // -------------------------------------------------------------------------
  template <int dim>
  void
  maxwell_relaxation()
  {
    // A shear of 1e-3 applied in one short step, then held: the deviatoric
    // stress decays as exp(-G t / eta), the pressure stays. Exact at any
    // step, from a tenth of the relaxation time to ten of them.
    const double eta = 2e6, t_relax = eta / G;
    for (const double steps_per_relaxation : {10., 1., 0.1})
      {
        Point<dim>   p("Maxwell viscoelastic", maxwell(eta));
        const double load_dt = 1e-12 * t_relax;
        p.step(shear_rate<dim>(1e-3 / load_dt), load_dt);
        const SymmetricTensor<2, 3> tau0 = p.tau();
        const double                dt   = t_relax / steps_per_relaxation;
        const unsigned int          n    = 3 * steps_per_relaxation + 1;
        for (unsigned int i = 0; i < n; ++i)
          p.step(Tensor<2, dim>(), dt);
        const double                decay = std::exp(-G * n * dt / eta);
        const SymmetricTensor<2, 3> expected =
          decay * deviator(tau0) +
          trace(tau0) / 3. * unit_symmetric_tensor<3>();
        check(std::to_string(dim) + "D Maxwell relaxation over " +
                std::to_string(n) + " steps of " +
                std::to_string(1. / steps_per_relaxation) +
                " relaxation times: |tau - tau_exact| / |tau0|",
              (p.tau() - expected).norm() / tau0.norm(),
              1e-8);
      }
  }


  template <int dim>
  void
  maxwell_spin()
  {
    // Two points prestressed alike; one is spun rigidly (exact rotation
    // increments) while the other is held. Relaxation proceeds alike, so
    // their stress invariants agree, and the spun stress is the held one
    // rotated.
    const double eta = 5e5, dt = 0.02 * eta / G;
    Point<dim>   spun("Maxwell viscoelastic", maxwell(eta)),
      held("Maxwell viscoelastic", maxwell(eta));
    for (Point<dim> *p : {&spun, &held})
      {
        Tensor<2, dim> L = shear_rate<dim>(2e-3 / 1e-9);
        L[0][0]          = 1e-3 / 1e-9;
        p->step(L, 1e-9);
      }
    const double   tau0_deviator = deviator(held.tau()).norm();
    const double   omega = 3., n = 100;
    Tensor<2, dim> dR = rotation<dim>(omega * dt);
    for (unsigned int i = 0; i < n; ++i)
      {
        spun.step((dR - unit_symmetric_tensor<dim>()) / dt, dt);
        held.step(Tensor<2, dim>(), dt);
      }
    Tensor<2, 3> R3 = unit_symmetric_tensor<3>();
    const auto   R  = rotation<dim>(omega * dt * n);
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        R3[i][j] = R[i][j];
    const Tensor<2, 3> expected = R3 * Tensor<2, 3>(held.tau()) * transpose(R3);
    check(std::to_string(dim) + "D Maxwell under rigid spin: |tau_spun - R " +
            "tau_held R^T| / |tau_held|",
          (Tensor<2, 3>(spun.tau()) - expected).norm() / held.tau().norm(),
          1e-10);
    check(std::to_string(dim) + "D   ... while relaxing: |tau'| / |tau'_0| "
                                "- exp(-G t / eta)",
          deviator(spun.tau()).norm() / tau0_deviator -
            std::exp(-G * n * dt / eta),
          1e-10);
  }


  template <int dim>
  void
  glen_steady_shear()
  {
    // Simple shear at a constant rate reaches the stress Glen's law gives,
    // tau_xy = (rate / (2 A))^(1/n) (tau_e = tau_xy in simple shear), up to
    // the elastic strain (tau / G ~ 1e-6 here), at any step: the
    // relaxation is integrated exactly for a steady rate. (A corrector by
    // exp(-G dt / eta) alone would be 2.5 % low at G dt / eta = 0.05.)
    const double A = 1e-18, n = 3, rate = 1e-6, E_ice = 1e10;
    const double G_ice    = E_ice / 2.6;
    const double expected = std::pow(rate / (2 * A), 1. / n);
    const double eta      = expected / rate;
    for (const double x : {0.05, 0.5, 5.})
      {
        Point<dim> p("Maxwell viscoelastic",
                     {{"Young's modulus", std::to_string(E_ice)},
                      {"Poisson's ratio", "0.3"},
                      {"viscosity law", "Glen"},
                      {"Glen rate factor", "1e-18"},
                      {"Glen exponent", std::to_string(n)}});
        // 20 relaxation times.
        const double dt = x * eta / G_ice;
        for (unsigned int i = 0; i < 20 / x; ++i)
          p.step(shear_rate<dim>(rate), dt);
        check(std::to_string(dim) +
                "D Glen steady simple shear, G dt / eta = " +
                std::to_string(x) + ": tau_xy / (rate / 2A)^(1/n) - 1",
              p.tau()[0][1] / expected - 1,
              1e-5);
      }
  }


  // -------------------------------------------------------------------------
  /// A Hencky point with damage, uniaxial (nu = 0), stretched in one short
  /// step to log strain @p strain.
  Point<3>
  damaged_bar(const std::string &evolution,
              const double       strain,
              const double       delay_time = 1e-2)
  {
    Point<3>     p("Hencky elastic",
               {{"Young's modulus", std::to_string(E)},
                    {"Poisson's ratio", "0"},
                    {"Damage/evolution", evolution},
                    {"Damage/initiation strain", "1e-4"},
                    {"Damage/failure strain", "1e-3"},
                    {"Damage/delay time", std::to_string(delay_time)}});
    const double load_dt = 1e-14;
    Tensor<2, 3> L;
    L[0][0] = std::expm1(strain) / load_dt;
    p.step(L, load_dt);
    return p;
  }

  double
  expected_damage(const double kappa)
  {
    return kappa <= 1e-4 ? 0. : 1. - std::exp(-(kappa - 1e-4) / (1e-3 - 1e-4));
  }

  void
  delayed_damage()
  {
    // Held at a stretch, chi is constant: kappa(t) = chi - (chi - kappa0)
    // exp(-t / t_d), exactly, whatever the step; d and the stress follow.
    const double strain = 5e-4, t_d = 1e-2;
    for (const double dt : {1e-4, 3e-3, 5e-2})
      {
        Point<3>           p      = damaged_bar("delayed", strain, t_d);
        const double       kappa0 = p.q[p.layout.damage_history];
        const double       chi    = E * strain / std::exp(strain) / E;
        const unsigned int n      = 0.1 / dt;
        for (unsigned int i = 0; i < n; ++i)
          p.step(Tensor<2, 3>(), dt);
        const double kappa = p.q[p.layout.damage_history];
        const double exact = chi - (chi - kappa0) * std::exp(-(n * dt) / t_d);
        check("delayed damage, dt = " + std::to_string(dt) +
                ": kappa / kappa_exact - 1",
              kappa / exact - 1,
              1e-12);
        check("  d - d(kappa)",
              p.q[p.layout.damage] - expected_damage(kappa),
              1e-15);
        check("  sigma_xx / ((1 - d) E eps / J) - 1",
              p.tau()[0][0] / (1 - expected_damage(kappa)) / (E * strain) - 1,
              1e-12);
      }
  }

  void
  instantaneous_damage()
  {
    // kappa jumps to chi, stays on unloading, and a crack closed in
    // compression carries the undamaged stress.
    Point<3>     p = damaged_bar("instantaneous", 6e-4);
    const double d = p.q[p.layout.damage];
    check("instantaneous damage at eps = 6e-4: d - d(chi)",
          d - expected_damage(6e-4 / std::exp(6e-4)),
          1e-13);
    Tensor<2, 3> L;
    L[0][0] = std::expm1(-8e-4) / 1.;
    p.step(L, 1.);
    check("  after unloading to eps = -2e-4: d unchanged",
          p.q[p.layout.damage] - d,
          0);
    check("  ... and the compression undamaged: tau_xx / (E eps) - 1",
          p.tau()[0][0] / (E * -2e-4) - 1,
          1e-9);
  }


  // -------------------------------------------------------------------------
  template <int dim>
  void
  newtonian_fluid()
  {
    const double K = 2e6, gamma = 7, eta = 0.5;
    const std::vector<std::pair<std::string, std::string>> water = {
      {"bulk modulus", "2e6"}, {"Tait exponent", "7"}, {"viscosity", "0.5"}};
    // Compressed in all in-plane directions by 1 %.
    Point<dim>     p("Newtonian fluid", water);
    Tensor<2, dim> L;
    for (unsigned int d = 0; d < dim; ++d)
      L[d][d] = -0.01 / 1e-9;
    p.step(L, 1e-9);
    const double J = std::pow(0.99, dim);
    // Now a pure shear rate: the stress is -p I + 2 eta D'.
    // Then a shear rate (in 1D a stretching rate, whose deviator is
    // 2/3 of it along x): the stress is -p I + 2 eta D'.
    const double   rate = 3.;
    Tensor<2, dim> L_rate;
    L_rate[0][dim - 1] = rate;
    p.step(L_rate, 1e-12);
    const SymmetricTensor<2, 3> sigma = p.tau() / p.J();
    const double pressure             = K / gamma * (std::pow(J, -gamma) - 1);
    check(std::to_string(dim) + "D fluid: p / (K/gamma (J^-gamma - 1)) - 1",
          -trace(sigma) / 3 / pressure - 1,
          1e-9);
    if (dim == 1)
      check("1D   (sigma_xx + p) / (4/3 eta rate) - 1",
            (sigma[0][0] + pressure) / (4. / 3. * eta * rate) - 1,
            1e-5);
    else
      check(std::to_string(dim) + "D   sigma_xy / (eta rate) - 1",
            sigma[0][dim - 1] / (eta * rate) - 1,
            1e-9);
    // At rest under a pressure, the density is the one the equation of
    // state gives, so the stress is the initial one.
    const double          p0     = 5e4;
    SymmetricTensor<2, 3> sigma0 = -p0 * unit_symmetric_tensor<3>();
    Point<dim>            q("Newtonian fluid", water, sigma0);
    q.step(Tensor<2, dim>(), 1e-3);
    check(std::to_string(dim) + "D   initial pressure kept: p / p0 - 1",
          -trace(q.tau() / q.J()) / 3 / p0 - 1,
          1e-12);
  }
} // namespace


int
main()
{
  std::cout << "Maxwell viscoelastic" << std::endl;
  maxwell_relaxation<2>();
  maxwell_relaxation<3>();
  maxwell_spin<2>();
  maxwell_spin<3>();
  glen_steady_shear<2>();
  glen_steady_shear<3>();

  std::cout << "Damage" << std::endl;
  delayed_damage();
  instantaneous_damage();

  std::cout << "Newtonian fluid" << std::endl;
  newtonian_fluid<1>();
  newtonian_fluid<2>();
  newtonian_fluid<3>();

  std::cout << (all_ok ? "passed" : "FAILED") << std::endl;
  return all_ok ? 0 : 1;
}
