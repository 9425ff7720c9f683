// The damage option of the log-strain models: its parameters.
#include <mpm/field_layout.h>
#include <mpm/materials/damage.h>
#include <mpm/materials/nonlocal_average.h>
#include <mpm/parameters.h>


namespace mpm
{
  void
  DamageLaw::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Damage");
    prm.declare_entry(
      "evolution",
      "none",
      Patterns::Selection("none|instantaneous|delayed"),
      "none: no damage. instantaneous: kappa = max(kappa, chi). delayed: "
      "kappa' = <chi - kappa> / delay time (dynamic fracture: damage "
      "cannot grow faster than 1 / delay time). chi = largest principal "
      "Cauchy stress / E, the damage d = 1 - exp(-(kappa - initiation "
      "strain) / (failure strain - initiation strain)) beyond initiation.");
    prm.declare_entry("initiation strain",
                      "1e-4",
                      Patterns::Anything(),
                      "eps0 > 0: damage starts where the largest principal "
                      "stress reaches E eps0 (the tensile strength).");
    prm.declare_entry("failure strain",
                      "1e-3",
                      Patterns::Anything(),
                      "epsf > initiation strain: sets the softening; "
                      "d = 1 - 1/e at kappa = epsf. The stress softens "
                      "from E eps0 on only if epsf <= 2 eps0; otherwise it "
                      "first rises to its peak at kappa = epsf - eps0.");
    prm.declare_entry("delay time",
                      "1e-3",
                      Patterns::Anything(),
                      "t_d > 0 in s, for 'delayed'.");
    NonlocalLength::declare_parameters(
      prm,
      "chi is averaged over the body's points before it drives kappa, so "
      "the softening zone keeps a width set by l under grid refinement");
    prm.declare_entry("degraded stress",
                      "tension",
                      Patterns::Selection("tension|all"),
                      "tension: the positive principal stresses are "
                      "multiplied by 1 - d (a crack carries compression). "
                      "all: the whole stress.");
    prm.leave_subsection();
  }


  DamageLaw::DamageLaw(ParameterHandler  &prm,
                       const std::string &model_path,
                       const double       E)
    : youngs_modulus(E)
  {
    prm.enter_subsection("Damage");
    const std::string path = model_path + "/Damage";
    const std::string e    = prm.get("evolution");
    evolution              = e == "none"            ? Evolution::none
                             : e == "instantaneous" ? Evolution::instantaneous
                                                    : Evolution::delayed;
    initiation_strain =
      Parse::bounded_double(prm, path, "initiation strain", 0, 1e300, true);
    failure_strain = Parse::bounded_double(
      prm, path, "failure strain", initiation_strain, 1e300, true);
    delay_time = Parse::bounded_double(prm, path, "delay time", 0, 1e300, true);
    nonlocal.parse(prm, path);
    tension_only = prm.get("degraded stress") == "tension";
    prm.leave_subsection();
  }


  void
  DamageLaw::request_fields(FieldRequests &requests) const
  {
    if (enabled())
      requests.damage = true;
  }
} // namespace mpm
