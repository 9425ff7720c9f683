// Single material points (no grid) of the log-strain models against closed
// forms: Hencky elasticity (simple shear, rotation, uniaxial stretch), and
// the plastic models (pure shear, uniaxial strain, triaxial compression,
// returns to each surface of Mohr-Coulomb, consistency and non-negative
// dissipation on random strain paths). A point is driven the way the
// integrator drives it: a velocity gradient L per step, the volume scaled
// by det(I + dt L), then the material's update.
//
// The yield functions here are written out again from their textbook form,
// independently of the models, so that a return landing on the wrong
// surface fails. The program prints what it measured and exits non-zero if
// a bound is exceeded.
#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/log_strain.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "checks.h"
#include "single_point.h"

using namespace dealii;
using namespace mpm;

namespace
{
  using namespace checks;
  using single_point::Point;


  /// Principal values, largest first. (deal.II's eigenvalues() of a 3x3
  /// tensor is a closed form that loses ~1e-8 at repeated eigenvalues, the
  /// edges of Mohr-Coulomb: use the accurate decomposition.)
  std::array<double, 3>
  sorted_principal(const SymmetricTensor<2, 3> &t)
  {
    auto v = LogStrain::decompose<3>(t).values;
    std::sort(v.begin(), v.end(), std::greater<double>());
    return {{v[0], v[1], v[2]}};
  }

  double
  equivalent_stress(const SymmetricTensor<2, 3> &t)
  {
    const auto s = deviator(t);
    return std::sqrt(1.5 * (s * s));
  }

  /// Mohr-Coulomb's largest yield function of sorted principal stresses.
  double
  mohr_coulomb_f(const std::array<double, 3> &s,
                 const double                 c,
                 const double                 phi)
  {
    const double sf = std::sin(phi), k = 2 * c * std::cos(phi);
    return std::max({(s[0] - s[2]) + (s[0] + s[2]) * sf - k,
                     (s[0] - s[1]) + (s[0] + s[1]) * sf - k,
                     (s[1] - s[2]) + (s[1] + s[2]) * sf - k});
  }

  const double E = 1e7, G_nu0 = E / 2;


  // -------------------------------------------------------------------------
  template <int dim>
  void
  hencky_simple_shear()
  {
    // F = I + gamma e_x (x) e_y exactly after n steps of I + dt L (L^2 = 0).
    Point<dim>     p("Hencky elastic",
                 {{"Young's modulus", "1e7"}, {"Poisson's ratio", "0"}});
    const double   gamma = 2, n = 400;
    Tensor<2, dim> L;
    L[0][1] = gamma / n;
    for (unsigned int i = 0; i < n; ++i)
      p.step(L, 1.);
    const auto   sigma = p.material->cauchy_stress_3d(p.q.data(), p.layout);
    const double a = std::asinh(gamma / 2), r = std::sqrt(4 + gamma * gamma);
    check(std::to_string(dim) + "D simple shear gamma = 2: sigma_xy / G - " +
            "4 asinh(gamma/2)/sqrt(4+gamma^2)",
          sigma[0][1] / G_nu0 - 4 * a / r,
          1e-10);
    check(std::to_string(dim) +
            "D simple shear: sigma_xx / G - 2 gamma asinh(" +
            "gamma/2)/sqrt(4+gamma^2)",
          sigma[0][0] / G_nu0 - 2 * gamma * a / r,
          1e-10);
    check(std::to_string(dim) + "D simple shear: sigma_yy + sigma_xx",
          (sigma[1][1] + sigma[0][0]) / G_nu0,
          1e-10);
  }


