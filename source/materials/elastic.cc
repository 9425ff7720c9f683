// The elastic models that work on the velocity gradient or on F directly:
// small-strain elasticity in rate form, and the neo-Hookean solid.
#include <mpm/materials/pointwise.h>

#include <cmath>

namespace mpm
{
  namespace
  {
    /**
     * The Hughes-Winget incremental rotation Q = (I - A)^{-1} (I + A) for
     * the half-step spin A = dt/2 (L - L^T)/2, in closed form (the Cayley
     * transform of a skew tensor): Q = I + 2/(1 + |a|^2) (A + A^2), with
     * |a|^2 = A:A/2. Exactly orthogonal for any step.
     */
    template <int dim>
    inline Tensor<2, dim>
    hughes_winget_rotation(const Tensor<2, dim> &L, const double dt)
    {
      const Tensor<2, dim> A  = (0.25 * dt) * (L - transpose(L));
      const double         a2 = 0.5 * scalar_product(A, A);
      Tensor<2, dim>       Q  = (2. / (1. + a2)) * (A + A * A);
      for (unsigned int d = 0; d < dim; ++d)
        Q[d][d] += 1.;
      return Q;
    }


    /// Q s Q^T for a symmetric s.
    template <int dim>
    inline SymmetricTensor<2, dim>
    rotate(const SymmetricTensor<2, dim> &s, const Tensor<2, dim> &Q)
    {
      const Tensor<2, dim>    QS = Q * s;
      SymmetricTensor<2, dim> r;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          {
            double v = 0;
            for (unsigned int k = 0; k < dim; ++k)
              v += QS[i][k] * Q[j][k];
            r[i][j] = v;
          }
      return r;
    }


    /**
     * Small-strain isotropic elasticity in rate form,
     *   sigma_{n+1} = Q sigma_n Q^T + lambda tr(e) I + 2 mu e,
     * e = dt D with its trace ln det(I + dt D) (volumetric_correction()),
     * with the Hughes-Winget rotation Q = (I - dt W/2)^{-1} (I + dt W/2)
     * built from the spin W. Q is exactly orthogonal, so a rigid rotation
     * rotates the stress and creates none: the update is objective.
     */
    template <int dim>
    class LinearElastic
      : public IsotropicPointwiseMaterial<dim, LinearElastic<dim>>
    {
    public:
      using IsotropicPointwiseMaterial<dim, LinearElastic<dim>>::
        IsotropicPointwiseMaterial;

      void
      request_fields(FieldRequests &) const override
      {
      }

      /**
       * The step's strain increment is dt D with its trace replaced by
       * ln det(I + dt D); this is the change of each diagonal component,
       * (ln det(I + dt D) - dt tr D) / dim. The volume change is then
       * integrated exactly, so the pressure is a function of the volume
       * alone and cannot drift when a point's volume goes back and forth. It
       * did with dt tr D, whose error ~ (dJ - 1)^2 always has one sign:
       * under F-bar, points that cross cells take the cell's J in jumps,
       * and a settling block at nu = 0.499 gained energy until it flew
       * apart. (D, not L: a spin changes no volume.) Scalars only: as a
       * SymmetricTensor expression it cost the stress update a third more.
       */
      static double
      volumetric_correction(const SymmetricTensor<2, dim> &D, const double dt)
      {
        // det(I + e) - 1 = I1 + I2 + I3 by the invariants of e = dt D.
        const double I1 = dt * trace(D);
        double       I2 = 0.5 * I1 * I1;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            I2 -= 0.5 * dt * dt * D[i][j] * D[i][j];
        const double I3 = dim == 3 ? dt * dt * dt * determinant(D) : 0.;
        const double x  = I1 + I2 + I3;
        return x > -1 ? (log1p(x) - I1) / dim : 0.;
      }

      /**
       * ln(1 + x). A step's volume change is small (|x| < 1e-3 for CFL
       * steps in all but impacts), where five terms of the series are exact
       * to round-off (the first left out is x^6 / 6 < 2e-16 |x|) and cost a
       * fraction of std::log1p.
       */
      static double
      log1p(const double x)
      {
        if (__builtin_expect(std::abs(x) < 1e-3, 1))
          return x * (1. - x * (0.5 - x * (1. / 3. - x * (0.25 - x * 0.2))));
        return large_log1p(x);
      }

      /// Out of line, so that the common path stays small enough to inline.
      [[gnu::noinline, gnu::cold]] static double
      large_log1p(const double x)
      {
        return std::log1p(x);
      }

      inline void
      update_point(double *p, const FieldLayout &layout, const double dt) const
      {
        const Tensor<2, dim> L =
          Fields::tensor<dim>(p + layout.velocity_gradient);
        const SymmetricTensor<2, dim> D = symmetrize(L);
        SymmetricTensor<2, dim>       sigma =
          Fields::symmetric<dim>(p + layout.stress);
        if constexpr (dim > 1)
          sigma = rotate(sigma, hughes_winget_rotation(L, dt));
        sigma += dt * (this->constants.lambda * trace(D) *
                         unit_symmetric_tensor<dim>() +
                       2. * this->constants.mu * D);
        const double pressure_change =
          (dim * this->constants.lambda + 2. * this->constants.mu) *
          volumetric_correction(D, dt);
        for (unsigned int d = 0; d < dim; ++d)
          sigma[d][d] += pressure_change;
        Fields::store(sigma, p + layout.stress);
      }

      /// Complementary energy sigma : C^{-1} : sigma / 2 times volume, of
      /// the in-plane stress (the energy of the plane-strain state).
      double
      strain_energy(const double *p, const FieldLayout &layout) const override
      {
        const SymmetricTensor<2, dim> s =
          Fields::symmetric<dim>(p + layout.stress);
        const double tr = trace(s);
        const double w =
          (s * s - this->constants.lambda /
                     (dim * this->constants.lambda + 2. * this->constants.mu) *
                     tr * tr) /
          (4. * this->constants.mu);
        return w * p[layout.volume];
      }

      /// Out of plane, the strain rate vanishes, so the stress there is
      /// what the in-plane stress implies: nu (s_xx + s_yy) in plane
      /// strain, nu / (1 - nu) s_xx in uniaxial strain (for a point that
      /// started from such a state).
      SymmetricTensor<2, 3>
      cauchy_stress_3d(const double      *p,
                       const FieldLayout &layout) const override
      {
        const SymmetricTensor<2, dim> s =
          Fields::symmetric<dim>(p + layout.stress);
        SymmetricTensor<2, 3> full;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            full[i][j] = s[i][j];
        const double ratio =
          this->constants.lambda /
          (dim * this->constants.lambda + 2. * this->constants.mu);
        for (unsigned int d = dim; d < 3; ++d)
          full[d][d] = ratio * trace(s);
        return full;
      }

    private:
    };


