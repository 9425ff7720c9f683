// The log-strain framework's own elastic model, Hencky elasticity, and the
// parameter readers its plastic models share.
#include <mpm/materials/log_strain.h>

#include <limits>

namespace mpm
{
  namespace LogStrain
  {
    void
    FrictionalStrength::declare_parameters(ParameterHandler &prm,
                                           const bool        peak)
    {
      prm.declare_entry("cohesion",
                        "1e4",
                        Patterns::Anything(),
                        (peak ? "(Peak) cohesion" : "Cohesion") +
                          std::string(" c in Pa, >= 0."));
      prm.declare_entry("friction angle",
                        "30",
                        Patterns::Anything(),
                        (peak ? "(Peak) friction" : "Friction") +
                          std::string(" angle phi in degrees, in [0, 90)."));
      prm.declare_entry("dilation angle",
                        "0",
                        Patterns::Anything(),
                        (peak ? "(Peak) dilation" : "Dilation") +
                          std::string(" angle psi in degrees, in [0, "
                                      "friction angle] (psi = phi: "
                                      "associated flow)."));
    }


    FrictionalStrength
    FrictionalStrength::parse(const ParameterHandler &prm,
                              const std::string      &path)
    {
      FrictionalStrength s;
      const double       phi = friction_angle_degrees(prm, path);
      s.c   = Parse::bounded_double(prm, path, "cohesion", 0, 1e300);
      s.phi = radians(phi);
      s.psi =
        radians(Parse::bounded_double(prm, path, "dilation angle", 0, phi));
      return s;
    }


    double
    friction_angle_degrees(const ParameterHandler &prm, const std::string &path)
    {
      return Parse::bounded_double(
        prm, path, "friction angle", 0, 90, false, true);
    }


    double
    parse_tension_cutoff(const ParameterHandler &prm, const std::string &path)
    {
      if (prm.get("tension cutoff") == "apex")
        return std::numeric_limits<double>::infinity();
      return Parse::bounded_double(prm, path, "tension cutoff", 0, 1e300);
    }


    /**
     * No plasticity: Kirchhoff stress linear in the logarithmic strain,
     * tau = lambda tr(eps) I + 2 mu eps, eps = 1/2 ln(F F^T). Hyperelastic
     * (the stored energy is lambda/2 tr^2 eps + mu eps:eps), so any path to
     * the same F gives the same stress.
     */
    struct NoFlow
    {
      static constexpr bool is_plastic = false;

      static void
      declare_parameters(ParameterHandler &)
      {
      }

      NoFlow(ParameterHandler &, const std::string &, const ElasticConstants &)
      {
      }

      bool
      return_map(std::array<double, 3> &, const double, const double) const
      {
        return false;
      }

      double
      yield_function(const std::array<double, 3> &, const double) const
      {
        return -1;
      }
    };
  } // namespace LogStrain


  MPM_LOG_STRAIN_ENTRY(hencky_elastic, NoFlow, "Hencky elastic")
} // namespace mpm