  template <int dim>
  void
  hencky_rotation()
  {
    // A prestressed point turned by exact rotations (I + dt L = R): the
    // Kirchhoff stress is rotated, not changed.
    SymmetricTensor<2, 3> sigma0;
    sigma0[0][0] = 3e4, sigma0[1][1] = -1e4, sigma0[2][2] = 5e3;
    sigma0[0][1] = 2e4;
    if (dim == 3)
      sigma0[1][2] = -7e3, sigma0[0][2] = 4e3;
    Point<dim>   p("Hencky elastic",
                 {{"Young's modulus", "1e7"}, {"Poisson's ratio", "0.3"}},
                 sigma0);
    Tensor<2, 3> R_total = unit_symmetric_tensor<3>();
    for (unsigned int i = 0; i < 50; ++i)
      {
        // Rotation by 0.1 rad about z, and in 3D then about x.
        const double c = std::cos(0.1), s = std::sin(0.1);
        Tensor<2, 3> R = unit_symmetric_tensor<3>();
        R[0][0] = R[1][1] = c, R[0][1] = -s, R[1][0] = s;
        if (dim == 3)
          {
            Tensor<2, 3> Rx = unit_symmetric_tensor<3>();
            Rx[1][1] = Rx[2][2] = c, Rx[1][2] = -s, Rx[2][1] = s;
            R = Rx * R;
          }
        Tensor<2, dim> dF;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            dF[a][b] = R[a][b];
        p.step_by(dF);
        R_total = R * R_total;
      }
    const Tensor<2, 3> expected =
      R_total * Tensor<2, 3>(sigma0) * transpose(R_total);
    check(std::to_string(dim) +
            "D 50 exact rotations (round-off of 50 steps): " +
            "|tau - R tau0 R^T| / |tau0|",
          (Tensor<2, 3>(p.tau()) - expected).norm() / sigma0.norm(),
          1e-11);
  }


  template <int dim>
  void
  hencky_uniaxial_stretch()
  {
    Point<dim>     p("Hencky elastic",
                 {{"Young's modulus", "1e7"}, {"Poisson's ratio", "0"}});
    const double   stretch = 1.8, n = 100;
    Tensor<2, dim> dF = unit_symmetric_tensor<dim>();
    dF[0][0]          = std::pow(stretch, 1. / n);
    for (unsigned int i = 0; i < n; ++i)
      p.step_by(dF);
    check(std::to_string(dim) + "D uniaxial stretch 1.8: tau_xx / (E ln " +
            "lambda) - 1",
          p.tau()[0][0] / (E * std::log(stretch)) - 1,
          1e-12);
  }


  // -------------------------------------------------------------------------
  template <int dim>
  void
  von_mises_pure_shear()
  {
    // Coaxial pure shear (symmetric L, fixed principal axes at 45 degrees):
    // tau_xy = 2 G e until it reaches (sigma_y + H eqps) / sqrt 3.
    const double   sigma_y = 2e4, H = 1e5, nu = 0.25;
    Point<dim>     p("von Mises",
                 {{"Young's modulus", "1e7"},
                      {"Poisson's ratio", "0.25"},
                      {"yield stress", "2e4"},
                      {"hardening modulus", "1e5"}});
    const double   G  = E / (2 * (1 + nu));
    Tensor<2, dim> dF = unit_symmetric_tensor<dim>();
    // I + dt L with the eigenvalues exp(+-1e-4) along the diagonals.
    const double e = 1e-4;
    dF[0][0] = dF[1][1] = std::cosh(e);
    dF[0][1] = dF[1][0] = std::sinh(e);
    double max_error = 0, first_yield = 0;
    for (unsigned int i = 1; i <= 300; ++i)
      {
        p.step_by(dF);
        const double tau_xy = p.tau()[0][1];
        const double eqps   = p.plastic_strain();
        if (eqps == 0)
          max_error =
            std::max(max_error, std::abs(tau_xy - 2 * G * i * e) / sigma_y);
        else
          {
            if (first_yield == 0)
              first_yield = i;
            max_error =
              std::max(max_error,
                       std::abs(tau_xy - (sigma_y + H * eqps) / std::sqrt(3.)) /
                         sigma_y);
          }
      }
    check(std::to_string(dim) +
            "D von Mises pure shear: tau_xy against 2 G e, then (sigma_y + H "
            "eqps) / sqrt 3",
          max_error,
          1e-10);
    // Yield between the steps where 2 G e crosses sigma_y / sqrt 3.
    check(std::to_string(dim) +
            "D von Mises pure shear: first plastic step - " +
            "sigma_y / (sqrt3 2 G e)",
          std::floor(first_yield - sigma_y / (std::sqrt(3.) * 2 * G * e)),
          0);
  }


