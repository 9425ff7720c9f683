// Every material model at the ends of the ranges its parameters allow
// (issue 32, class 4): a range the program accepts must run. Mohr-Coulomb
// with 'friction angle = 89.9' (the range is [0, 90)) used to stop after one
// step with "no active set found for the return mapping", naming no
// parameter.
//
// For each model, each bounded parameter is set to each end of its range
// (an open end: the nearest value a scene would write, e.g. 89.99 for
// [0, 90)), the others kept at ordinary values, and one point is driven
// along random strain paths from rest: compression, tension and shear, with
// strains up to 40 %. Every step must succeed and leave a finite state (the
// stress, every stored field, the strain energy). The plastic models also
// must leave the stress on or inside their yield surface, checked as the
// dissipation tau : d eps_p >= 0 of each plastic step (a return that
// misses the surface or runs the wrong way fails it).
#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/log_strain.h>

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
  using Settings = std::vector<std::pair<std::string, std::string>>;

  SymmetricTensor<2, 3>
  half_log(const SymmetricTensor<2, 3> &b)
  {
    const auto s = LogStrain::decompose<3>(b);
    return LogStrain::compose<3>(LogStrain::half_log(s), s);
  }

  /// Drive a point of @p model with @p settings along random paths; report
  /// the first failure (empty: none).
  std::string
  drive(const std::string &model, const Settings &settings)
  {
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const double                           dt = 1e-3;
    for (unsigned int path = 0; path < 6; ++path)
      {
        std::unique_ptr<Point<3>> point;
        try
          {
            point = std::make_unique<Point<3>>(model, settings);
          }
        catch (const std::exception &e)
          {
            return std::string("rejected: ") + e.what();
          }
        Point<3> &p = *point;
        // Paths 0-1 compress, 2-3 stretch, 4-5 shear mostly.
        const double bias = path < 2 ? -1. : path < 4 ? 1. : 0.;
        for (unsigned int i = 0; i < 200; ++i)
          {
            Tensor<2, 3> L;
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = 0; b < 3; ++b)
                L[a][b] = 1. * u(rng) + (a == b ? bias : 0.);
            const bool log_strain =
              p.layout.elastic_left_cauchy_green != FieldLayout::absent;
            SymmetricTensor<2, 3> trial;
            const double eqps = p.layout.plastic_strain != FieldLayout::absent
                                  ? p.plastic_strain()
                                  : 0.;
            if (log_strain)
              {
                Tensor<2, 3> dF = dt * L;
                for (unsigned int d = 0; d < 3; ++d)
                  dF[d][d] += 1;
                trial =
                  LogStrain::push_forward(Fields::embedded<3>(
                                            p.q.data() +
                                            p.layout.elastic_left_cauchy_green),
                                          dF);
              }
            try
              {
                p.step(L, dt);
              }
            catch (const std::exception &e)
              {
                return "step " + std::to_string(i) + " threw: " + e.what();
              }
            for (unsigned int k = 0; k < p.q.size(); ++k)
              if (!std::isfinite(p.q[k]))
                return "step " + std::to_string(i) + ": field " +
                       std::to_string(k) + " not finite";
            if (!std::isfinite(p.material->strain_energy(p.q.data(), p.layout)))
              return "step " + std::to_string(i) + ": strain energy not finite";
            if (p.layout.plastic_strain != FieldLayout::absent &&
                p.plastic_strain() > eqps)
              {
                const SymmetricTensor<2, 3> eps_p =
                  half_log(trial) -
                  half_log(Fields::embedded<3>(
                    p.q.data() + p.layout.elastic_left_cauchy_green));
                const SymmetricTensor<2, 3> tau = p.tau();
                // At an apex of zero strength tau is round-off: the floor
                // is the stiffness times the step's strain.
                const double scale =
                  std::max(tau.norm(),
                           p.material->p_wave_modulus() * eps_p.norm());
                // Round-off in the log strains grows with the model's
                // condition, the ratio of its stiffnesses (nu -> 0.5).
                const double tolerance =
                  1e-10 * p.material->p_wave_modulus() /
                  std::max(p.material->shear_modulus(), 1e-300);
                if (tau * eps_p < -tolerance * scale * eps_p.norm())
                  return "step " + std::to_string(i) +
                         ": negative dissipation " +
                         std::to_string(tau * eps_p / (scale * eps_p.norm()));
              }
          }
      }
    return "";
  }

  /// Each end of @p parameter of @p model, the rest from @p base.
  void
  ends(const std::string              &model,
       const Settings                 &base,
       const std::string              &parameter,
       const std::vector<std::string> &values)
  {
    for (const auto &value : values)
      {
        Settings s     = base;
        bool     found = false;
        for (auto &[key, v] : s)
          if (key == parameter)
            {
              v     = value;
              found = true;
            }
        if (!found)
          s.emplace_back(parameter, value);
        const std::string failure = drive(model, s);
        check_true(model + ", " + parameter + " = " + value +
                     (failure.empty() ? "" : ": " + failure),
                   failure.empty());
      }
  }

  /// ends() of each parameter in @p ranges, with its values.
  void
  ends_of_each(
    const std::string                                                   &model,
    const Settings                                                      &base,
    const std::vector<std::pair<std::string, std::vector<std::string>>> &ranges)
  {
    for (const auto &[parameter, values] : ranges)
      ends(model, base, parameter, values);
  }
} // namespace


