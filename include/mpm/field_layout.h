#ifndef mpm_field_layout_h
#define mpm_field_layout_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Which properties each material point of this scene stores, and at which
   * offset of deal.II's per-particle property array. Assembled once from
   * what the scene uses, so that a scene carries no field it does not need:
   * the deformation gradient only if a material asks for it, the initial
   * position only if displacement is written or checked (or a body force
   * needs it), the affine velocity only with APIC, the elastic left
   * Cauchy-Green tensor and the plastic strain only for the models that
   * keep them.
   */
  struct FieldLayout
  {
    static constexpr unsigned int absent = static_cast<unsigned int>(-1);

    unsigned int mass                 = absent; ///< 1
    unsigned int volume               = absent; ///< 1, current volume
    unsigned int velocity             = absent; ///< dim
    unsigned int stress               = absent; ///< dim(dim+1)/2, Cauchy
    unsigned int velocity_gradient    = absent; ///< dim*dim
    unsigned int body                 = absent; ///< 1, body index
    unsigned int deformation_gradient = absent; ///< dim*dim, optional
    unsigned int initial_position     = absent; ///< dim, optional
    /// dim, a stage resets displacements only: where the displacement
    /// output counts from (the initial position until a reset).
    unsigned int displacement_origin = absent;
    unsigned int affine_velocity     = absent; ///< dim*dim, APIC's C_p
    /// Elastic left Cauchy-Green tensor b_e of the log-strain models, in
    /// the embedded form of Fields::embedded (3, 4 or 6 values).
    unsigned int elastic_left_cauchy_green = absent;
    unsigned int plastic_strain = absent; ///< 1, equivalent plastic strain
    /// 1, the log volume a cohesionless material gained at zero stress (its
    /// grains parted), given back without stress when it is compressed.
    unsigned int opening        = absent;
    unsigned int damage         = absent; ///< 1, damage d
    unsigned int damage_history = absent; ///< 1, its history variable kappa
    /// 2, nonlocal softening only: the over-nonlocal shift of the plastic
    /// strain the strength softens with, m (eqps_bar - eqps), and the
    /// plastic strain eqps when it was averaged (a shift is kept until the
    /// plastic strain has grown enough to average again).
    unsigned int nonlocal_softening = absent;
    /// dim: the outward area vector N dA of the loaded surface a point of
    /// a pressure-loaded body carries (zero inside the body).
    unsigned int surface_area = absent;
    /// dim: where the point's loaded surface lies relative to it, d (half
    /// a point spacing along the normal on a face of a lattice body, see
    /// SurfaceShare): the load acts through the basis at x + d, to first
    /// order phi(x) + d . grad phi(x).
    unsigned int surface_offset = absent;
    /// dim*dim: this step's surface load times that offset, load (x) d,
    /// which the scatter adds to the stress term (see ParticleToGrid::scatter).
    unsigned int load_moment = absent;
    /// dim: the loads on the point this step besides body forces (a rigid
    /// wall's contact force, a pressure on a loaded face), made before the
    /// scatter so that it adds one vector.
    unsigned int point_load = absent;
    /// dim per rigid wall with friction: the elastic tangential
    /// displacement of the point's contact with it (stick spring).
    unsigned int wall_slip = absent;
    /// dim + dim*dim, substepping only: the other end of the macro step's
    /// motion (x_p^n during the substeps, x_p^(n+1) while the points sit
    /// at x_p^n for the reconstruction), then the substeps' deformation
    /// increment F^(n+1) (F^n)^-1.
    unsigned int macro_step = absent;
    /// 1, F-bar only: the mean stress of the point's cell minus its own,
    /// which the internal force adds (FBar::average_mean_stress).
    unsigned int mean_stress_correction = absent;
    unsigned int n_properties           = 0;

    /// Reserve @p n consecutive slots and return the first.
    unsigned int
    add(const unsigned int n)
    {
      const unsigned int first = n_properties;
      n_properties += n;
      return first;
    }

    /// Names of the stored fields with their sizes, for the memory report.
    std::vector<std::pair<std::string, unsigned int>> description;
  };


  /// Fields that a scene needs beyond the ones every scene stores.
  struct FieldRequests
  {
    bool initial_position          = false;
    bool displacement_origin       = false;
    bool deformation_gradient      = false;
    bool affine_velocity           = false;
    bool elastic_left_cauchy_green = false;
    bool plastic_strain            = false;
    bool opening                   = false;
    bool damage                    = false;
    bool nonlocal_softening        = false;
    bool surface_area              = false;
    /// Offset and load moment: only a load on a face of a shape has one.
    bool         surface_offset         = false;
    bool         point_load             = false;
    unsigned int wall_slips             = 0; ///< walls with friction
    bool         macro_step             = false;
    bool         mean_stress_correction = false; ///< F-bar

    /// Also ask for what @p other asks for (the stages of a scene store
    /// the fields of them all: a checkpoint carries the points from one
    /// stage to the next).
    FieldRequests &
    operator|=(const FieldRequests &other);
  };


  /// The layout of a scene that stores what @p requests asks for, besides
  /// the fields every scene stores; @p dim sets the tensor sizes.
  template <int dim>
  FieldLayout
  assemble_layout(const FieldRequests &requests);


  /// Reading and writing tensors from a flat property array.
  namespace Fields
  {
    template <int dim>
    inline Tensor<1, dim>
    vector(const double *p)
    {
      Tensor<1, dim> v;
      for (unsigned int d = 0; d < dim; ++d)
        v[d] = p[d];
      return v;
    }

    template <int dim>
    inline void
    store(const Tensor<1, dim> &v, double *p)
    {
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = v[d];
    }

    template <int dim>
    inline Tensor<2, dim>
    tensor(const double *p)
    {
      Tensor<2, dim> t;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          t[i][j] = p[i * dim + j];
      return t;
    }

    template <int dim>
    inline void
    store(const Tensor<2, dim> &t, double *p)
    {
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          p[i * dim + j] = t[i][j];
    }

    /// Symmetric tensors use deal.II's unrolled component order.
    template <int dim>
    inline SymmetricTensor<2, dim>
    symmetric(const double *p)
    {
      SymmetricTensor<2, dim> s;
      for (unsigned int k = 0; k < s.n_independent_components; ++k)
        s.access_raw_entry(k) = p[k];
      return s;
    }

    template <int dim>
    inline void
    store(const SymmetricTensor<2, dim> &s, double *p)
    {
      for (unsigned int k = 0; k < s.n_independent_components; ++k)
        p[k] = s.access_raw_entry(k);
    }

    /**
     * A 3D symmetric tensor of a point in uniaxial (1D) or plane (2D)
     * strain: its in-plane components in deal.II's order, then the
     * out-of-plane normal ones (the shear components across the plane
     * vanish there). 3, 4 or 6 values.
     */
    template <int dim>
    constexpr unsigned int n_embedded = dim *(dim + 1) / 2 + 3 - dim;

    template <int dim>
    inline SymmetricTensor<2, 3>
    embedded(const double *p)
    {
      SymmetricTensor<2, 3> t;
      const auto            in_plane = symmetric<dim>(p);
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          t[i][j] = in_plane[i][j];
      for (unsigned int d = dim; d < 3; ++d)
        t[d][d] =
          p[SymmetricTensor<2, dim>::n_independent_components + d - dim];
      return t;
    }

    template <int dim>
    inline void
    store_embedded(const SymmetricTensor<2, 3> &t, double *p)
    {
      SymmetricTensor<2, dim> in_plane;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          in_plane[i][j] = t[i][j];
      store(in_plane, p);
      for (unsigned int d = dim; d < 3; ++d)
        p[SymmetricTensor<2, dim>::n_independent_components + d - dim] =
          t[d][d];
    }

    /// The in-plane part of a 3D tensor.
    template <int dim>
    inline SymmetricTensor<2, dim>
    in_plane(const SymmetricTensor<2, 3> &t)
    {
      SymmetricTensor<2, dim> s;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          s[i][j] = t[i][j];
      return s;
    }
  } // namespace Fields
} // namespace mpm

#endif
