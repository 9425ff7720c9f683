// Drucker-Prager plasticity with non-associated flow and a tension cutoff,
// in the log-strain framework (de Souza Neto et al. 2008, sec. 8.3).
#include <mpm/materials/log_strain.h>

#include <algorithm>

namespace mpm
{
  namespace LogStrain
  {
    /**
     * Yield function f = sqrt(J2) + eta p - xi c, plastic potential
     * sqrt(J2) + eta_bar p, with p the mean (Kirchhoff) stress, tension
     * positive, and a tension cutoff p <= p_t. The cone is matched to
     * Mohr-Coulomb's friction angle phi as the scene chooses:
     * - 'outer': through the triaxial-compression edges of Mohr-Coulomb
     *   (eta = 6 sin phi / (sqrt3 (3 - sin phi)), xi = 6 cos phi / (...)),
     *   so triaxial compression peaks where Mohr-Coulomb does;
     * - 'inner': through the triaxial-extension edges (3 + sin phi);
     * - 'plane strain': the cone that gives Mohr-Coulomb's collapse load
     *   in plane strain with associated flow (eta = 3 tan phi /
     *   sqrt(9 + 12 tan^2 phi), xi = 3 / sqrt(9 + 12 tan^2 phi)); the
     *   default, since most plastic MPM scenes here are 2D.
     * eta_bar follows from the dilation angle psi by the same formula.
     * Perfect plasticity; the return is in closed form: to the cone, or to
     * the apex / the cutoff plane where the cone return would pass them.
     */
    struct DruckerPragerFlow
    {
      static constexpr bool is_plastic = true;

      static void
      declare_parameters(ParameterHandler &prm)
      {
        FrictionalStrength::declare_parameters(prm, false);
        prm.declare_entry("tension cutoff",
                          "apex",
                          Patterns::Anything(),
                          "Largest mean stress (tension positive) in Pa: a "
                          "number >= 0, or 'apex' for none beyond the cone's "
                          "apex c xi / eta.");
        prm.declare_entry("cone",
                          "plane strain",
                          Patterns::Selection("outer|inner|plane strain"),
                          "How the cone matches Mohr-Coulomb: outer "
                          "(triaxial compression), inner (triaxial "
                          "extension), plane strain (plane-strain collapse "
                          "load).");
      }

      /// The cone's slope for angle @p angle: {eta, xi}.
      static std::pair<double, double>
      cone(const std::string &match, const double angle)
      {
        const double s = std::sin(angle), c = std::cos(angle);
        if (match == "outer")
          return {6 * s / (std::sqrt(3.) * (3 - s)),
                  6 * c / (std::sqrt(3.) * (3 - s))};
        if (match == "inner")
          return {6 * s / (std::sqrt(3.) * (3 + s)),
                  6 * c / (std::sqrt(3.) * (3 + s))};
        const double t = std::tan(angle), r = std::sqrt(9 + 12 * t * t);
        return {3 * t / r, 3 / r};
      }

      DruckerPragerFlow(ParameterHandler       &prm,
                        const std::string      &path,
                        const ElasticConstants &c)
        : mu(c.mu)
        , K(c.bulk_modulus())
      {
        const auto        strength = FrictionalStrength::parse(prm, path);
        const std::string match    = prm.get("cone");
        std::tie(eta, xi)          = cone(match, strength.phi);
        eta_bar                    = cone(match, strength.psi).first;
        xi_c                       = xi * strength.c;
        p_max                      = std::min(parse_tension_cutoff(prm, path),
                         eta > 0 ? xi_c / eta
                                                      : std::numeric_limits<double>::infinity());
      }

      /// Mean stress and sqrt(J2) = |s| / sqrt 2.
      static std::pair<double, double>
      invariants(const std::array<double, 3> &tau)
      {
        const auto [p, s] = mean_and_deviator_norm(tau);
        return {p, s / std::sqrt(2.)};
      }

      double
      yield_function(const std::array<double, 3> &tau, const double) const
      {
        const auto [p, r] = invariants(tau);
        return std::max(r + eta * p - xi_c, p - p_max);
      }

      bool
      return_map(std::array<double, 3> &tau, const double, const double) const
      {
        const auto [p_trial, r_trial] = invariants(tau);
        const double f                = r_trial + eta * p_trial - xi_c;
        if (f <= 0 && p_trial <= p_max)
          return false;
        double p = p_trial, r = r_trial;
        if (f > 0)
          {
            const double dgamma = f / (mu + K * eta * eta_bar);
            r                   = r_trial - mu * dgamma;
            p                   = p_trial - K * eta_bar * dgamma;
          }
        if (r < 0 || p > p_max)
          {
            // The corner of cone and cutoff (the apex without a cutoff):
            // on the cutoff plane, inside or on the cone.
            p = p_max;
            r = std::min(r_trial, std::max(xi_c - eta * p_max, 0.));
          }
        const double factor = r_trial > 0 ? r / r_trial : 0.;
        for (double &t : tau)
          t = p + factor * (t - p_trial);
        return true;
      }

      /// The apex (or the cutoff's corner) is at zero stress.
      bool
      can_part() const
      {
        return p_max == 0;
      }

      const double mu, K;
      double       eta, xi, eta_bar, xi_c, p_max;
    };
  } // namespace LogStrain


  MPM_LOG_STRAIN_ENTRY(drucker_prager, DruckerPragerFlow, "Drucker-Prager")
} // namespace mpm
