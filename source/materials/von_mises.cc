// J2 plasticity with linear isotropic hardening, in the log-strain
// framework (de Souza Neto et al. 2008, ch. 7 and 14).
#include <mpm/materials/log_strain.h>

namespace mpm
{
  namespace LogStrain
  {
    /**
     * Yield function f = q - (sigma_y + H eqps), q = sqrt(3/2 s:s) of the
     * deviatoric Kirchhoff stress s. Radial return in principal space: the
     * trial deviator shrinks by 1 - 3 mu dgamma / q_trial with
     * dgamma = f_trial / (3 mu + H), exact for linear hardening; the
     * pressure does not change.
     */
    struct VonMisesFlow
    {
      static constexpr bool is_plastic = true;

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("yield stress",
                          "1e4",
                          Patterns::Anything(),
                          "Initial uniaxial yield stress sigma_y in Pa, > 0 "
                          "(in pure shear the material yields at sigma_y / "
                          "sqrt 3).");
        prm.declare_entry("hardening modulus",
                          "0",
                          Patterns::Anything(),
                          "Linear isotropic hardening modulus H in Pa, >= 0: "
                          "the yield stress is sigma_y + H eqps.");
      }

      VonMisesFlow(ParameterHandler       &prm,
                   const std::string      &path,
                   const ElasticConstants &c)
        : yield_stress(
            Parse::bounded_double(prm, path, "yield stress", 0, 1e300, true))
        , hardening(
            Parse::bounded_double(prm, path, "hardening modulus", 0, 1e300))
        , mu(c.mu)
      {
      }

      /// Mean and the equivalent stress q = sqrt(3/2) |s|.
      static std::pair<double, double>
      invariants(const std::array<double, 3> &tau)
      {
        const auto [p, s] = mean_and_deviator_norm(tau);
        return {p, std::sqrt(1.5) * s};
      }

      double
      yield_function(const std::array<double, 3> &tau, const double eqps) const
      {
        return invariants(tau).second - (yield_stress + hardening * eqps);
      }

      bool
      return_map(std::array<double, 3> &tau,
                 const double           eqps,
                 const double) const
      {
        const auto [p, q] = invariants(tau);
        const double f    = q - (yield_stress + hardening * eqps);
        if (f <= 0)
          return false;
        const double dgamma = f / (3. * mu + hardening);
        const double factor = 1. - 3. * mu * dgamma / q;
        for (double &t : tau)
          t = p + factor * (t - p);
        return true;
      }

      const double yield_stress, hardening, mu;
    };
  } // namespace LogStrain


  MPM_LOG_STRAIN_ENTRY(von_mises, VonMisesFlow, "von Mises")
} // namespace mpm
