#include <deal.II/base/symmetric_tensor.h>

#include <mpm/material.h>
#include <mpm/parameters.h>

#include <cmath>

namespace mpm
{
  namespace
  {
    /**
     * The loop every pointwise model shares: visit the points of one body
     * and apply Law::update_point, inlined, to each.
     */
    template <int dim, typename Law>
    class PointwiseMaterial : public Material<dim>
    {
    public:
      void
      update_stresses(Particles::ParticleHandler<dim> &particles,
                      const FieldLayout               &layout,
                      const unsigned int               body,
                      const double                     dt) const override
      {
        const Law   &law = static_cast<const Law &>(*this);
        const double id  = body;
        for (auto &particle : particles)
          {
            double *p = particle.get_properties().data();
            if (p[layout.body] == id)
              law.update_point(p, layout, dt);
          }
      }
    };


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


    /// Lame constants from E and nu, read and checked in one place.
    struct ElasticConstants
    {
      ElasticConstants(ParameterHandler &prm, const std::string &path)
      {
        const double E = Parse::bounded_double(
          prm, path, "Young's modulus", 0., 1e300, true, false);
        const double nu = Parse::bounded_double(
          prm, path, "Poisson's ratio", -1., 0.5, true, true);
        lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
        mu     = E / (2. * (1. + nu));
      }

      static void
      declare(ParameterHandler &prm)
      {
        prm.declare_entry("Young's modulus",
                          "1e6",
                          Patterns::Anything(),
                          "Young's modulus E in Pa, > 0.");
        prm.declare_entry("Poisson's ratio",
                          "0.3",
                          Patterns::Anything(),
                          "Poisson's ratio, in (-1, 0.5) for these "
                          "compressible models. In 2D the models are plane "
                          "strain.");
      }

      double lambda;
      double mu;
    };


    /**
     * Small-strain isotropic elasticity in rate form,
     *   sigma_{n+1} = Q sigma_n Q^T + dt (lambda tr(D) I + 2 mu D),
     * with the Hughes-Winget rotation Q = (I - dt W/2)^{-1} (I + dt W/2)
     * built from the spin W. Q is exactly orthogonal, so a rigid rotation
     * rotates the stress and creates none: the update is objective.
     */
    template <int dim>
    class LinearElastic : public PointwiseMaterial<dim, LinearElastic<dim>>
    {
    public:
      LinearElastic(ParameterHandler &prm, const std::string &path)
        : c(prm, path)
      {
      }

      bool
      needs_deformation_gradient() const override
      {
        return false;
      }

      double
      p_wave_modulus() const override
      {
        return c.lambda + 2. * c.mu;
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
        sigma += dt * (c.lambda * trace(D) * unit_symmetric_tensor<dim>() +
                       2. * c.mu * D);
        Fields::store(sigma, p + layout.stress);
      }

      /// Complementary energy sigma : C^{-1} : sigma / 2 times volume.
      double
      strain_energy(const double *p, const FieldLayout &layout) const override
      {
        const SymmetricTensor<2, dim> s =
          Fields::symmetric<dim>(p + layout.stress);
        const double tr = trace(s);
        const double w =
          (s * s - c.lambda / (dim * c.lambda + 2. * c.mu) * tr * tr) /
          (4. * c.mu);
        return w * p[layout.volume];
      }

    private:
      const ElasticConstants c;
    };


    /**
     * Compressible neo-Hookean solid,
     *   sigma = mu/J (b - I) + lambda ln(J)/J I,   b = F F^T,
     * with stored energy psi = mu/2 (tr C - dim) - mu ln J + lambda/2 ln^2 J
     * per unit reference volume.
     */
    template <int dim>
    class NeoHookean : public PointwiseMaterial<dim, NeoHookean<dim>>
    {
    public:
      NeoHookean(ParameterHandler &prm, const std::string &path)
        : c(prm, path)
      {
      }