  template <int dim>
  void
  von_mises_uniaxial_strain()
  {
    // Uniaxial compression (dF = diag(a, 1, 1)): the pressure is elastic,
    // p = K ln J, and once plastic q = sigma_y exactly (no hardening).
    const double   sigma_y = 2e4, nu = 0.3;
    Point<dim>     p("von Mises",
                 {{"Young's modulus", "1e7"},
                      {"Poisson's ratio", "0.3"},
                      {"yield stress", "2e4"}});
    const double   K  = E / (3 * (1 - 2 * nu));
    Tensor<2, dim> dF = unit_symmetric_tensor<dim>();
    dF[0][0]          = 1 - 1e-4;
    double p_error = 0, q_error = 0;
    for (unsigned int i = 0; i < 200; ++i)
      {
        p.step_by(dF);
        const auto tau = p.tau();
        p_error =
          std::max(p_error,
                   std::abs(trace(tau) / 3 - K * std::log(p.J())) / sigma_y);
        if (p.plastic_strain() > 0)
          q_error =
            std::max(q_error, std::abs(equivalent_stress(tau) / sigma_y - 1));
      }
    check(std::to_string(dim) +
            "D von Mises uniaxial strain: mean stress - K " + "ln J",
          p_error,
          1e-10);
    check(std::to_string(dim) +
            "D von Mises uniaxial strain: q / sigma_y - 1 once plastic",
          q_error,
          1e-10);
    check(std::to_string(dim) + "D von Mises uniaxial strain: yielded",
          p.plastic_strain() > 0 ? 0 : 1,
          0);
  }


  // -------------------------------------------------------------------------
  /**
   * Triaxial compression under a confining stress s_c (tension positive:
   * the lateral Kirchhoff stresses are held at -s_c by adjusting the
   * lateral strain each step, the axial strain is driven). The deviator
   * q = tau_lateral - tau_axial must level off at the Mohr-Coulomb peak
   *   q = (2 c cos phi + 2 s_c sin phi) / (1 - sin phi),
   * which Drucker-Prager's outer cone shares.
   */
  template <int dim>
  double
  triaxial_peak(
    const std::string                                      &model,
    const std::vector<std::pair<std::string, std::string>> &settings,
    const double                                            s_c,
    double                                                 &edge)
  {
    SymmetricTensor<2, 3> sigma0;
    for (unsigned int d = 0; d < 3; ++d)
      sigma0[d][d] = -s_c;
    Point<dim> p(model, settings, sigma0);
    double     lateral_rate = 0;
    for (unsigned int i = 0; i < 400; ++i)
      {
        // Secant iterations on the lateral strain so that tau_yy = -s_c.
        const std::vector<double> saved          = p.q;
        auto                      lateral_stress = [&](const double rate) {
          p.q = saved;
          Tensor<2, dim> L;
          L[0][0] = -2e-4;
          for (unsigned int d = 1; d < dim; ++d)
            L[d][d] = rate;
          p.step(L, 1.);
          return p.tau()[1][1] + s_c;
        };
        double x0 = lateral_rate, f0 = lateral_stress(x0);
        double x1 = x0 + 1e-5, f1 = lateral_stress(x1);
        for (unsigned int k = 0; k < 30 && std::abs(f1) > 1e-9 * s_c; ++k)
          {
            const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
            x0 = x1, f0 = f1;
            x1 = x2, f1 = lateral_stress(x1);
          }
        lateral_rate = x1;
      }
    const auto tau = p.tau();
    edge           = std::abs(tau[1][1] - tau[2][2]) / s_c;
    return tau[1][1] - tau[0][0];
  }


  void
  triaxial_compression()
  {
    const double c = 1e4, phi = 30 * M_PI / 180;
    for (const double s_c : {5e4, 2e5})
      {
        const double expected =
          (2 * c * std::cos(phi) + 2 * s_c * std::sin(phi)) /
          (1 - std::sin(phi));
        double edge = 0;
        // The out-of-plane stress of a 2D point is the third lateral one:
        // hold it too by running in 3D (2D would be plane strain).
        const double q_mc = triaxial_peak<3>("Mohr-Coulomb",
                                             {{"Young's modulus", "1e7"},
                                              {"Poisson's ratio", "0.3"},
                                              {"cohesion", "1e4"},
                                              {"friction angle", "30"},
                                              {"dilation angle", "10"}},
                                             s_c,
                                             edge);
        check("Mohr-Coulomb triaxial compression, s_c = " +
                std::to_string(s_c) + ": q / q_peak - 1",
              q_mc / expected - 1,
              1e-9);
        check("  lateral stresses equal (returned to the compression edge)",
              edge,
              1e-9);
        // Associated flow (psi = phi, the closed end of the dilation
        // angle's range): the peak is the yield surface's, whatever psi.
        const double q_dp = triaxial_peak<3>("Drucker-Prager",
                                             {{"Young's modulus", "1e7"},
                                              {"Poisson's ratio", "0.3"},
                                              {"cohesion", "1e4"},
                                              {"friction angle", "30"},
                                              {"dilation angle", "30"},
                                              {"cone", "outer"}},
                                             s_c,
                                             edge);
        check("Drucker-Prager (outer cone) triaxial compression, s_c = " +
                std::to_string(s_c) + ": q / q_peak - 1",
              q_dp / expected - 1,
              1e-9);
      }
  }


