#ifndef mpm_materials_damage_h
#define mpm_materials_damage_h

// Continuum damage (seed 002), an option of every log-strain model: a
// history variable kappa, driven by an equivalent strain chi, sets the
// damage d in [0, 1), and d softens the stress the model computes. The
// model's own state (b_e, plastic strain) stays undamaged: damage acts on
// the nominal stress only (the effective-stress concept).
//
//   chi   = max principal Cauchy stress / E   (Rankine; 0 in compression)
//   kappa = max(kappa, chi)                    (instantaneous), or
//   kappa' = <chi - kappa> / t_d               (delayed, integrated exactly
//                                              for chi fixed over a step)
//   d     = 1 - exp(-(kappa - eps0) / (epsf - eps0))  for kappa > eps0
//
// (seed 002 prints the exponent with the other sign, which makes d
// negative.) With a nonlocal length, chi is first averaged over the
// neighbouring points (NonlocalAverage); kappa then follows from the
// average, so the softening zone has a width set by the length, not by h.
//
// Included by the model sources only.

#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/nonlocal_average.h>

#include <array>
#include <cmath>
#include <string>

namespace mpm
{
  struct FieldRequests;

  class DamageLaw
  {
  public:
    enum class Evolution
    {
      none,
      instantaneous,
      delayed
    };
    /// Declare subsection 'Damage' inside the current (model) subsection.
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /// Read subsection 'Damage' of the current subsection; @p path names
    /// the model's subsection in error messages, @p youngs_modulus scales
    /// the criterion.
    DamageLaw(dealii::ParameterHandler &prm,
              const std::string        &path,
              const double              youngs_modulus);

    bool
    enabled() const
    {
      return evolution != Evolution::none;
    }

    bool
    is_nonlocal() const
    {
      return enabled() && nonlocal.enabled();
    }

    void
    request_fields(FieldRequests &requests) const;

    /// The equivalent strain of principal Cauchy stresses @p sigma.
    double
    equivalent_strain(const std::array<double, 3> &sigma) const
    {
      return std::max({sigma[0], sigma[1], sigma[2], 0.}) / youngs_modulus;
    }

    /// kappa after a step of length @p dt with equivalent strain @p chi.
    double
    evolve(const double kappa, const double chi, const double dt) const
    {
      if (chi <= kappa)
        return kappa;
      if (evolution == Evolution::delayed)
        return chi - (chi - kappa) * std::exp(-dt / delay_time);
      return chi;
    }

    /// d(kappa).
    double
    damage(const double kappa) const
    {
      if (kappa <= initiation_strain)
        return 0.;
      return 1. - std::exp(-(kappa - initiation_strain) /
                           (failure_strain - initiation_strain));
    }

    /// Soften principal stresses @p tau by the damage @p d: the tensile
    /// ones only (a crack closes in compression), or all of them.
    void
    degrade(std::array<double, 3> &tau, const double d) const
    {
      for (double &t : tau)
        if (t > 0 || !tension_only)
          t *= 1. - d;
    }

    Evolution      evolution;
    double         youngs_modulus;
    double         initiation_strain, failure_strain;
    double         delay_time;
    bool           tension_only;
    NonlocalLength nonlocal;
  };
} // namespace mpm

#endif