      bool
      needs_deformation_gradient() const override
      {
        return true;
      }

      double
      p_wave_modulus() const override
      {
        return c.lambda + 2. * c.mu;
      }

      inline void
      update_point(double *p, const FieldLayout &layout, const double) const
      {
        const Tensor<2, dim> F =
          Fields::tensor<dim>(p + layout.deformation_gradient);
        const double J = determinant(F);
        // J <= 0 is caught by the integrator's kinematic update before this.
        const SymmetricTensor<2, dim> b = symmetrize(F * transpose(F));
        const SymmetricTensor<2, dim> sigma =
          (c.mu / J) * (b - unit_symmetric_tensor<dim>()) +
          (c.lambda * std::log(J) / J) * unit_symmetric_tensor<dim>();
        Fields::store(sigma, p + layout.stress);
      }

      double
      strain_energy(const double *p, const FieldLayout &layout) const override
      {
        const Tensor<2, dim> F =
          Fields::tensor<dim>(p + layout.deformation_gradient);
        const double J   = determinant(F);
        const double lnJ = std::log(J);
        const double psi = 0.5 * c.mu * (scalar_product(F, F) - dim) -
                           c.mu * lnJ + 0.5 * c.lambda * lnJ * lnJ;
        return psi * p[layout.volume] / J;
      }

    private:
      const ElasticConstants c;
    };


    template <int dim>
    using Creator = std::unique_ptr<Material<dim>> (*)(ParameterHandler &,
                                                       const std::string &);

    template <int dim, template <int> class Model>
    std::unique_ptr<Material<dim>>
    make(ParameterHandler &prm, const std::string &path)
    {
      return std::make_unique<Model<dim>>(prm, path);
    }

    struct Entry
    {
      const char *name;
      void (*declare)(ParameterHandler &);
      Creator<1> create_1d;
      Creator<2> create_2d;
      Creator<3> create_3d;
    };

    /// The registry itself: one line per model.
    const Entry registry[] = {
      {"linear elastic",
       &ElasticConstants::declare,
       &make<1, LinearElastic>,
       &make<2, LinearElastic>,
       &make<3, LinearElastic>},
      {"neo-Hookean",
       &ElasticConstants::declare,
       &make<1, NeoHookean>,
       &make<2, NeoHookean>,
       &make<3, NeoHookean>},
    };
  } // namespace


  namespace MaterialRegistry
  {
    std::string
    names()
    {
      std::string s;
      for (const auto &e : registry)
        s += (s.empty() ? "" : "|") + std::string(e.name);
      return s;
    }


    void
    declare_parameters(ParameterHandler &prm)
    {
      for (const auto &e : registry)
        {
          prm.enter_subsection(e.name);
          e.declare(prm);
          prm.leave_subsection();
        }
    }


    template <int dim>
    std::unique_ptr<Material<dim>>
    create(const std::string &name,
           ParameterHandler  &prm,
           const std::string &path)
    {
      for (const auto &e : registry)
        if (name == e.name)
          {
            prm.enter_subsection(name);
            std::unique_ptr<Material<dim>> m;
            if constexpr (dim == 1)
              m = e.create_1d(prm, path + "/" + name);
            else if constexpr (dim == 2)
              m = e.create_2d(prm, path + "/" + name);
            else
              m = e.create_3d(prm, path + "/" + name);
            prm.leave_subsection();
            return m;
          }
      throw InputError(path + "/material",
                       name,
                       "known materials are " + names());
    }


    template std::unique_ptr<Material<1>>
    create<1>(const std::string &, ParameterHandler &, const std::string &);
    template std::unique_ptr<Material<2>>
    create<2>(const std::string &, ParameterHandler &, const std::string &);
    template std::unique_ptr<Material<3>>
    create<3>(const std::string &, ParameterHandler &, const std::string &);
  } // namespace MaterialRegistry
} // namespace mpm