  // -------------------------------------------------------------------------
  /**
   * Mohr-Coulomb returns from one elastic trial step (coaxial, from zero
   * stress): the trial principal log strains are those of dF exactly, so
   * the trial stresses are known and each return can be computed here in
   * closed form (de Souza Neto et al., Box 8.4) and compared.
   */
  void
  mohr_coulomb_regions()
  {
    const double nu = 0.3, c = 1e4, phi = 30 * M_PI / 180,
                 psi    = 10 * M_PI / 180;
    const double G      = E / (2 * (1 + nu)),
                 lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    const double K      = lambda + 2 * G / 3;
    const double sf = std::sin(phi), sp = std::sin(psi);
    auto         trial_stress = [&](const std::array<double, 3> &eps) {
      const double v = lambda * (eps[0] + eps[1] + eps[2]);
      return std::array<double, 3>{
        {v + 2 * G * eps[0], v + 2 * G * eps[1], v + 2 * G * eps[2]}};
    };
    auto returned = [&](const std::array<double, 3> &eps,
                        const std::string           &cutoff) {
      Point<3>     p("Mohr-Coulomb",
                 {{"Young's modulus", "1e7"},
                      {"Poisson's ratio", "0.3"},
                      {"cohesion", "1e4"},
                      {"friction angle", "30"},
                      {"dilation angle", "10"},
                      {"tension cutoff", cutoff}});
      Tensor<2, 3> dF;
      for (unsigned int d = 0; d < 3; ++d)
        dF[d][d] = std::exp(eps[d]);
      p.step_by(dF);
      return sorted_principal(p.tau());
    };
    auto relative = [](const std::array<double, 3> &a,
                       const std::array<double, 3> &b) {
      return std::max({std::abs(a[0] - b[0]),
                       std::abs(a[1] - b[1]),
                       std::abs(a[2] - b[2])}) /
             (std::abs(b[0]) + std::abs(b[1]) + std::abs(b[2]));
    };

    // Main plane: s1 > s2 > s3 well apart.
    {
      const std::array<double, 3> eps = {{3e-3, -1e-3, -1e-2}};
      const auto                  t   = trial_stress(eps);
      const double                f =
        (t[0] - t[2]) + (t[0] + t[2]) * sf - 2 * c * std::cos(phi);
      const double a      = 4 * G * (1 + sf * sp / 3) + 4 * K * sf * sp;
      const double dgamma = f / a;
      const std::array<double, 3> expected = {
        {t[0] - dgamma * (2 * G * (1 + sp) + 2 * K * sp - 4. / 3 * G * sp),
         t[1] - dgamma * (2 * K * sp - 4. / 3 * G * sp),
         t[2] - dgamma * (-2 * G * (1 - sp) + 2 * K * sp - 4. / 3 * G * sp)}};
      const auto s = returned(eps, "apex");
      check("Mohr-Coulomb main-plane return against the closed form",
            relative(s, expected),
            1e-12);
      check("  on the yield surface", mohr_coulomb_f(s, c, phi) / c, 1e-10);
    }
    // Triaxial-compression edge (s1 = s2 > s3) and extension edge
    // (s1 > s2 = s3): two equal trial stresses stay equal.
    for (const bool compression : {true, false})
      {
        const std::array<double, 3> eps =
          compression ? std::array<double, 3>{{2e-3, 2e-3, -1e-2}}
                      : std::array<double, 3>{{3e-3, -4e-3, -4e-3}};
        const auto s = returned(eps, "apex");
        const auto t = trial_stress(eps);
        check(std::string("Mohr-Coulomb ") +
                (compression ? "compression" : "extension") +
                " edge: the equal stresses stay equal",
              (compression ? s[0] - s[1] : s[1] - s[2]) / c,
              1e-10);
        check("  the other one differs",
              (compression ? s[1] - s[2] : s[0] - s[1]) / c > 0.1 ? 0 : 1,
              0);
        check("  on the yield surface", mohr_coulomb_f(s, c, phi) / c, 1e-10);
        check("  yielded", mohr_coulomb_f(t, c, phi) > 0 ? 0 : 1, 0);
      }
    // An edge reached from distinct trial stresses (the main-plane return
    // would cross s1 >= s2): the return must not land on the main plane
    // alone, which would break the ordering.
    {
      const std::array<double, 3> eps = {{2e-3, 1.9e-3, -1e-2}};
      const auto                  s   = returned(eps, "apex");
      check("Mohr-Coulomb edge from distinct trial stresses: s1 = s2",
            (s[0] - s[1]) / c,
            1e-10);
      check("  on the yield surface", mohr_coulomb_f(s, c, phi) / c, 1e-10);
    }
    // Apex: hydrostatic tension beyond c cot phi.
    {
      const auto   s    = returned({{5e-3, 5e-3, 5e-3}}, "apex");
      const double apex = c / std::tan(phi);
      check("Mohr-Coulomb apex return: s_i / (c cot phi) - 1",
            std::max({std::abs(s[0] / apex - 1),
                      std::abs(s[1] / apex - 1),
                      std::abs(s[2] / apex - 1)}),
            1e-12);
    }
    // Tension cutoff at 5 kPa: uniaxial tension returns to s1 = 5e3.
    {
      const auto s = returned({{2e-3, 0, 0}}, "5e3");
      check("Mohr-Coulomb tension cutoff: s1 / 5e3 - 1", s[0] / 5e3 - 1, 1e-12);
      check("  inside Mohr-Coulomb",
            std::max(mohr_coulomb_f(s, c, phi), 0.) / c,
            1e-10);
    }
  }