    /**
     * Compressible neo-Hookean solid,
     *   sigma = mu/J (b - I) + lambda ln(J)/J I,   b = F F^T,
     * with stored energy psi = mu/2 (tr C - dim) - mu ln J + lambda/2 ln^2 J
     * per unit reference volume.
     */
    template <int dim>
    class NeoHookean : public IsotropicPointwiseMaterial<dim, NeoHookean<dim>>
    {
    public:
      using IsotropicPointwiseMaterial<dim, NeoHookean<dim>>::
        IsotropicPointwiseMaterial;

      void
      request_fields(FieldRequests &requests) const override
      {
        requests.deformation_gradient = true;
      }

      /// Its stress follows from F: a stress it starts with would need the
      /// F that produces it.
      bool
      accepts_initial_stress() const override
      {
        return false;
      }

      bool
      stiffness_is_kirchhoff() const override
      {
        return true;
      }

      inline void
      update_point(double *p, const FieldLayout &layout, const double) const
      {
        Fields::store(stress(p, layout), p + layout.stress);
      }

      double
      strain_energy(const double *p, const FieldLayout &layout) const override
      {
        const Tensor<2, dim> F =
          Fields::tensor<dim>(p + layout.deformation_gradient);
        const double J   = determinant(F);
        const double lnJ = std::log(J);
        const double psi =
          0.5 * this->constants.mu * (scalar_product(F, F) - dim) -
          this->constants.mu * lnJ + 0.5 * this->constants.lambda * lnJ * lnJ;
        return psi * p[layout.volume] / J;
      }

      SymmetricTensor<2, 3>
      cauchy_stress_3d(const double      *p,
                       const FieldLayout &layout) const override
      {
        const SymmetricTensor<2, dim> in_plane = stress(p, layout);
        SymmetricTensor<2, 3>         sigma;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            sigma[i][j] = in_plane[i][j];
        // Out of plane b = 1, so only the volumetric term remains.
        const double J =
          determinant(Fields::tensor<dim>(p + layout.deformation_gradient));
        for (unsigned int d = dim; d < 3; ++d)
          sigma[d][d] = this->constants.lambda * std::log(J) / J;
        return sigma;
      }

    private:
      /// The in-plane stress, inlined into the per-point update.
      inline SymmetricTensor<2, dim>
      stress(const double *p, const FieldLayout &layout) const
      {
        const Tensor<2, dim> F =
          Fields::tensor<dim>(p + layout.deformation_gradient);
        const double J = determinant(F);
        // J <= 0 is caught by the integrator's kinematic update before this.
        const SymmetricTensor<2, dim> b = symmetrize(F * transpose(F));
        return (this->constants.mu / J) * (b - unit_symmetric_tensor<dim>()) +
               (this->constants.lambda * std::log(J) / J) *
                 unit_symmetric_tensor<dim>();
      }
    };
  } // namespace


  namespace Elastic
  {
    MaterialEntry
    linear_elastic()
    {
      return material_entry<LinearElastic>("linear elastic");
    }

    MaterialEntry
    neo_hookean()
    {
      return material_entry<NeoHookean>("neo-Hookean");
    }
  } // namespace Elastic
} // namespace mpm