int
main()
{
  const Settings elastic = {{"Young's modulus", "1e7"},
                            {"Poisson's ratio", "0.3"}};
  // The elastic constants of every model: E in (0, 1e15], nu in (-1, 0.5).
  // Ordinary values first: a failure there is the test's, not a range's.
  for (const std::string model : {"linear elastic",
                                  "neo-Hookean",
                                  "Hencky elastic",
                                  "von Mises",
                                  "Drucker-Prager",
                                  "Mohr-Coulomb",
                                  "Maxwell viscoelastic"})
    {
      ends(model, elastic, "Young's modulus", {"1e7", "1e-300", "1e15"});
      ends(model, elastic, "Poisson's ratio", {"-0.9999999", "0.4999999"});
    }

  ends("von Mises", elastic, "yield stress", {"1e-300", "1e300"});
  ends("von Mises", elastic, "hardening modulus", {"0", "1e300"});

  for (const std::string model : {"Drucker-Prager", "Mohr-Coulomb"})
    {
      Settings frictional = elastic;
      frictional.emplace_back("tension cutoff", "1e3");
      ends(model, frictional, "cohesion", {"0", "1e300"});
      ends(model, frictional, "friction angle", {"0", "89.99"});
      Settings steep = frictional;
      steep.emplace_back("friction angle", "89.99");
      ends(model, steep, "dilation angle", {"0", "89.99"});
      ends(model, frictional, "tension cutoff", {"0", "1e300", "apex"});
    }
  for (const std::string cone : {"outer", "inner", "plane strain"})
    ends("Drucker-Prager",
         {{"friction angle", "89.99"}, {"cohesion", "0"}},
         "cone",
         {cone});
  Settings softening = elastic;
  softening.emplace_back("softening", "linear");
  softening.emplace_back("friction angle", "40");
  softening.emplace_back("residual friction angle", "20");
  ends_of_each("Mohr-Coulomb",
               softening,
               {{"residual cohesion", {"0", "1e4"}},
                {"residual friction angle", {"0", "40"}},
                {"residual dilation angle", {"0", "20"}},
                {"residual plastic strain", {"1e-300", "1e300"}},
                {"shear band thickness", {"1e-300", "1e300"}}});

  Settings inertial = elastic;
  inertial.emplace_back("cohesion", "0");
  inertial.emplace_back("friction angle", "20");
  inertial.emplace_back("rate strengthening", "inertial");
  inertial.emplace_back("dynamic friction angle", "35");
  inertial.emplace_back("grain diameter", "1e-3");
  ends_of_each("Mohr-Coulomb",
               inertial,
               {{"dynamic friction angle", {"20", "89.99"}},
                {"grain diameter", {"1e-300", "1e300"}},
                {"reference inertial number", {"1e-300", "1e300"}},
                {"grain density", {"1e-300", "1e300"}}});

  const std::string maxwell = "Maxwell viscoelastic";
  ends(maxwell, elastic, "viscosity", {"1e-300", "1e300"});
  Settings glen = elastic;
  glen.emplace_back("viscosity law", "Glen");
  ends(maxwell, glen, "Glen rate factor", {"1e-300", "1e300"});
  ends(maxwell, glen, "Glen exponent", {"1", "10"});
  ends(maxwell, glen, "minimum strain rate", {"1e-300", "1e300"});

  const std::string fluid = "Newtonian fluid";
  ends(fluid, {}, "bulk modulus", {"1e-300", "1e15"});
  ends(fluid, {}, "Tait exponent", {"1", "20"});
  ends(fluid, {}, "viscosity", {"0", "1e300"});

  for (const std::string evolution : {"instantaneous", "delayed"})
    {
      Settings damage = elastic;
      damage.emplace_back("Damage/evolution", evolution);
      ends("Hencky elastic", damage, "Damage/initiation strain", {"1e-300"});
      damage.emplace_back("Damage/initiation strain", "1e-4");
      ends("Hencky elastic",
           damage,
           "Damage/failure strain",
           {"1.0000001e-4", "1e300"});
      ends("Hencky elastic", damage, "Damage/delay time", {"1e-300", "1e300"});
    }

  return all_ok ? 0 : 1;
}