  /// Drucker-Prager's apex and tension cutoff: hydrostatic tension returns
  /// to p = xi c / eta, or to the cutoff.
  void
  drucker_prager_apex()
  {
    for (const std::string cutoff : {"apex", "2e3"})
      {
        Point<2>     p("Drucker-Prager",
                   {{"Young's modulus", "1e7"},
                        {"Poisson's ratio", "0.3"},
                        {"cohesion", "1e4"},
                        {"friction angle", "30"},
                        {"dilation angle", "10"},
                        {"tension cutoff", cutoff}});
        const double t    = std::tan(30 * M_PI / 180);
        const double apex = cutoff == "apex"
                              ? 1e4 * (3 / std::sqrt(9 + 12 * t * t)) /
                                  (3 * t / std::sqrt(9 + 12 * t * t))
                              : 2e3;
        Tensor<2, 2> dF;
        dF[0][0] = 1.004, dF[1][1] = 1.003;
        p.step_by(dF);
        const auto tau = p.tau();
        check("Drucker-Prager hydrostatic tension, cutoff " + cutoff +
                ": p / p_max - 1",
              trace(tau) / 3 / apex - 1,
              1e-12);
        check("  deviator vanishes at the apex / is kept at the cutoff",
              cutoff == "apex" ? deviator(tau).norm() / 1e4
              : deviator(tau).norm() / 1e4 - 0.1 > 0 ? 0
                                                     : 1,
              1e-12);
      }
  }


