// The Maxwell viscoelastic solid of seed 002 (glaciers: ice flows as a
// viscous fluid over years and is elastic over seconds), in the log-strain
// framework.
#include <mpm/materials/log_strain.h>

#include <cmath>

namespace mpm
{
  namespace LogStrain
  {
    /**
     * The deviatoric Kirchhoff stress relaxes at the rate mu / eta,
     *   d(tau') / dt = 2 mu D' - (mu / eta) tau',
     * the volumetric part stays elastic. Written on b_e (F = F_e F_v, the
     * viscous stretching D_v = tau' / (2 eta)), the relaxation is a
     * corrector after the elastic predictor, in the trial's principal
     * directions n_i. The exact solution of the equation over a step with
     * D' held, with x = mu dt / eta, f = exp(-x), phi = (1 - f) / x, is
     *   tau'_{n+1} = f tau'_n + phi 2 mu dt D'
     *              = f tau'_trial + (phi - f) 2 mu dt D',
     * evaluated with the principal components n_i . D' . n_i. A held
     * stretch (D' = 0) thus relaxes as exp(-mu t / eta) at any dt, a steady
     * flow keeps its exact stress at any dt (correcting the trial by f
     * alone would lower it by x / 2, which Glen's law raises to a rate
     * error of n x / 2), and the update is stable for any dt. The b_e
     * update is objective without a stress rate, so no spin Omega^log
     * needs to be formed.
     *
     * The viscosity is a constant, or Glen's flow law for ice,
     *   D' = A tau_e^(n-1) tau',   tau_e = sqrt(tau':tau' / 2),
     * as a viscosity of the effective strain rate e = sqrt(D':D' / 2):
     *   eta = 1/2 A^(-1/n) e^((1-n)/n),
     * with e at least 'minimum strain rate' (Glen's viscosity is infinite
     * at rest).
     */
    struct MaxwellFlow
    {
      static constexpr bool is_plastic = false;

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("viscosity law",
                          "constant",
                          Patterns::Selection("constant|Glen"),
                          "constant: 'viscosity'. Glen: ice's power law, "
                          "eta = 1/2 A^(-1/n) e^((1-n)/n) of the effective "
                          "strain rate e.");
        prm.declare_entry("viscosity",
                          "1e6",
                          Patterns::Anything(),
                          "Shear viscosity eta in Pa s, > 0 (constant law): "
                          "the relaxation time is eta / shear modulus.");
        prm.declare_entry("Glen rate factor",
                          "2.4e-24",
                          Patterns::Anything(),
                          "A in Pa^-n s^-1, > 0 (Glen; 2.4e-24 is ice at "
                          "0 C with n = 3).");
        prm.declare_entry("Glen exponent",
                          "3",
                          Patterns::Anything(),
                          "n, in [1, 10] (Glen).");
        prm.declare_entry("minimum strain rate",
                          "1e-15",
                          Patterns::Anything(),
                          "Smallest effective strain rate in 1/s, > 0, in "
                          "Glen's viscosity: it caps eta where the ice is at "
                          "rest.");
      }

      MaxwellFlow(ParameterHandler       &prm,
                  const std::string      &path,
                  const ElasticConstants &c)
        : glen(prm.get("viscosity law") == "Glen")
        , viscosity(
            Parse::bounded_double(prm, path, "viscosity", 0, 1e300, true))
        , rate_factor(Parse::bounded_double(prm,
                                            path,
                                            "Glen rate factor",
                                            0,
                                            1e300,
                                            true))
        , exponent(Parse::bounded_double(prm, path, "Glen exponent", 1, 10))
        , minimum_rate(Parse::bounded_double(prm,
                                             path,
                                             "minimum strain rate",
                                             0,
                                             1e300,
                                             true))
        , glen_factor(0.5 * std::pow(rate_factor, -1. / exponent))
        , glen_power((1. - exponent) / exponent)
        , mu(c.mu)
      {
      }

      /// The viscosity at effective strain rate @p rate.
      double
      eta(const double rate) const
      {
        if (!glen)
          return viscosity;
        return glen_factor * std::pow(std::max(rate, minimum_rate), glen_power);
      }

      /**
       * The stretching of the step, (dF dF^T - I) / (2 dt) with
       * dF = I + dt L, i.e. sym(L) + dt/2 L L^T: zero for a rotation
       * increment of any size, where sym(L) alone is not.
       */
      template <int dim>
      static SymmetricTensor<2, 3>
      stretching(const Tensor<2, dim> &L, const double dt)
      {
        SymmetricTensor<2, 3> D;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            {
              double LLt = 0;
              for (unsigned int k = 0; k < dim; ++k)
                LLt += L[i][k] * L[j][k];
              D[i][j] = 0.5 * (L[i][j] + L[j][i]) + 0.5 * dt * LLt;
            }
        return D;
      }

      template <int dim>
      void
      relax(std::array<double, 3> &tau,
            const double           dt,
            const Tensor<2, dim>  &L,
            const Spectral        &s) const
      {
        const SymmetricTensor<2, 3> D_dev = deviator(stretching(L, dt));
        // Glen's effective strain rate sqrt(D':D' / 2).
        const double x =
          mu * dt / eta(glen ? std::sqrt(0.5 * (D_dev * D_dev)) : 0.);
        // One expm1 gives both, accurately also for x << 1 (real ice:
        // x ~ 1e-7, where 1 - exp(-x) would keep half the digits).
        const double em1 = std::expm1(-x);
        const double f   = 1. + em1;
        const double phi = x > 0 ? -em1 / x : 1.;
        const double p   = (tau[0] + tau[1] + tau[2]) / 3.;
        for (unsigned int k = 0; k < 3; ++k)
          tau[k] =
            p + f * (tau[k] - p) +
            (phi - f) * 2. * mu * dt * (s.vectors[k] * (D_dev * s.vectors[k]));
      }

      const bool   glen;
      const double viscosity, rate_factor, exponent, minimum_rate;
      /// 1/2 A^(-1/n) and (1 - n) / n, made once.
      const double glen_factor, glen_power;
      const double mu;
    };
  } // namespace LogStrain


  MPM_LOG_STRAIN_ENTRY(maxwell_viscoelastic,
                       MaxwellFlow,
                       "Maxwell viscoelastic")
} // namespace mpm
