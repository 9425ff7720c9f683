#ifndef mpm_materials_log_strain_h
#define mpm_materials_log_strain_h

// The finite-strain framework of the elastoplastic models (cl-mpm's, seed
// 002; Simo 1992): each point stores its elastic left Cauchy-Green tensor
// b_e. A step pushes it forward with the step's deformation increment,
//   b_e,trial = dF b_e,n dF^T,   dF = I + dt L,
// takes the logarithmic elastic strain eps_e = 1/2 ln b_e,trial, and maps
// it to Kirchhoff stress with small-strain elasticity, tau = D^e : eps_e.
// A plastic model corrects tau by a return mapping in principal space (the
// eigenvectors do not change, for isotropic models); then
//   b_e,n+1 = exp(2 eps_e,n+1),   sigma = tau / J.
// So a small-strain model runs at large deformation unchanged, exactly
// objective, with no stress rate.
//
// Included by the model sources only.

#include <deal.II/base/symmetric_tensor.h>

#include <mpm/materials/damage.h>
#include <mpm/materials/nonlocal_average.h>
#include <mpm/materials/pointwise.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace mpm
{
  namespace LogStrain
  {
    /// Principal values and orthonormal principal directions.
    struct Spectral
    {
      std::array<double, 3>       values;
      std::array<Tensor<1, 3>, 3> vectors;
    };


    /**
     * Eigen-decomposition of a symmetric tensor whose out-of-plane part is
     * diagonal (a point in 1D or 2D: those directions are principal).
     * - 3D: deal.II's QL method with implicit shifts. Measured
     *   (benchmarks/eigensolver): ~1e-15 error in ln(b) also for repeated
     *   and nearly repeated eigenvalues, at the cost of Eigen's iterative
     *   solver; deal.II's default 'hybrid' loses 1e-7 at a gap of 1e-5
     *   and Eigen's closed form 1e-9 at equal eigenvalues.
     * - 2D: the in-plane 2x2 block in closed form, without trigonometry
     *   and without cancellation (the eigenvector is formed from the larger
     *   of two non-negative expressions), exactly orthonormal.
     */
    template <int dim>
    inline Spectral
    decompose(const SymmetricTensor<2, 3> &b)
    {
      Spectral s;
      if constexpr (dim == 3)
        {
          const auto pairs =
            eigenvectors(b,
                         SymmetricTensorEigenvectorMethod::ql_implicit_shifts);
          for (unsigned int i = 0; i < 3; ++i)
            {
              s.values[i]  = pairs[i].first;
              s.vectors[i] = pairs[i].second;
            }
        }
      else
        {
          for (unsigned int i = 0; i < 3; ++i)
            {
              s.values[i]     = b[i][i];
              s.vectors[i]    = Tensor<1, 3>();
              s.vectors[i][i] = 1.;
            }
          if constexpr (dim == 2)
            {
              const double half_difference = 0.5 * (b[0][0] - b[1][1]);
              const double mean            = 0.5 * (b[0][0] + b[1][1]);
              const double c               = b[0][1];
              // sqrt rather than hypot (measured 6% of a plastic step):
              // b is near I, far from overflow.
              const double r =
                std::sqrt(half_difference * half_difference + c * c);
              if (r > 0)
                {
                  s.values[0] = mean + r;
                  s.values[1] = mean - r;
                  // (b - lambda_2 I) has the first eigenvector as its
                  // columns' direction: (hd + r, c) or (c, r - hd), both
                  // free of cancellation on their side of hd = 0.
                  double x = half_difference + r, y = c;
                  if (half_difference < 0)
                    x = c, y = r - half_difference;
                  const double inverse_norm = 1. / std::sqrt(x * x + y * y);
                  x *= inverse_norm, y *= inverse_norm;
                  s.vectors[0][0] = x, s.vectors[0][1] = y;
                  s.vectors[1][0] = -y, s.vectors[1][1] = x;
                }
            }
        }
      return s;
    }


    /// sum_i values[i] n_i (x) n_i with the directions of @p s.
    template <int dim>
    inline SymmetricTensor<2, 3>
    compose(const std::array<double, 3> &values, const Spectral &s)
    {
      SymmetricTensor<2, 3> t;
      if constexpr (dim == 3)
        {
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = i; j < 3; ++j)
                t[i][j] += values[k] * s.vectors[k][i] * s.vectors[k][j];
        }
      else
        {
          // The in-plane block from the first two directions; the rest is
          // diagonal.
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = i; j < dim; ++j)
                t[i][j] += values[k] * s.vectors[k][i] * s.vectors[k][j];
          for (unsigned int d = dim; d < 3; ++d)
            t[d][d] = values[d];
        }
      return t;
    }


    /// 1/2 ln of the principal values of @p s: the principal log strains of
    /// a left Cauchy-Green tensor.
    inline std::array<double, 3>
    half_log(const Spectral &s)
    {
      return {{0.5 * std::log(s.values[0]),
               0.5 * std::log(s.values[1]),
               0.5 * std::log(s.values[2])}};
    }


    /// The left Cauchy-Green tensor with principal log strains @p eps on
    /// the directions of @p s: sum exp(2 eps_i) n_i (x) n_i.
    template <int dim>
    inline SymmetricTensor<2, 3>
    stretch_tensor(const std::array<double, 3> &eps, const Spectral &s)
    {
      return compose<dim>(
        {{std::exp(2. * eps[0]), std::exp(2. * eps[1]), std::exp(2. * eps[2])}},
        s);
    }


    /// The step's deformation increment I + dt L, embedded in 3D (the
    /// out-of-plane stretches are 1).
    template <int dim>
    inline Tensor<2, 3>
    increment(const Tensor<2, dim> &L, const double dt)
    {
      Tensor<2, 3> dF;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          dF[i][j] = dt * L[i][j];
      for (unsigned int d = 0; d < 3; ++d)
        dF[d][d] += 1.;
      return dF;
    }


    /// dF b dF^T; for a point in 1D or 2D only the in-plane block changes.
    template <int dim = 3>
    inline SymmetricTensor<2, 3>
    push_forward(const SymmetricTensor<2, 3> &b, const Tensor<2, 3> &dF)
    {
      if constexpr (dim < 3)
        {
          SymmetricTensor<2, 3> r = b;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              {
                double v = 0;
                for (unsigned int k = 0; k < dim; ++k)
                  for (unsigned int l = 0; l < dim; ++l)
                    v += dF[i][k] * b[k][l] * dF[j][l];
                r[i][j] = v;
              }
          return r;
        }
      const Tensor<2, 3>    dFb = dF * b;
      SymmetricTensor<2, 3> r;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          r[i][j] =
            dFb[i][0] * dF[j][0] + dFb[i][1] * dF[j][1] + dFb[i][2] * dF[j][2];
      return r;
    }


    /// Mean of principal stresses and the norm |s| of their deviator.
    inline std::pair<double, double>
    mean_and_deviator_norm(const std::array<double, 3> &tau)
    {
      const double p  = (tau[0] + tau[1] + tau[2]) / 3.;
      const double s0 = tau[0] - p, s1 = tau[1] - p, s2 = tau[2] - p;
      return {p, std::sqrt(s0 * s0 + s1 * s1 + s2 * s2)};
    }


    /// Isotropic elasticity between principal log strains and principal
    /// Kirchhoff stresses.
    struct PrincipalElasticity
    {
      explicit PrincipalElasticity(const ElasticConstants &c)
        : lambda(c.lambda)
        , mu(c.mu)
      {
      }

      std::array<double, 3>
      stress(const std::array<double, 3> &eps) const
      {
        const double v = lambda * (eps[0] + eps[1] + eps[2]);
        return {
          {v + 2 * mu * eps[0], v + 2 * mu * eps[1], v + 2 * mu * eps[2]}};
      }

      std::array<double, 3>
      strain(const std::array<double, 3> &tau) const
      {
        const double v =
          lambda / (3 * lambda + 2 * mu) * (tau[0] + tau[1] + tau[2]);
        return {{(tau[0] - v) / (2 * mu),
                 (tau[1] - v) / (2 * mu),
                 (tau[2] - v) / (2 * mu)}};
      }

      /// Stored energy per unit reference volume.
      double
      energy(const std::array<double, 3> &eps) const
      {
        const double tr = eps[0] + eps[1] + eps[2];
        return 0.5 * lambda * tr * tr +
               mu * (eps[0] * eps[0] + eps[1] * eps[1] + eps[2] * eps[2]);
      }

      /**
       * The equivalent plastic strain of a return from @p trial to @p tau:
       * sqrt(2/3) |d eps_p| with d eps_p = D^-1 (trial - tau) (for J2
       * plasticity this is the plastic multiplier itself). One definition
       * for every model.
       */
      double
      equivalent_plastic_strain(const std::array<double, 3> &trial,
                                const std::array<double, 3> &tau) const
      {
        const auto d =
          strain({{trial[0] - tau[0], trial[1] - tau[1], trial[2] - tau[2]}});
        return std::sqrt(2. / 3. * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
      }

      double lambda, mu;
    };


    /// A Flow with a relax() member is viscous (see Model).
    template <typename Flow, typename = void>
    struct IsViscous : std::false_type
    {
    };
    template <typename Flow>
    struct IsViscous<Flow, std::void_t<decltype(&Flow::template relax<3>)>>
      : std::true_type
    {
    };


    /// A Flow with a can_part() member may return to zero stress (see Model).
    template <typename Flow, typename = void>
    struct CanPart : std::false_type
    {
    };
    template <typename Flow>
    struct CanPart<Flow, std::void_t<decltype(&Flow::can_part)>>
      : std::true_type
    {
    };


    /// A flow whose softening may follow a nonlocal average of the plastic
    /// strain: it has softening_average() (its NonlocalLength),
    /// nonlocal_shift(eqps, average) and softening_strain().
    template <typename Flow, typename = void>
    struct HasNonlocalSoftening : std::false_type
    {
    };
    template <typename Flow>
    struct HasNonlocalSoftening<Flow,
                                std::void_t<decltype(&Flow::softening_average)>>
      : std::true_type
    {
    };


    /**
     * A model in the log-strain framework. @p Flow corrects the elastic
     * trial state: a plastic flow returns it to its admissible set, a
     * viscous flow relaxes it over the step, the elastic flow does nothing.
     *
     *   struct Flow {
     *     static constexpr bool is_plastic;  // stores the plastic strain
     *     static void declare_parameters(ParameterHandler &);
     *     Flow(ParameterHandler &, const std::string &path,
     *          const ElasticConstants &);
     *     // (or with a fourth argument, const MaterialContext &, for a
     *     // flow that needs the body's context)
     *     // Plastic: return tau (in place) to the admissible set of a
     *     // point with equivalent plastic strain eqps in a step dt (a
     *     // rate-dependent strength needs it); false if it was inside.
     *     bool return_map(std::array<double,3> &tau, double eqps,
     *                     double dt) const;
     *     // <= 0 inside the admissible set (initial-stress check).
     *     double yield_function(const std::array<double,3> &tau,
     *                           double eqps) const;
     *     // Viscous, instead of the two above: relax tau (in place) over
     *     // a step dt with velocity gradient L; tau's directions are s's.
     *     template <int dim>
     *     void relax(std::array<double,3> &tau, double dt,
     *                const Tensor<2,dim> &L, const Spectral &s) const;
     *     // Optional, plastic: true if the admissible set holds zero
     *     // stress at its tip (no cohesion, or a tension cutoff of 0).
     *     bool can_part() const;
     *     // Optional, plastic with softening: its nonlocal length; the
     *     // shift from a point's plastic strain to the one it softens with
     *     // (return_map's eqps), given the average over its neighbours;
     *     // the plastic strain over which it softens.
     *     const NonlocalLength &softening_average() const;
     *     double nonlocal_shift(double eqps, double average) const;
     *     double softening_strain() const;
     *   };
     *
     * A material without cohesion that is stretched returns to zero
     * stress: its grains part, and the volume it gains at zero stress is
     * not elastic. Stored as plastic strain alone, that volume would stay:
     * compressed again, the point would resist at once as if its parted
     * state were its packing, and a granular front torn into a sparse
     * sheet (J of 3 to 20 behind a collapsing column) would rest as a
     * foam of that density instead of closing up. So a flow that can part
     * stores the volume gained at zero stress as the point's 'opening'
     * (a log volume) and gives it back first, without stress, when the
     * point is compressed: grains that have parted touch again before
     * they push on each other (the disconnected phase of Dunatunga and
     * Kamrin 2015).
     *
     * Every model takes the 'Damage' option (damage.h): the stress it
     * computes is softened by the damage of the point; its own state stays
     * undamaged.
     */
    template <int dim, typename Flow>
    class Model : public IsotropicPointwiseMaterial<dim, Model<dim, Flow>>
    {
      static constexpr bool is_viscous = IsViscous<Flow>::value;

    public:
      Model(ParameterHandler      &prm,
            const std::string     &path,
            const MaterialContext &context)
        : IsotropicPointwiseMaterial<dim, Model<dim, Flow>>(prm, path)
        , elasticity(this->constants)
        , flow(make_flow(prm, path, this->constants, context))
        , damage(prm, path, this->constants.youngs_modulus())
        , reference_density(context.density)
      {
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        ElasticConstants::declare(prm);
        Flow::declare_parameters(prm);
        DamageLaw::declare_parameters(prm);
      }

      void
      request_fields(FieldRequests &requests) const override
      {
        requests.elastic_left_cauchy_green = true;
        if (Flow::is_plastic)
          requests.plastic_strain = true;
        if constexpr (CanPart<Flow>::value)
          requests.opening = requests.opening || flow.can_part();
        damage.request_fields(requests);
        requests.nonlocal_softening =
          requests.nonlocal_softening || softening_nonlocal.enabled();
      }

      bool
      stiffness_is_kirchhoff() const override
      {
        return true;
      }

      /// The pressure-dependent flows (those with an apex, which may part)
      /// change the volume plastically; von Mises and the viscous flows
      /// keep it.
      bool
      volume_has_history() const override
      {
        return CanPart<Flow>::value;
      }

      /// The elastic strain that carries @p sigma0 (at the point's J).
      void
      initialise_point(double                      *p,
                       const FieldLayout           &layout,
                       const SymmetricTensor<2, 3> &sigma0) const override
      {
        const double                 J = jacobian(p, layout, reference_density);
        const Spectral               s = decompose<dim>(J * sigma0);
        const std::array<double, 3> &tau = s.values;
        if constexpr (Flow::is_plastic)
          {
            const double f = flow.yield_function(tau, 0.);
            if (f > 1e-10 * (std::abs(tau[0]) + std::abs(tau[1]) +
                             std::abs(tau[2]) + 1.))
              throw std::domain_error(
                "lies outside the yield surface (yield function " +
                std::to_string(f) + " > 0)");
            p[layout.plastic_strain] = 0.;
          }
        if (layout.opening != FieldLayout::absent)
          p[layout.opening] = 0.;
        if (layout.nonlocal_softening != FieldLayout::absent)
          p[layout.nonlocal_softening] = p[layout.nonlocal_softening + 1] = 0.;
        if (damage.enabled())
          {
            if (damage.equivalent_strain(s.values) / J >
                damage.initiation_strain)
              throw std::domain_error(
                "exceeds the damage initiation strain (largest principal "
                "stress / E > initiation strain)");
            p[layout.damage] = p[layout.damage_history] = 0.;
          }
        Fields::store_embedded<dim>(stretch_tensor<dim>(elasticity.strain(tau),
                                                        s),
                                    p + layout.elastic_left_cauchy_green);
        Fields::store(Fields::in_plane<dim>(sigma0), p + layout.stress);
      }

      /// Nonlocal damage needs every point's equivalent strain before any
      /// point's damage: two passes; nonlocal softening, every point's
      /// plastic strain before any return. Otherwise one pass of
      /// update_point.
      void
      update_stresses(Particles::ParticleHandler<dim> &particles,
                      const FieldLayout               &layout,
                      const unsigned int               body,
                      const double                     dt,
                      const MPI_Comm                   comm) const override
      {
        if (damage.is_nonlocal() || softening_nonlocal.enabled())
          update_nonlocal(particles, layout, body, dt, comm);
        else
          PointwiseMaterial<dim, Model<dim, Flow>>::update_stresses(
            particles, layout, body, dt, comm);
      }

      /// The step of one point; @p softening is the plastic strain its
      /// strength softens with, or local_softening for its own.
      inline void
      update_point(double            *p,
                   const FieldLayout &layout,
                   const double       dt,
                   const double       softening = local_softening) const
      {
        auto [sigma, s] = undamaged_update(p, layout, dt, softening);
        if (damage.enabled())
          apply_damage(p, layout, sigma, damage.equivalent_strain(sigma), dt);
        Fields::store(Fields::in_plane<dim>(compose<dim>(sigma, s)),
                      p + layout.stress);
      }

      /// The stored energy, 1/2 tau : eps_e per reference volume with the
      /// damaged tau (the elastic energy when undamaged).
      double
      strain_energy(const double *p, const FieldLayout &layout) const override
      {
        const Spectral              s   = stored_b_e(p, layout);
        const std::array<double, 3> eps = half_log(s);
        std::array<double, 3>       tau = elasticity.stress(eps);
        if (damage.enabled())
          damage.degrade(tau, p[layout.damage]);
        return 0.5 * (tau[0] * eps[0] + tau[1] * eps[1] + tau[2] * eps[2]) *
               p[layout.mass] / reference_density;
      }

      SymmetricTensor<2, 3>
      cauchy_stress_3d(const double      *p,
                       const FieldLayout &layout) const override
      {
        auto [sigma, s] = stored_undamaged_stress(p, layout);
        if (damage.enabled())
          damage.degrade(sigma, p[layout.damage]);
        return compose<dim>(sigma, s);
      }

    private:
      /**
       * The step without damage: push b_e forward, correct it by the flow,
       * store it; return the principal Cauchy stresses and directions.
       */
      inline std::pair<std::array<double, 3>, Spectral>
      undamaged_update(double            *p,
                       const FieldLayout &layout,
                       const double       dt,
                       const double       softening) const
      {
        double    *be_data = p + layout.elastic_left_cauchy_green;
        const auto L       = Fields::tensor<dim>(p + layout.velocity_gradient);
        const SymmetricTensor<2, 3> trial =
          push_forward<dim>(Fields::embedded<dim>(be_data),
                            increment<dim>(L, dt));
        const Spectral        s   = decompose<dim>(trial);
        std::array<double, 3> eps = half_log(s);
        const bool stores_opening = layout.opening != FieldLayout::absent;
        bool       corrected =
          stores_opening && close_opening(eps, p[layout.opening]);
        std::array<double, 3> tau = elasticity.stress(eps);
        if constexpr (Flow::is_plastic)
          {
            const std::array<double, 3> tau_trial = tau;
            double                     &eqps      = p[layout.plastic_strain];
            const double                state =
              softening == local_softening ? eqps : softening;
            if (flow.return_map(tau, state, dt))
              {
                corrected = true;
                eqps += elasticity.equivalent_plastic_strain(tau_trial, tau);
                if (stores_opening)
                  open(eps, tau, tau_trial, p[layout.opening]);
              }
          }
        if constexpr (is_viscous)
          {
            flow.relax(tau, dt, L, s);
            corrected = true;
          }
        Fields::store_embedded<dim>(
          corrected ? stretch_tensor<dim>(elasticity.strain(tau), s) : trial,
          be_data);
        return {cauchy(tau, p, layout), s};
      }

      /// Give back the opening first when the trial strain @p eps compresses
      /// the point: true if @p eps changed.
      static bool
      close_opening(std::array<double, 3> &eps, double &opening)
      {
        const double compression = -(eps[0] + eps[1] + eps[2]);
        if (opening <= 0 || compression <= 0)
          return false;
        const double closed = std::min(opening, compression);
        for (double &e : eps)
          e += closed / 3;
        opening -= closed;
        return true;
      }

      /// A return to zero stress (@p tau, from @p tau_trial) parts the
      /// point: its trial strain @p eps is all plastic, and the volume it
      /// gains is opening.
      static void
      open(const std::array<double, 3> &eps,
           const std::array<double, 3> &tau,
           const std::array<double, 3> &tau_trial,
           double                      &opening)
      {
        const double scale = std::max({std::abs(tau_trial[0]),
                                       std::abs(tau_trial[1]),
                                       std::abs(tau_trial[2])});
        if (std::max({std::abs(tau[0]), std::abs(tau[1]), std::abs(tau[2])}) <=
            1e-10 * scale)
          opening += std::max(eps[0] + eps[1] + eps[2], 0.);
      }

      /// Principal Cauchy stresses tau / J of principal Kirchhoff stresses.
      std::array<double, 3>
      cauchy(std::array<double, 3> tau,
             const double         *p,
             const FieldLayout    &layout) const
      {
        const double J = jacobian(p, layout, reference_density);
        for (double &t : tau)
          t /= J;
        return tau;
      }

      /// The undamaged principal Cauchy stresses of a point's stored b_e,
      /// and their directions.
      std::pair<std::array<double, 3>, Spectral>
      stored_undamaged_stress(const double *p, const FieldLayout &layout) const
      {
        const Spectral s = stored_b_e(p, layout);
        return {cauchy(elasticity.stress(half_log(s)), p, layout), s};
      }

      /// Evolve the point's damage with equivalent strain @p chi and soften
      /// the principal stresses @p sigma by it.
      inline void
      apply_damage(double                *p,
                   const FieldLayout     &layout,
                   std::array<double, 3> &sigma,
                   const double           chi,
                   const double           dt) const
      {
        double &kappa    = p[layout.damage_history];
        kappa            = damage.evolve(kappa, chi, dt);
        p[layout.damage] = damage.damage(kappa);
        damage.degrade(sigma, p[layout.damage]);
      }

      /// update_point's marker for a point that softens with its own
      /// plastic strain.
      static constexpr double local_softening = -1;

      /// How far a point's plastic strain may grow, as a share of the
      /// softening's range, before the body's average is taken again. The
      /// average costs a sum over some hundred neighbours per point; taken
      /// every step it cost 3.5 times the local run of a softening
      /// specimen, for a slip the same to 1 % (benchmarks/plasticity/
      /// README.md).
      static constexpr double refresh_growth = 0.01;

      /// Average the plastic strain of body @p body again if some point's
      /// has grown by refresh_growth of the softening's range since the
      /// last average (collective over @p comm): store each point's
      /// over-nonlocal shift and the plastic strain it was made at.
      ///
      /// What is averaged is the plastic strain up to the softening's end
      /// (softening_part): beyond it the strength no longer changes, and a
      /// point sheared far past it (plastic strains of 10 in a slide's
      /// base) would otherwise lead its neighbours by so much that the
      /// over-nonlocal mix put it back at its peak strength, and keep the
      /// average being taken while the debris flows.
      void
      refresh_softening_shifts(Particles::ParticleHandler<dim> &particles,
                               const FieldLayout               &layout,
                               const unsigned int               body,
                               const MPI_Comm                   comm) const
      {
        if constexpr (HasNonlocalSoftening<Flow>::value)
          {
            const double id        = body;
            const double allowed   = refresh_growth * flow.softening_strain();
            const unsigned int k   = layout.nonlocal_softening;
            bool               due = false;
            for (const auto &particle : particles)
              {
                const double *p = particle.get_properties().data();
                due =
                  due || (p[layout.body] == id &&
                          softening_part(p[layout.plastic_strain]) - p[k + 1] >
                            allowed);
              }
            if (Utilities::MPI::max(due ? 1 : 0, comm) == 0)
              return;
            std::vector<Point<dim>> x;
            std::vector<double>     volume, eqps;
            for (const auto &particle : particles)
              {
                const double *p = particle.get_properties().data();
                if (p[layout.body] == id)
                  {
                    x.push_back(particle.get_location());
                    volume.push_back(p[layout.volume]);
                    eqps.push_back(softening_part(p[layout.plastic_strain]));
                  }
              }
            // A plastic strain is >= 0: where no neighbour has yielded the
            // average is 0 without the sum.
            const std::vector<double> average = softening_nonlocal.average(
              x, volume, eqps, std::vector<double>(x.size(), 0.), comm);
            unsigned int i = 0;
            for (auto &particle : particles)
              {
                double *p = particle.get_properties().data();
                if (p[layout.body] == id)
                  {
                    p[k]     = flow.nonlocal_shift(eqps[i], average[i]);
                    p[k + 1] = eqps[i];
                    ++i;
                  }
              }
          }
      }

      /// A plastic strain up to the end of the flow's softening range.
      double
      softening_part(const double eqps) const
      {
        if constexpr (HasNonlocalSoftening<Flow>::value)
          return std::min(eqps, flow.softening_strain());
        else
          return eqps;
      }

      /// The plastic strain point @p p softens with: its own (up to the
      /// softening's end), shifted by its stored over-nonlocal shift (>= 0:
      /// the peak below), or local_softening without a nonlocal length.
      double
      softening_of(const double *p, const FieldLayout &layout) const
      {
        if (!softening_nonlocal.enabled())
          return local_softening;
        return std::max(softening_part(p[layout.plastic_strain]) +
                          p[layout.nonlocal_softening],
                        0.);
      }

      void
      update_nonlocal(Particles::ParticleHandler<dim> &particles,
                      const FieldLayout               &layout,
                      const unsigned int               body,
                      const double                     dt,
                      const MPI_Comm                   comm) const
      {
        if (softening_nonlocal.enabled())
          refresh_softening_shifts(particles, layout, body, comm);
        const double id = body;
        if (!damage.is_nonlocal())
          {
            for (auto &particle : particles)
              {
                double *p = particle.get_properties().data();
                if (p[layout.body] == id)
                  update_point(p, layout, dt, softening_of(p, layout));
              }
            return;
          }
        std::vector<Point<dim>> x;
        std::vector<double>     volume, chi, kappa;
        for (auto &particle : particles)
          {
            double *p = particle.get_properties().data();
            if (p[layout.body] == id)
              {
                const auto sigma =
                  undamaged_update(p, layout, dt, softening_of(p, layout))
                    .first;
                x.push_back(particle.get_location());
                volume.push_back(p[layout.volume]);
                chi.push_back(damage.equivalent_strain(sigma));
                kappa.push_back(p[layout.damage_history]);
              }
          }
        const std::vector<double> chi_bar =
          nonlocal.average(x, volume, chi, kappa, comm);
        unsigned int i = 0;
        for (auto &particle : particles)
          {
            double *p = particle.get_properties().data();
            if (p[layout.body] == id)
              {
                auto [sigma, s] = stored_undamaged_stress(p, layout);
                apply_damage(p, layout, sigma, chi_bar[i++], dt);
                Fields::store(Fields::in_plane<dim>(compose<dim>(sigma, s)),
                              p + layout.stress);
              }
          }
      }

      /// The flow rule, given the body's context if it takes one (a
      /// softening model's regularisation needs the cell size).
      static Flow
      make_flow(ParameterHandler       &prm,
                const std::string      &path,
                const ElasticConstants &constants,
                const MaterialContext  &context)
      {
        if constexpr (std::is_constructible_v<Flow,
                                              ParameterHandler &,
                                              const std::string &,
                                              const ElasticConstants &,
                                              const MaterialContext &>)
          return Flow(prm, path, constants, context);
        else
          return Flow(prm, path, constants);
      }

      /// The nonlocal length of @p flow's softening (0: local, or a flow
      /// without softening).
      static NonlocalLength
      softening_length(const Flow &flow)
      {
        if constexpr (HasNonlocalSoftening<Flow>::value)
          return flow.softening_average();
        else
          return {};
      }

      /// The spectral decomposition of a point's stored b_e.
      static Spectral
      stored_b_e(const double *p, const FieldLayout &layout)
      {
        return decompose<dim>(
          Fields::embedded<dim>(p + layout.elastic_left_cauchy_green));
      }

      const PrincipalElasticity  elasticity;
      const Flow                 flow;
      const DamageLaw            damage;
      const NonlocalAverage<dim> nonlocal{damage.nonlocal};
      const NonlocalAverage<dim> softening_nonlocal{softening_length(flow)};
      const double               reference_density;
    };

    /// Cohesion, friction and dilation angle (radians) of the frictional
    /// models, declared and read in one place.
    struct FrictionalStrength
    {
      double c, phi, psi;

      /// @p peak: the documentation calls them the peak values (models
      /// that soften).
      static void
      declare_parameters(ParameterHandler &prm, const bool peak);
      static FrictionalStrength
      parse(const ParameterHandler &prm, const std::string &path);
    };


    /// An angle given in degrees, in radians.
    inline double
    radians(const double degrees)
    {
      return degrees * M_PI / 180.;
    }

    /// 'friction angle' in degrees, in [0, 90). Dilation angles are bounded
    /// by it in degrees, as given: phi * 180 / pi would round 30 to
    /// 29.999999999999996 and reject associated flow (psi = phi).
    double
    friction_angle_degrees(const ParameterHandler &prm,
                           const std::string      &path);

    /// 'tension cutoff': 'apex' (none beyond the cone's apex, returned as
    /// +infinity) or a number >= 0.
    double
    parse_tension_cutoff(const ParameterHandler &prm, const std::string &path);

    /// The log-strain model with flow rule @p Flow, as the class template
    /// on the dimension that the registry's material_entry() takes.
    template <typename Flow>
    struct ModelOf
    {
      template <int dim>
      using type = Model<dim, Flow>;
    };
  } // namespace LogStrain
} // namespace mpm

/**
 * Define LogStrainModels::@p function (declared in pointwise.h), the
 * registry entry of the log-strain model with flow rule LogStrain::@p Flow
 * under @p name: the one line a log-strain model's source file adds.
 */
#define MPM_LOG_STRAIN_ENTRY(function, Flow, name)                          \
  MaterialEntry LogStrainModels::function()                                 \
  {                                                                         \
    return material_entry<LogStrain::ModelOf<LogStrain::Flow>::type>(name); \
  }

#endif