  // -------------------------------------------------------------------------
  /**
   * Steady simple shear (plane strain) of a cohesionless Mohr-Coulomb
   * point with inertial rate strengthening, from an isotropic pressure
   * p0, at the shear rate of a given inertial number. Once the flow is
   * steady all of the shear rate is plastic, and the friction the point
   * mobilises must be mu(I) = tan phi_s + (tan phi_d - tan phi_s) I / (I +
   * I_0), I = gamma_dot_p d / sqrt(p / rho_s), on the Mohr-Coulomb
   * surface: the in-plane Mohr circle's radius over its centre is
   * sin(atan mu(I)) (the out-of-plane stress stays intermediate). Without
   * the rate strengthening the circle would give sin phi_s at every rate.
   */
  void
  mohr_coulomb_inertial_shear()
  {
    const double p0 = 1e4, d = 1e-3, I_0 = 0.3, rho = Point<2>::density;
    const double mu_s = std::tan(20 * M_PI / 180);
    const double mu_d = std::tan(35 * M_PI / 180);
    SymmetricTensor<2, 3> sigma0;
    for (unsigned int i = 0; i < 3; ++i)
      sigma0[i][i] = -p0;
    for (const double I_target : {1e-6, 0.03, 0.3, 3.})
      {
        Point<2>     p("Mohr-Coulomb",
                   {{"Young's modulus", "1e7"},
                        {"Poisson's ratio", "0.3"},
                        {"cohesion", "0"},
                        {"friction angle", "20"},
                        {"dilation angle", "0"},
                        {"rate strengthening", "inertial"},
                        {"dynamic friction angle", "35"},
                        {"grain diameter", "1e-3"},
                        {"reference inertial number", "0.3"}},
                   sigma0);
        const double gamma_dot = I_target * std::sqrt(p0 / rho) / d;
        const double dt        = 1e-4 / gamma_dot;
        Tensor<2, 2> L;
        L[0][1]            = gamma_dot;
        double eqps_before = 0;
        for (unsigned int i = 0; i < 600; ++i)
          {
            eqps_before = p.plastic_strain();
            p.step(L, dt);
          }
        const double plastic_rate =
          std::sqrt(3.) * (p.plastic_strain() - eqps_before) / dt;
        const auto   tau    = p.tau();
        const double centre = -(tau[0][0] + tau[1][1]) / 2;
        const double radius =
          std::hypot((tau[0][0] - tau[1][1]) / 2, tau[0][1]);
        const double      pressure = -trace(tau) / 3;
        const double      I  = plastic_rate * d / std::sqrt(pressure / rho);
        const double      mu = mu_s + (mu_d - mu_s) * I / (I + I_0);
        const std::string at =
          "inertial shear at I = " + std::to_string(I_target);
        check(at + ": plastic shear rate / gamma_dot - 1",
              plastic_rate / gamma_dot - 1,
              1e-5);
        check(at + ": mobilised sin phi / sin(atan mu(I)) - 1",
              radius / centre / std::sin(std::atan(mu)) - 1,
              1e-6);
      }
  }


  // -------------------------------------------------------------------------
  /**
   * A cohesionless point pulled apart parts at zero stress and closes
   * again without stress: stretched by J = 1.2^dim it keeps zero stress
   * and an opening ln J; squeezed back half way and then all the way it
   * stays at zero stress (the opening halves, then vanishes; before the
   * opening existed, the way back was elastic and the point ended at
   * -K ln 1.2^dim); squeezed beyond, it answers elastically from its
   * packing, tau = K ln J I. A point with cohesion never reaches zero
   * stress at its tip and stores no opening.
   */
  template <int dim>
  void
  cohesionless_parting(const std::string &model)
  {
    const std::vector<std::pair<std::string, std::string>> settings = {
      {"Young's modulus", "1e7"},
      {"Poisson's ratio", "0.3"},
      {"cohesion", "0"},
      {"friction angle", "30"},
      {"dilation angle", "0"}};
    const std::string name =
      std::to_string(dim) + "D " + model + ", no cohesion: ";
    Point<dim>   p(model, settings);
    const double K         = 1e7 / (3 * (1 - 2 * 0.3));
    auto         isotropic = [&](const double stretch) {
      Tensor<2, dim> dF;
      for (unsigned int d = 0; d < dim; ++d)
        dF[d][d] = stretch;
      p.step_by(dF);
    };
    const double log_J = dim * std::log(1.2);
    isotropic(1.2);
    check(name + "pulled apart, |tau| / K", p.tau().norm() / K, 1e-14);
    check("  opening / ln J - 1", p.q[p.layout.opening] / log_J - 1, 1e-12);
    isotropic(std::pow(1.2, -0.5));
    check("  squeezed half way back, |tau| / K", p.tau().norm() / K, 1e-14);
    check("  opening / (ln J / 2) - 1",
          p.q[p.layout.opening] / (log_J / 2) - 1,
          1e-12);
    isotropic(std::pow(1.2, -0.5));
    check("  squeezed all the way back, |tau| / K", p.tau().norm() / K, 1e-14);
    check("  opening", p.q[p.layout.opening], 1e-14);
    // Squeezed beyond by 0.99 in-plane: elastic from the packing,
    // tau_xx = (dim lambda + 2 mu) ln 0.99 (plane strain in 2D).
    isotropic(0.99);
    const double lambda = 1e7 * 0.3 / (1.3 * 0.4), mu = 1e7 / 2.6;
    check("  squeezed beyond: tau_xx / ((dim lambda + 2 mu) ln 0.99) - 1",
          p.tau()[0][0] / ((dim * lambda + 2 * mu) * std::log(0.99)) - 1,
          1e-12);

    auto cohesive      = settings;
    cohesive[2].second = "1e4";
    const Point<dim> q(model, cohesive);
    check_true(std::to_string(dim) + "D " + model +
                 " with cohesion stores no opening",
               q.layout.opening == FieldLayout::absent);
  }


