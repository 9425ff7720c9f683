// The log-strain framework's own elastic model, Hencky elasticity, and the
// parameter readers its plastic models share.
#include <mpm/materials/log_strain.h>

#include <limits>

namespace mpm
{
  namespace LogStrain
  {
    double
    parse_angle(const ParameterHandler &prm,
                const std::string      &path,
                const std::string      &name,
                const double            lower,
                const double            upper,
                const bool              upper_open)
    {
      return Parse::bounded_double(
               prm, path, name, lower, upper, false, upper_open) *
             M_PI / 180.;
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
      return_map(std::array<double, 3> &, const double) const
      {
        return false;
      }

      double
      yield_function(const std::array<double, 3> &, const double) const
      {
        return -1;
      }
    };

    template <int dim>
    using Hencky = Model<dim, NoFlow>;
  } // namespace LogStrain


  namespace LogStrainModels
  {
    MaterialEntry
    hencky_elastic()
    {
      return material_entry<LogStrain::Hencky>("Hencky elastic");
    }
  } // namespace LogStrainModels
} // namespace mpm
