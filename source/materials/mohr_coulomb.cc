// Mohr-Coulomb plasticity with non-associated flow, a tension cutoff and
// optional linear softening, in the log-strain framework (Clausen et al.
// 2007; de Souza Neto et al. 2008, sec. 8.2).
#include <mpm/materials/log_strain.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace mpm
{
  namespace LogStrain
  {
    namespace
    {
      /// A plane f = a . sigma - k <= 0 in principal stress space, with
      /// plastic flow along n.
      struct Plane
      {
        std::array<double, 3> a, n;
        double                k;
      };

      double
      dot(const std::array<double, 3> &x, const std::array<double, 3> &y)
      {
        return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
      }

      /// Solve the m x m system A x = b (m <= 3) by Gaussian elimination
      /// with partial pivoting; false if it is singular.
      bool
      solve(std::array<std::array<double, 3>, 3> A,
            std::array<double, 3>               &b,
            const unsigned int                   m)
      {
        for (unsigned int c = 0; c < m; ++c)
          {
            unsigned int pivot = c;
            for (unsigned int r = c + 1; r < m; ++r)
              if (std::abs(A[r][c]) > std::abs(A[pivot][c]))
                pivot = r;
            if (std::abs(A[pivot][c]) < 1e-12 * std::abs(A[0][0]))
              return false;
            std::swap(A[c], A[pivot]);
            std::swap(b[c], b[pivot]);
            for (unsigned int r = c + 1; r < m; ++r)
              {
                const double factor = A[r][c] / A[c][c];
                for (unsigned int k = c; k < m; ++k)
                  A[r][k] -= factor * A[c][k];
                b[r] -= factor * b[c];
              }
          }
        for (int c = m - 1; c >= 0; --c)
          {
            for (unsigned int k = c + 1; k < m; ++k)
              b[c] -= A[c][k] * b[k];
            b[c] /= A[c][c];
          }
        return true;
      }
    } // namespace


    /**
     * With principal stresses sorted, s1 >= s2 >= s3 (tension positive),
     * Mohr-Coulomb is the plane
     *   f = (s1 - s3) + (s1 + s3) sin phi - 2 c cos phi <= 0,
     * and at the edges of the pyramid the planes of the neighbouring
     * sextants, (s1, s2) and (s2, s3), take over; the tension cutoff adds
     * the planes s_i <= t. The flow follows the same planes with the
     * dilation angle psi.
     *
     * For fixed strength parameters every surface is a plane and the
     * return is linear in the plastic multipliers, so it is found exactly:
     * for each candidate set of active planes (one plane, an edge of two,
     * a corner of three; the main plane first), solve for the multipliers
     * and accept the first set whose multipliers are non-negative and whose
     * stress satisfies every plane and stays sorted (the conditions of
     * Clausen et al. for main plane, edges and apex, in one loop). Without
     * a cutoff, t is the apex c cot phi, so the corner of the three cutoff
     * planes is the apex return.
     *
     * Softening: c, phi and psi fall linearly from their peak to their
     * residual values as the equivalent plastic strain grows to the
     * 'residual plastic strain'. The return is then consistent at the end
     * of the step: the plastic strain increment solves
     *   x = g(x),  g(x) = increment of the return with the parameters at
     *   eqps_n + x,
     * by the secant method on the active set of the return with the
     * strength at eqps_n (consistent_softening_return), and by the
     * Illinois (regula falsi) method on [0, g(residual)], which brackets
     * the root because g grows as the material softens, where that fails.
     *
     * Rate strengthening (the mu(I) rheology of dense granular flow, Jop,
     * Forterre and Pouliquen 2006): the friction rises with the inertial
     * number of the plastic flow, I = gamma_dot d / sqrt(p / rho_s), as
     *   tan phi = mu(I) = tan phi_s + (tan phi_d - tan phi_s) I / (I + I_0),
     * phi_s the friction angle, phi_d its limit for fast flow. gamma_dot is
     * the plastic shear rate of the step, sqrt(3) x / dt for a plastic
     * strain increment x (x is the von Mises equivalent, gamma / sqrt 3 in
     * simple shear), and p the trial's Kirchhoff pressure (the Cauchy one
     * within the elastic volume change; exact at psi = 0, where the return
     * keeps the pressure). The return is consistent at the end of the step,
     * as for softening: x solves x = g(x), g(x) the increment of the return
     * with the friction of rate x / dt. The friction grows with x, so g
     * falls and [0, g(0)] brackets the root. Because the return is
     * implicit in the rate, the rate term adds no time step limit (a
     * viscosity of up to (tan phi_d - tan phi_s) p / gamma_dot would, if
     * taken explicitly). Dunatunga and Kamrin (2015) return mu(I) in an
     * elastic-plastic MPM in the same way. The incompressible mu(I)
     * equations are ill-posed at very low and very high I (Barker et al.
     * 2015); what elasticity and the grid do to that here is not analysed.
     */
    struct MohrCoulombFlow
    {
      static constexpr bool is_plastic = true;

      static void
      declare_parameters(ParameterHandler &prm)
      {
        FrictionalStrength::declare_parameters(prm, true);
        prm.declare_entry("tension cutoff",
                          "apex",
                          Patterns::Anything(),
                          "Largest principal stress (tension positive) in Pa: "
                          "a number >= 0, or 'apex' for none beyond the "
                          "apex c cot phi.");
        prm.declare_entry("softening",
                          "none",
                          Patterns::Selection("none|linear"),
                          "none, or linear: c, phi and psi fall linearly from "
                          "their peak to their residual values as the "
                          "equivalent plastic strain grows from 0 to "
                          "'residual plastic strain'.");
        // The residual values default to the peak ones, so that a scene
        // softens only what it names (a friction angle falling to 0 by
        // default turned every softening slope into a fluid).
        prm.declare_entry("residual cohesion",
                          "peak",
                          Patterns::Anything(),
                          "Softening: residual cohesion in Pa, in [0, "
                          "cohesion], or 'peak' for the cohesion.");
        prm.declare_entry("residual friction angle",
                          "peak",
                          Patterns::Anything(),
                          "Softening: residual friction angle in degrees, in "
                          "[0, friction angle], or 'peak' for the friction "
                          "angle.");
        prm.declare_entry("residual dilation angle",
                          "peak",
                          Patterns::Anything(),
                          "Softening: residual dilation angle in degrees, in "
                          "[0, residual friction angle], or 'peak' for the "
                          "smaller of the dilation angle and the residual "
                          "friction angle.");
        prm.declare_entry("residual plastic strain",
                          "0.1",
                          Patterns::Anything(),
                          "Softening: equivalent plastic strain at which the "
                          "residual values are reached, > 0 (in a shear "
                          "band of 'shear band thickness').");
        prm.declare_entry(
          "shear band thickness",
          "local",
          Patterns::Anything(),
          "Softening: 'local' (the residual plastic strain as given, on "
          "every grid: a band of softening forms a cell wide, so on a finer "
          "grid the soil is residual after less slip and dissipates less "
          "work), or the thickness in m, > 0, of the band for which the "
          "residual plastic strain is given: the program scales the strain "
          "by this thickness over the cell size, so that the slip across "
          "the band at which the soil is residual, strain x thickness, is "
          "the same on every grid (regularisation by the band's width; it "
          "assumes the band a cell wide, which it is not on fine grids: "
          "benchmarks/plasticity/README.md). 'local' with a nonlocal length.");
        NonlocalLength::declare_parameters(
          prm,
          "with softening, the strength softens with an average of the plastic "
          "strain over the body's points ('nonlocal factor'), so that a "
          "shear band keeps a width set by l on every grid and the residual "
          "plastic strain is the band's strain, not a cell's");
        prm.declare_entry(
          "nonlocal factor",
          "2",
          Patterns::Anything(),
          "Softening with a nonlocal length: m >= 1; the strength softens "
          "with max(0, (1 - m) eqps + m eqps_bar), eqps_bar the average, "
          "both counted up to the residual plastic strain (over-nonlocal, "
          "Vermeer and Brinkgreve 1994). m = 1, the plain average, does not "
          "keep a plastic band from narrowing to a cell (Jirasek and "
          "Rolshoven 2003).");
        prm.declare_entry(
          "rate strengthening",
          "none",
          Patterns::Selection("none|inertial"),
          "none, or inertial: the friction rises with the inertial number of "
          "the plastic flow, I = gamma_dot d / sqrt(p / rho_s) (gamma_dot "
          "the plastic shear rate, p the pressure, d and rho_s the grains' "
          "diameter and density), as tan phi = tan phi_s + (tan phi_d - tan "
          "phi_s) I / (I + I_0), phi_s the friction angle (the mu(I) "
          "rheology of dense granular flow, Jop, Forterre and Pouliquen "
          "2006). Not with softening.");
        prm.declare_entry("dynamic friction angle",
                          "",
                          Patterns::Anything(),
                          "Inertial rate strengthening: phi_d in degrees, the "
                          "friction angle of fast flow (I >> I_0), in "
                          "[friction angle, 90).");
        prm.declare_entry("reference inertial number",
                          "0.279",
                          Patterns::Anything(),
                          "Inertial rate strengthening: I_0 > 0, the inertial "
                          "number at which the friction is half-way from "
                          "phi_s to phi_d (0.279 for glass beads, Jop et al. "
                          "2006).");
        prm.declare_entry("grain diameter",
                          "",
                          Patterns::Anything(),
                          "Inertial rate strengthening: d in m, > 0.");
        prm.declare_entry("grain density",
                          "body",
                          Patterns::Anything(),
                          "Inertial rate strengthening: rho_s in kg/m^3, > 0, "
                          "or 'body' for the body's density.");
      }

      using Strength = FrictionalStrength;

      MohrCoulombFlow(ParameterHandler       &prm,
                      const std::string      &path,
                      const ElasticConstants &constants,
                      const MaterialContext  &context)
        : elasticity(constants)
      {
        peak      = FrictionalStrength::parse(prm, path);
        cutoff    = parse_tension_cutoff(prm, path);
        softening = prm.get("softening") == "linear";
        residual  = peak;
        if (softening)
          {
            // 'peak' (the default) keeps the peak value.
            const auto residual_or_peak = [&](const char  *name,
                                              const double peak_value,
                                              const double upper) {
              return prm.get(name) == "peak"
                       ? std::min(peak_value, upper)
                       : Parse::bounded_double(prm, path, name, 0, upper);
            };
            const double phi_peak = friction_angle_degrees(prm, path);
            residual.c = residual_or_peak("residual cohesion", peak.c, peak.c);
            const double phi =
              residual_or_peak("residual friction angle", phi_peak, phi_peak);
            residual.phi    = radians(phi);
            residual.psi    = radians(residual_or_peak(
              "residual dilation angle",
              Parse::bounded_double(prm, path, "dilation angle", 0, phi_peak),
              phi));
            residual_strain = Parse::bounded_double(
              prm, path, "residual plastic strain", 0, 1e300, true);
            residual_strain *= band_scale(prm, path, context.cell_size);
          }
        parse_nonlocal_softening(prm, path);
        inertial    = parse_rate_strengthening(prm, path, context.density);
        peak_angles = angles_of(peak);
        const Strength end        = strength(residual_strain);
        const Angles   end_angles = angles_of(end);
        peak_surface              = surface(peak, peak_angles);
        residual_surface          = surface(end, end_angles);
        peak_main_plane           = main_plane(peak, peak_angles);
        residual_main_plane       = main_plane(end, end_angles);
      }

      /**
       * The factor from the residual plastic strain as given to the one the
       * grid needs: 1 for 'local', otherwise the band's thickness over the
       * cell size. A shear band of strain softening localises into one
       * cell whatever the grid (measured: benchmarks/slope/README.md), so
       * the slip across it at a given strain shrinks with the cell, and so
       * does the work the softening dissipates; scaling the strain by
       * thickness / h keeps both fixed (Pietruszczak and Mroz 1981; the
       * crack band of Bazant and Oh 1983 for shear).
       */
      static double
      band_scale(const ParameterHandler &prm,
                 const std::string      &path,
                 const double            cell_size)
      {
        const std::string text = prm.get("shear band thickness");
        if (text == "local")
          return 1.;
        double thickness = 0;
        try
          {
            thickness = Parse::bounded_double(
              prm, path, "shear band thickness", 0, 1e300, true);
          }
        catch (const InputError &)
          {
            throw InputError(path + "/shear band thickness",
                             text,
                             "must be 'local' or a thickness in m, > 0");
          }
        if (!(cell_size > 0))
          throw InputError(path + "/shear band thickness",
                           text,
                           "needs a grid (the strain is scaled by the cell "
                           "size); 'local' here");
        return thickness / cell_size;
      }

      /// The nonlocal length and factor of softening; a length needs
      /// softening and excludes the band's scaling, which assumes the band a
      /// cell wide.
      void
      parse_nonlocal_softening(const ParameterHandler &prm,
                               const std::string      &path)
      {
        NonlocalLength length;
        length.parse(prm, path);
        if (!length.enabled())
          return;
        const std::string value = prm.get("nonlocal length");
        if (!softening)
          throw InputError(path + "/nonlocal length",
                           value,
                           "averages the softening's plastic strain: it "
                           "needs softening = linear (or a nonlocal length "
                           "of 0)");
        if (prm.get("shear band thickness") != "local")
          throw InputError(path + "/nonlocal length",
                           value,
                           "cannot be combined with a shear band thickness, "
                           "which scales the strain for a band a cell wide: "
                           "set shear band thickness = local (or nonlocal "
                           "length = 0)");
        nonlocal = length;
        over_nonlocal =
          Parse::bounded_double(prm, path, "nonlocal factor", 1, 1e300);
      }

      /// Inertial rate strengthening's constants; off unless 'inertial'.
      struct InertialFriction
      {
        bool   on = false;
        double mu_s, mu_d, I_0, d, rho_s;
      };

      InertialFriction
      parse_rate_strengthening(const ParameterHandler &prm,
                               const std::string      &path,
                               const double            body_density) const
      {
        InertialFriction inertial;
        if (prm.get("rate strengthening") != "inertial")
          return inertial;
        if (softening)
          throw InputError(path + "/rate strengthening",
                           "inertial",
                           "cannot be combined with softening = linear: "
                           "choose one");
        // An empty entry is a missing one: say what it needs.
        const auto require = [&](const std::string &name,
                                 const std::string &range) {
          if (prm.get(name).empty())
            throw InputError(path + "/" + name,
                             "",
                             "is needed with rate strengthening = inertial: " +
                               range);
        };
        require("dynamic friction angle", "degrees in [friction angle, 90)");
        require("grain diameter", "a diameter in m, > 0");
        const double phi_s = friction_angle_degrees(prm, path);
        inertial.mu_s      = std::tan(peak.phi);
        inertial.mu_d      = std::tan(radians(Parse::bounded_double(
          prm, path, "dynamic friction angle", phi_s, 90, false, true)));
        inertial.d =
          Parse::bounded_double(prm, path, "grain diameter", 0, 1e300, true);
        inertial.I_0 = Parse::bounded_double(
          prm, path, "reference inertial number", 0, 1e300, true);
        inertial.rho_s =
          prm.get("grain density") == "body"
            ? body_density
            : Parse::bounded_double(prm, path, "grain density", 0, 1e300, true);
        inertial.on = true;
        return inertial;
      }

      /// The inertial number per unit plastic strain increment in a step
      /// @p dt at pressure @p p > 0: I = gamma_dot d / sqrt(p / rho_s),
      /// gamma_dot = sqrt(3) x / dt. One number per point and step.
      double
      inertial_number_per_increment(const double dt, const double p) const
      {
        return std::sqrt(3.) / dt * inertial.d / std::sqrt(p / inertial.rho_s);
      }

      /// The friction coefficient tan phi = mu(I) (rate strengthening).
      double
      rate_friction(const double I) const
      {
        // Written with I_0 / I, so that I = 0 and I = infinity (extreme
        // grains) give mu_s and mu_d, not 0 / 0.
        return inertial.mu_s +
               (inertial.mu_d - inertial.mu_s) / (1. + inertial.I_0 / I);
      }

      Strength
      strength(const double eqps) const
      {
        if (!softening)
          return peak;
        const double w = std::min(eqps / residual_strain, 1.);
        return {peak.c + w * (residual.c - peak.c),
                peak.phi + w * (residual.phi - peak.phi),
                peak.psi + w * (residual.psi - peak.psi)};
      }

      /// The admissible set for one strength: its planes with their flow
      /// stresses D n, and the cohesion (the scale of the tolerances).
      struct Surface
      {
        std::array<Plane, 6>                 planes;
        std::array<std::array<double, 3>, 6> Dn;
        unsigned int                         n;
        double                               c;

        /// The largest yield function of sorted stresses @p s.
        double
        max_yield(const std::array<double, 3> &s) const
        {
          double f = -std::numeric_limits<double>::infinity();
          for (unsigned int i = 0; i < n; ++i)
            f = std::max(f, dot(planes[i].a, s) - planes[i].k);
          return f;
        }
      };

      /// The sines and cosines of a strength's friction and dilation
      /// angles.
      struct Angles
      {
        double sin_phi, cos_phi, sin_psi, cos_psi;
      };

      static Angles
      angles_of(const Strength &m)
      {
        return {std::sin(m.phi),
                std::cos(m.phi),
                std::sin(m.psi),
                std::cos(m.psi)};
      }

      /// The angles of the strength at plastic strain eqps + x from @p base,
      /// those at eqps. In one step the angles change by little, and
      /// sin(a + d) = sin a cos d + cos a sin d with the series of sin d
      /// and cos d is exact to round-off for |d| < 1e-3: the softening
      /// return's trial strengths cost no trigonometry. A larger turn (from
      /// the peak to a point's plastic strain) takes sin d and cos d, and
      /// an angle that does not soften (d = 0) nothing.
      Angles
      angles_after(const Angles &base, const double eqps, const double x) const
      {
        const double w0 = std::min(eqps / residual_strain, 1.);
        const double w1 = std::min((eqps + x) / residual_strain, 1.);
        const auto   turn =
          [](const double sin_a, const double cos_a, const double d) {
            if (d == 0)
              return std::make_pair(sin_a, cos_a);
            double sin_d, cos_d;
            if (std::abs(d) < 1e-3)
              {
                const double d2 = d * d;
                sin_d           = d * (1 - d2 / 6 * (1 - d2 / 20));
                cos_d           = 1 - d2 / 2 * (1 - d2 / 12);
              }
            else
              sin_d = std::sin(d), cos_d = std::cos(d);
            return std::make_pair(sin_a * cos_d + cos_a * sin_d,
                                  cos_a * cos_d - sin_a * sin_d);
          };
        const auto [sin_phi, cos_phi] =
          turn(base.sin_phi,
               base.cos_phi,
               (w1 - w0) * (residual.phi - peak.phi));
        const auto [sin_psi, cos_psi] =
          turn(base.sin_psi,
               base.cos_psi,
               (w1 - w0) * (residual.psi - peak.psi));
        return {sin_phi, cos_phi, sin_psi, cos_psi};
      }

      /// The surface for strength @p m: three Mohr-Coulomb planes of the
      /// sorted sextant, then the cutoff planes (if any).
      Surface
      surface(const Strength &m) const
      {
        return surface(m, angles_of(m));
      }

      /// The same, with the angles' sines and cosines @p t given.
      Surface
      surface(const Strength &m, const Angles &angles) const
      {
        Surface      surface;
        auto        &p  = surface.planes;
        const double sf = angles.sin_phi, sp = angles.sin_psi;
        const double k = 2 * m.c * angles.cos_phi;
        // Main plane (s1, s3); edge planes (s1, s2) and (s2, s3).
        const unsigned int pairs[3][2] = {{0, 2}, {0, 1}, {1, 2}};
        for (unsigned int i = 0; i < 3; ++i)
          {
            p[i].a = p[i].n     = {{0, 0, 0}};
            p[i].a[pairs[i][0]] = 1 + sf, p[i].a[pairs[i][1]] = -(1 - sf);
            p[i].n[pairs[i][0]] = 1 + sp, p[i].n[pairs[i][1]] = -(1 - sp);
            p[i].k = k;
          }
        const double t = tension_limit(m, angles);
        surface.n      = 3;
        if (std::isfinite(t))
          {
            for (unsigned int i = 0; i < 3; ++i)
              {
                p[3 + i].a = p[3 + i].n = {{0, 0, 0}};
                p[3 + i].a[i] = p[3 + i].n[i] = 1;
                p[3 + i].k                    = t;
              }
            surface.n = 6;
          }
        // The stress change per unit multiplier of each plane, D n.
        for (unsigned int j = 0; j < surface.n; ++j)
          surface.Dn[j] = elasticity.stress(p[j].n);
        surface.c = m.c;
        return surface;
      }

      /// The surface of a point with plastic strain @p eqps: at the peak
      /// (no plastic strain yet, or no softening) and once fully softened
      /// the ones made at construction, the same numbers without
      /// trigonometry or a copy per point (issue 33: in a softening slope
      /// most points have not yielded, and each paid for its surface);
      /// on the way, made in @p buffer.
      const Surface &
      surface_at(const double eqps, Surface &buffer) const
      {
        if (!softening || eqps <= 0)
          return peak_surface;
        if (eqps >= residual_strain)
          return residual_surface;
        buffer = surface(strength(eqps));
        return buffer;
      }

      /// How far sorted stresses @p t lie outside @p surface or out of
      /// order (<= 0 if admissible and sorted).
      static double
      miss(const std::array<double, 3> &t, const Surface &surface)
      {
        return std::max({t[1] - t[0], t[2] - t[1], surface.max_yield(t)});
      }

      /// The tolerance of the return of sorted stresses @p s to a surface
      /// of cohesion @p c.
      static double
      tolerance_of(const std::array<double, 3> &s, const double c)
      {
        return 1e-12 *
               (std::abs(s[0]) + std::abs(s[1]) + std::abs(s[2]) + c + 1e-300);
      }

      /**
       * The main plane (s1, s3) of one strength alone, with what decides
       * whether a stress on it is admissible: for sorted stresses it lies
       * above both edge planes (f_main - f_(1,2) = (s2 - s3)(1 - sin phi)
       * >= 0, f_main - f_(2,3) = (s1 - s2)(1 + sin phi) >= 0), so a sorted
       * stress on it is admissible if its largest value is below the
       * cutoff or apex. A softening return whose active set stays this
       * plane (nearly always) needs no other plane: issue 33's softening
       * cost came from building the six planes of every trial strength.
       */
      struct MainPlane
      {
        std::array<double, 3> a, Dn;
        double                k, tension, c;

        /// The yield function of sorted stresses @p s: the larger of the
        /// main plane's and the cutoff's (the surface's largest).
        double
        max_yield(const std::array<double, 3> &s) const
        {
          return std::max(dot(a, s) - k, s[0] - tension);
        }
      };

      MainPlane
      main_plane(const Strength &m, const Angles &angles) const
      {
        MainPlane    plane;
        const double sf = angles.sin_phi, sp = angles.sin_psi;
        plane.a       = {{1 + sf, 0, -(1 - sf)}};
        plane.Dn      = elasticity.stress({{1 + sp, 0, -(1 - sp)}});
        plane.k       = 2 * m.c * angles.cos_phi;
        plane.tension = tension_limit(m, angles);
        plane.c       = m.c;
        return plane;
      }

      /// The largest principal stress strength @p m admits: the cutoff, or
      /// the apex c cot phi if that is lower (none without friction).
      double
      tension_limit(const Strength &m, const Angles &angles) const
      {
        return std::min(cutoff,
                        angles.sin_phi > 0
                          ? m.c * angles.cos_phi / angles.sin_phi
                          : std::numeric_limits<double>::infinity());
      }

      /// Return sorted stresses @p s onto the planes of @p surface in the
      /// bit mask @p set, with them all active: false (and @p s as it was)
      /// if their system is singular or a multiplier is negative.
      static bool
      return_on(std::array<double, 3> &s,
                const Surface         &surface,
                const unsigned int     set)
      {
        const auto                 &p  = surface.planes;
        const auto                 &Dn = surface.Dn;
        std::array<unsigned int, 3> active;
        unsigned int                size = 0;
        for (unsigned int i = 0; i < surface.n; ++i)
          if (set & (1u << i))
            active[size++] = i;
        std::array<std::array<double, 3>, 3> A;
        std::array<double, 3>                dgamma;
        for (unsigned int r = 0; r < size; ++r)
          {
            dgamma[r] = dot(p[active[r]].a, s) - p[active[r]].k;
            for (unsigned int c = 0; c < size; ++c)
              A[r][c] = dot(p[active[r]].a, Dn[active[c]]);
          }
        if (!solve(A, dgamma, size))
          return false;
        for (unsigned int r = 0; r < size; ++r)
          if (dgamma[r] < -1e-14)
            return false;
        for (unsigned int r = 0; r < size; ++r)
          for (unsigned int i = 0; i < 3; ++i)
            s[i] -= dgamma[r] * Dn[active[r]][i];
        return true;
      }

      /// Return sorted trial stresses @p s to @p surface (see the class
      /// documentation); @p accepted (if given) is the active set's bit
      /// mask. False if @p s is admissible.
      bool
      return_sorted(std::array<double, 3> &s,
                    const Surface         &surface,
                    unsigned int          *accepted = nullptr) const
      {
        const double tolerance = tolerance_of(s, surface.c);
        if (surface.max_yield(s) <= tolerance)
          return false;
        // Candidate active sets, one plane before two before three, the
        // main plane first. Near phi = 90 degrees the planes almost meet
        // (their apex tends to the origin) and round-off can leave every
        // set outside the tolerance: the set that misses it least is kept
        // for then.
        std::array<double, 3> closest;
        unsigned int          closest_set  = 0;
        double                closest_miss = std::numeric_limits<double>::max();
        for (unsigned int size = 1; size <= 3; ++size)
          for (unsigned int set = 1; set < (1u << surface.n); ++set)
            {
              if (__builtin_popcount(set) != int(size))
                continue;
              std::array<double, 3> t = s;
              if (!return_on(t, surface, set))
                continue;
              const double m = miss(t, surface);
              if (m > tolerance)
                {
                  if (m < closest_miss)
                    closest_miss = m, closest = t, closest_set = set;
                  continue;
                }
              s = t;
              if (accepted != nullptr)
                *accepted = set;
              return true;
            }
        // The pyramid (or prism, phi = 0) always has a valid active set,
        // and with tension planes their corner is one: what is missed is
        // round-off.
        AssertThrow(closest_miss <= 1e4 * tolerance,
                    ExcMessage("Mohr-Coulomb: no active set found for the "
                               "return mapping"));
        s = closest;
        if (accepted != nullptr)
          *accepted = closest_set;
        return true;
      }

      /// The nonlocal length of softening (0: local).
      const NonlocalLength &
      softening_average() const
      {
        return nonlocal;
      }

      /// The over-nonlocal shift of the plastic strain that softens a
      /// point of plastic strain @p eqps whose neighbourhood averages
      /// @p average: the strength softens with (1 - m) eqps + m average =
      /// eqps + m (average - eqps), so a point softens less than its
      /// neighbours where it leads them, which spreads the band.
      double
      nonlocal_shift(const double eqps, const double average) const
      {
        return over_nonlocal * (average - eqps);
      }

      /// The plastic strain over which the strength softens.
      double
      softening_strain() const
      {
        return residual_strain;
      }

      double
      yield_function(const std::array<double, 3> &tau, const double eqps) const
      {
        std::array<double, 3> s = tau;
        std::sort(s.begin(), s.end(), std::greater<double>());
        Surface buffer;
        return surface_at(eqps, buffer).max_yield(s);
      }

      bool
      return_map(std::array<double, 3> &tau,
                 const double           eqps,
                 const double           dt) const
      {
        std::array<unsigned int, 3> order = {{0, 1, 2}};
        std::sort(order.begin(),
                  order.end(),
                  [&](unsigned int i, unsigned int j) {
                    return tau[i] > tau[j];
                  });
        const std::array<double, 3> trial = {
          {tau[order[0]], tau[order[1]], tau[order[2]]}};
        std::array<double, 3> s = trial;
        Surface               buffer;
        unsigned int          set = 0;
        // Without softening left, one return; with it, the consistent
        // return starts from the one with the strength at the step's start.
        if (inertial.on)
          {
            if (!rate_strengthened_return(trial, dt, s))
              return false;
          }
        else if (!softening || eqps >= residual_strain)
          {
            if (!return_sorted(s, surface_at(eqps, buffer)))
              return false;
          }
        else
          {
            // Turned from the peak: no trigonometry for an angle that
            // does not soften (the cohesion alone, or psi = 0 throughout).
            const Angles    base = angles_after(peak_angles, 0, eqps);
            const Strength  m    = strength(eqps);
            const MainPlane start =
              eqps <= 0 ? peak_main_plane : main_plane(m, base);
            // The test of return_sorted, on the plane that decides it.
            if (start.max_yield(s) <= tolerance_of(s, start.c))
              return false;
            if (!main_plane_softening_return(trial, eqps, base, start, s))
              {
                const Surface &full = eqps <= 0
                                        ? peak_surface
                                        : (buffer = surface(m, base), buffer);
                if (!return_sorted(s, full, &set))
                  return false;
                s = consistent_softening_return(trial, eqps, base, s, set);
              }
          }
        for (unsigned int i = 0; i < 3; ++i)
          tau[order[i]] = s[i];
        return true;
      }

      /// One secant step on the plastic strain increment's residual h(x):
      /// from (x0, h0) and (x1, h1) to x1 and the new iterate in x1. False
      /// if it cannot be taken (h flat, or the new x negative).
      static bool
      secant_step(double &x0, double &h0, double &x1, const double h1)
      {
        if (h1 == h0)
          return false;
        const double x2 = x1 - h1 * (x1 - x0) / (h1 - h0);
        if (!(x2 >= 0))
          return false;
        x0 = x1, h0 = h1, x1 = x2;
        return true;
      }

      /// Sorted trial stresses @p trial returned to @p plane.
      std::array<double, 3>
      returned_to(const std::array<double, 3> &trial,
                  const MainPlane             &plane) const
      {
        const double dgamma =
          (dot(plane.a, trial) - plane.k) / dot(plane.a, plane.Dn);
        return {{trial[0] - dgamma * plane.Dn[0],
                 trial[1] - dgamma * plane.Dn[1],
                 trial[2] - dgamma * plane.Dn[2]}};
      }

      /**
       * The consistent softening return (see consistent_softening_return)
       * with the main plane as its active set, by the secant method from
       * the return to @p start, the main plane of the strength at the
       * step's start @p eqps (its angles @p base). True, with @p s, if it
       * converges to a sorted stress within the cutoff of its own
       * strength: that stress then solves the consistent return. False
       * (then the search over active sets decides) if not.
       */
      bool
      main_plane_softening_return(const std::array<double, 3> &trial,
                                  const double                 eqps,
                                  const Angles                &base,
                                  const MainPlane             &start,
                                  std::array<double, 3>       &s) const
      {
        std::array<double, 3> t  = returned_to(trial, start);
        double                x0 = 0;
        double h0 = elasticity.equivalent_plastic_strain(trial, t);
        double x1 = h0, h1 = 0;
        for (unsigned int it = 0; it < 20; ++it)
          {
            const MainPlane plane =
              eqps + x1 >= residual_strain
                ? residual_main_plane
                : main_plane(strength(eqps + x1), angles_after(base, eqps, x1));
            if (!(dot(plane.a, trial) - plane.k >= 0))
              return false;
            t  = returned_to(trial, plane);
            h1 = elasticity.equivalent_plastic_strain(trial, t) - x1;
            if (std::abs(h1) <= 1e-10 * x1 + 1e-300)
              {
                if (std::max({t[1] - t[0], t[2] - t[1], t[0] - plane.tension}) >
                    tolerance_of(t, plane.c))
                  return false;
                s = t;
                return true;
              }
            if (!secant_step(x0, h0, x1, h1))
              return false;
          }
        return false;
      }

      /**
       * The return whose strength is that of its own end-of-step plastic
       * strain (see the class documentation), from @p s, the return with
       * the strength at the step's start @p eqps (its angles @p base) on
       * the planes @p active_set.
       *
       * The plastic strain increment x solves h(x) = g(x) - x = 0, g(x) the
       * increment of the return with the strength at eqps + x. A step
       * softens the strength little, so the active set of the return at
       * the step's start is almost always the set at its end, and on a
       * fixed set g is smooth: the secant method from x = 0 and x = g(0)
       * converges in two or three returns on that set alone, each a small
       * linear solve without the search over sets (issue 33: the bracketing
       * search took seven full returns per plastic point, and softening
       * cost 7x the plain model). If the end stress is not admissible on
       * its surface, or the secant does not converge, the bracketing
       * search decides.
       */
      std::array<double, 3>
      consistent_softening_return(const std::array<double, 3> &trial,
                                  const double                 eqps,
                                  const Angles                &base,
                                  const std::array<double, 3> &s,
                                  const unsigned int           active_set) const
      {
        Surface               buffer;
        std::array<double, 3> t  = s;
        double                x0 = 0;
        double       h0 = elasticity.equivalent_plastic_strain(trial, s);
        double       x1 = h0, h1 = 0;
        unsigned int set      = active_set;
        bool         switched = false;
        for (unsigned int it = 0; it < 20; ++it)
          {
            const Surface &trial_surface =
              eqps + x1 >= residual_strain
                ? residual_surface
                : (buffer =
                     surface(strength(eqps + x1), angles_after(base, eqps, x1)),
                   buffer);
            t = trial;
            if (!return_on(t, trial_surface, set))
              break;
            h1 = elasticity.equivalent_plastic_strain(trial, t) - x1;
            if (std::abs(h1) <= 1e-10 * x1 + 1e-300)
              {
                if (miss(t, trial_surface) <= tolerance_of(t, trial_surface.c))
                  return t;
                // The set changed in the step (an edge reached): go on
                // from here with the set of the full return, once.
                if (switched)
                  break;
                switched = true;
                t        = trial;
                return_sorted(t, trial_surface, &set);
                h1 = elasticity.equivalent_plastic_strain(trial, t) - x1;
                if (std::abs(h1) <= 1e-10 * x1 + 1e-300)
                  return t;
              }
            if (!secant_step(x0, h0, x1, h1))
              break;
          }
        return bracketed_softening_return(trial, eqps);
      }

      /// The root of @p h on [a, b], h(a) = fa > 0 > fb = h(b), by the
      /// Illinois (regula falsi) method, to |h| <= @p relative (x + @p
      /// absolute).
      template <typename Function>
      static double
      illinois_root(const Function &h,
                    double          a,
                    double          fa,
                    double          b,
                    double          fb,
                    const double    relative,
                    const double    absolute)
      {
        int    side = 0;
        double x    = a;
        for (unsigned int it = 0; it < 100; ++it)
          {
            x              = (a * fb - b * fa) / (fb - fa);
            const double f = h(x);
            if (std::abs(f) <= relative * (absolute + x) || b - a < 1e-15)
              break;
            if (f * fb > 0)
              {
                b = x, fb = f;
                if (side == -1)
                  fa *= 0.5;
                side = -1;
              }
            else
              {
                a = x, fa = f;
                if (side == 1)
                  fb *= 0.5;
                side = 1;
              }
          }
        return x;
      }

      /// The consistent return by the Illinois (regula falsi) method on
      /// [0, g(residual)], which brackets the root because g grows as the
      /// material softens: whatever the active set does.
      std::array<double, 3>
      bracketed_softening_return(const std::array<double, 3> &trial,
                                 const double                 eqps) const
      {
        auto returned = [&](const double x) {
          std::array<double, 3> s = trial;
          Surface               buffer;
          return_sorted(s, surface_at(eqps + x, buffer));
          return s;
        };
        auto h = [&](const double x) {
          return elasticity.equivalent_plastic_strain(trial, returned(x)) - x;
        };
        const double fa = h(0);
        const double b  = std::max(residual_strain - eqps, 0.) +
                         elasticity.equivalent_plastic_strain(
                           trial, returned(residual_strain - eqps));
        const double fb = h(b);
        if (fa <= 0)
          return returned(0);
        if (fb >= 0)
          return returned(b);
        return returned(illinois_root(h, 0, fa, b, fb, 1e-14, 1e-6));
      }

      /**
       * The return of sorted trial stresses @p trial with inertial rate
       * strengthening in a step @p dt, into @p s; false if the trial is
       * admissible at the static friction. The plastic strain increment x
       * solves h(x) = g(x) - x = 0 on [0, g(0)] (see the class
       * documentation), by the Illinois method: first with the main plane
       * alone as the active set, where each g(x) is a closed form; if that
       * stress is not sorted or crosses the cutoff, with the full return.
       */
      bool
      rate_strengthened_return(const std::array<double, 3> &trial,
                               const double                 dt,
                               std::array<double, 3>       &s) const
      {
        // The test of return_sorted, on the plane that decides it (as in
        // return_map's softening branch): no full return for the decision.
        if (peak_main_plane.max_yield(trial) <= tolerance_of(trial, peak.c))
          return false;
        // No pressure (the apex, parted points) or no step: no rate.
        const double p = -(trial[0] + trial[1] + trial[2]) / 3.;
        if (!(p > 0) || !(dt > 0))
          {
            s = trial;
            return_sorted(s, peak_surface);
            return true;
          }
        const double I_per_x = inertial_number_per_increment(dt, p);
        // The main plane of friction mu(I(x)): its flow (psi), cohesion
        // and Dn are the peak's; sin and cos of phi = atan mu are
        // algebraic, so an evaluation of h costs no trigonometry.
        const auto plane_at = [&](const double x) {
          const double mu      = rate_friction(I_per_x * x);
          const double cos_phi = 1. / std::sqrt(1. + mu * mu);
          MainPlane    plane   = peak_main_plane;
          plane.a              = {{1 + mu * cos_phi, 0, -(1 - mu * cos_phi)}};
          plane.k              = 2 * peak.c * cos_phi;
          plane.tension = tension_limit(peak, {mu * cos_phi, cos_phi, 0., 1.});
          return plane;
        };
        const auto on_main_plane = [&](const double x) {
          const MainPlane plane = plane_at(x);
          return dot(plane.a, trial) > plane.k ? returned_to(trial, plane)
                                               : trial;
        };
        const auto on_surface = [&](const double x) {
          Strength m              = peak;
          m.phi                   = std::atan(rate_friction(I_per_x * x));
          std::array<double, 3> t = trial;
          return_sorted(t, surface(m));
          return t;
        };
        // The root of h for the return @p returned; g falls with x, so
        // g(0) bounds it.
        const auto increment = [&](const auto &returned) {
          const auto h = [&](const double x) {
            return elasticity.equivalent_plastic_strain(trial, returned(x)) - x;
          };
          const double g0 = h(0);
          if (!(g0 > 0))
            return 0.;
          const double fb = h(g0);
          return fb >= 0 ? g0 : illinois_root(h, 0, g0, g0, fb, 1e-10, 0);
        };
        const double x       = increment(on_main_plane);
        const auto   t       = on_main_plane(x);
        const double tension = plane_at(x).tension;
        if (x > 0 && std::max({t[1] - t[0], t[2] - t[1], t[0] - tension}) <=
                       tolerance_of(t, peak.c))
          s = t;
        else
          s = on_surface(increment(on_surface));
        return true;
      }

      /// The apex (or the cutoffs' corner) is at zero stress, at the peak
      /// or once softened.
      bool
      can_part() const
      {
        const auto tip_at_zero = [this](const Strength &m) {
          return cutoff == 0 || (m.c == 0 && std::sin(m.phi) > 0);
        };
        return tip_at_zero(peak) || (softening && tip_at_zero(residual));
      }

      const PrincipalElasticity elasticity;
      Strength                  peak, residual;
      Angles                    peak_angles;
      Surface                   peak_surface, residual_surface;
      MainPlane                 peak_main_plane, residual_main_plane;
      double                    cutoff;
      bool                      softening;
      double                    residual_strain = 1;
      NonlocalLength            nonlocal;
      double                    over_nonlocal = 1;
      InertialFriction          inertial;
    };
  } // namespace LogStrain


  MPM_LOG_STRAIN_ENTRY(mohr_coulomb, MohrCoulombFlow, "Mohr-Coulomb")
} // namespace mpm