  // -------------------------------------------------------------------------
  /// 1/2 ln of a symmetric positive tensor.
  SymmetricTensor<2, 3>
  half_log(const SymmetricTensor<2, 3> &b)
  {
    const auto s = LogStrain::decompose<3>(b);
    return LogStrain::compose<3>(LogStrain::half_log(s), s);
  }

  /**
   * Random strain paths from a confined state: every step must dissipate
   * tau : d eps_p >= 0 (d eps_p = eps_trial - eps_new, coaxial), never
   * lower the plastic strain, and leave the stress inside the yield
   * surface (@p f: the model's yield function of the Kirchhoff stress and
   * the plastic strain, normalised), in a grid of cell size @p cell_size.
   */
  template <typename YieldFunction>
  void
  random_paths(const std::string                                      &model,
               const std::vector<std::pair<std::string, std::string>> &settings,
               const YieldFunction                                    &f,
               const double cell_size = 1.)
  {
    std::mt19937                           rng(42);
    std::uniform_real_distribution<double> u(-1, 1);
    double min_dissipation = 0, max_f = -1, eqps_drop = 0;
    // A plastic step ends on the surface of its own end-of-step plastic
    // strain (with softening: the consistent return).
    double       min_f_plastic = 0;
    unsigned int plastic_steps = 0;
    for (unsigned int path = 0; path < 20; ++path)
      {
        SymmetricTensor<2, 3> sigma0;
        for (unsigned int d = 0; d < 3; ++d)
          sigma0[d][d] = -5e4;
        Point<3> p(model, settings, sigma0, cell_size);
        for (unsigned int i = 0; i < 200; ++i)
          {
            Tensor<2, 3> L;
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = 0; b < 3; ++b)
                L[a][b] = 2e-3 * u(rng);
            const SymmetricTensor<2, 3> b_n = Fields::embedded<3>(
              p.q.data() + p.layout.elastic_left_cauchy_green);
            Tensor<2, 3> dF = L;
            for (unsigned int d = 0; d < 3; ++d)
              dF[d][d] += 1;
            const SymmetricTensor<2, 3> trial =
              LogStrain::push_forward(b_n, dF);
            const double eqps = p.plastic_strain();
            p.step(L, 1.);
            const SymmetricTensor<2, 3> eps_p =
              half_log(trial) -
              half_log(Fields::embedded<3>(p.q.data() +
                                           p.layout.elastic_left_cauchy_green));
            const SymmetricTensor<2, 3> tau = p.tau();
            if (p.plastic_strain() > eqps)
              {
                ++plastic_steps;
                min_dissipation =
                  std::min(min_dissipation, tau * eps_p / tau.norm());
                min_f_plastic =
                  std::min(min_f_plastic, f(tau, p.plastic_strain()));
              }
            eqps_drop = std::max(eqps_drop, eqps - p.plastic_strain());
            max_f     = std::max(max_f, f(tau, p.plastic_strain()));
          }
      }
    std::cout << "  " << model << ": " << plastic_steps
              << " plastic steps of 4000" << std::endl;
    check(model + " random paths: smallest dissipation tau : d eps_p / |tau|",
          min_dissipation,
          1e-14);
    check(model + " random paths: largest yield function after the step",
          std::max(max_f, 0.),
          1e-10);
    check(model + " random paths: plastic steps end on the yield surface",
          -min_f_plastic,
          1e-10);
    check(model + " random paths: plastic strain never falls", eqps_drop, 0);
    check(model + " random paths: some steps plastic",
          plastic_steps > 100 ? 0 : 1,
          0);
  }
} // namespace


int
main()
{
  std::cout << "Hencky elasticity" << std::endl;
  hencky_simple_shear<2>();
  hencky_simple_shear<3>();
  hencky_rotation<2>();
  hencky_rotation<3>();
  hencky_uniaxial_stretch<1>();
  hencky_uniaxial_stretch<2>();
  hencky_uniaxial_stretch<3>();

  std::cout << "von Mises" << std::endl;
  von_mises_pure_shear<2>();
  von_mises_pure_shear<3>();
  von_mises_uniaxial_strain<1>();
  von_mises_uniaxial_strain<2>();
  von_mises_uniaxial_strain<3>();

  std::cout << "Triaxial compression" << std::endl;
  triaxial_compression();

  std::cout << "Mohr-Coulomb returns" << std::endl;
  mohr_coulomb_regions();

  drucker_prager_apex();

  std::cout << "Mohr-Coulomb with inertial rate strengthening" << std::endl;
  mohr_coulomb_inertial_shear();

  std::cout << "Cohesionless points part and close" << std::endl;
  for (const std::string model : {"Mohr-Coulomb", "Drucker-Prager"})
    {
      cohesionless_parting<2>(model);
      cohesionless_parting<3>(model);
    }

  std::cout << "Random strain paths" << std::endl;
  const double c = 1e4, phi = 30 * M_PI / 180;
  random_paths("von Mises",
               {{"Young's modulus", "1e7"},
                {"Poisson's ratio", "0.3"},
                {"yield stress", "3e4"},
                {"hardening modulus", "1e5"}},
               [](const SymmetricTensor<2, 3> &tau, const double eqps) {
                 return (equivalent_stress(tau) - (3e4 + 1e5 * eqps)) / 3e4;
               });
  random_paths("Drucker-Prager",
               {{"Young's modulus", "1e7"},
                {"Poisson's ratio", "0.3"},
                {"cohesion", "1e4"},
                {"friction angle", "30"},
                {"dilation angle", "5"},
                {"cone", "outer"}},
               [&](const SymmetricTensor<2, 3> &tau, const double) {
                 const double eta =
                   6 * std::sin(phi) / (std::sqrt(3.) * (3 - std::sin(phi)));
                 const double xi =
                   6 * std::cos(phi) / (std::sqrt(3.) * (3 - std::sin(phi)));
                 const auto s = deviator(tau);
                 return (std::sqrt(0.5 * (s * s)) + eta * trace(tau) / 3 -
                         xi * c) /
                        c;
               });
  random_paths("Mohr-Coulomb",
               {{"Young's modulus", "1e7"},
                {"Poisson's ratio", "0.3"},
                {"cohesion", "1e4"},
                {"friction angle", "30"},
                {"dilation angle", "10"},
                {"tension cutoff", "3e3"}},
               [&](const SymmetricTensor<2, 3> &tau, const double) {
                 const auto s = sorted_principal(tau);
                 return std::max(mohr_coulomb_f(s, c, phi), s[0] - 3e3) / c;
               });
  // Softening: the strength follows the plastic strain at the end of the
  // step; c, phi and psi are residual at 5 % (the yield function of a
  // model residual at @p residual with residual friction angle @p phi_r).
  const std::vector<std::pair<std::string, std::string>> softening = {
    {"Young's modulus", "1e7"},
    {"Poisson's ratio", "0.3"},
    {"cohesion", "1e4"},
    {"friction angle", "30"},
    {"dilation angle", "10"},
    {"softening", "linear"},
    {"residual cohesion", "2e3"},
    {"residual plastic strain", "0.05"},
    {"residual friction angle", "20"},
    {"residual dilation angle", "0"}};
  const auto softened_yield = [&](const double residual, const double phi_r) {
    return [&, residual, phi_r](const SymmetricTensor<2, 3> &tau,
                                const double                 eqps) {
      const double w  = std::min(eqps / residual, 1.);
      const double cw = 1e4 + w * (2e3 - 1e4);
      const double pw = phi + w * (phi_r - phi);
      return mohr_coulomb_f(sorted_principal(tau), cw, pw) / 1e4;
    };
  };
  const double phi_r = 20 * M_PI / 180;
  random_paths("Mohr-Coulomb", softening, softened_yield(0.05, phi_r));
  // Softening regularised by the band's thickness: a band 0.2 m thick in
  // cells of 0.4 m is residual at half the strain given (the slip across
  // the cell, 0.025 x 0.4 m, is the band's, 0.05 x 0.2 m).
  auto regularised = softening;
  regularised.emplace_back("shear band thickness", "0.2");
  random_paths("Mohr-Coulomb", regularised, softened_yield(0.025, phi_r), 0.4);
  // Softening of the cohesion alone: the residual friction and dilation
  // angles default to the peak ones ('peak'), so phi stays 30 degrees.
  const decltype(softening) cohesion_only(softening.begin(),
                                          softening.end() - 2);
  random_paths("Mohr-Coulomb", cohesion_only, softened_yield(0.05, phi));

  std::cout << (all_ok ? "passed" : "FAILED") << std::endl;
  return all_ok ? 0 : 1;
}
