// A single material point driven the way the integrator drives it, for
// the constitutive unit tests.
#ifndef mpm_tests_single_point_h
#define mpm_tests_single_point_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/field_layout.h>
#include <mpm/materials/material.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace single_point
{
  using namespace dealii;
  using namespace mpm;

  /// One material point of model @p name with parameters @p settings, of
  /// unit volume in a grid of cell size @p cell_size.
  template <int dim>
  struct Point
  {
    Point(const std::string                                      &name,
          const std::vector<std::pair<std::string, std::string>> &settings,
          const SymmetricTensor<2, 3> &sigma0    = SymmetricTensor<2, 3>(),
          const double                 cell_size = 1.)
    {
      ParameterHandler prm;
      MaterialRegistry::declare_parameters(prm);
      prm.enter_subsection(name);
      for (const auto &[key, value] : settings)
        if (key.rfind("Damage/", 0) == 0)
          {
            prm.enter_subsection("Damage");
            prm.set(key.substr(7), value);
            prm.leave_subsection();
          }
        else
          prm.set(key, value);
      prm.leave_subsection();
      material =
        MaterialRegistry::create<dim>(name, prm, "test", {density, cell_size});
      FieldRequests requests;
      material->request_fields(requests);
      layout = assemble_layout<dim>(requests);
      q.assign(layout.n_properties, 0.);
      q[layout.mass]   = density;
      q[layout.volume] = 1;
      if (layout.deformation_gradient != FieldLayout::absent)
        for (unsigned int d = 0; d < dim; ++d)
          q[layout.deformation_gradient + d * dim + d] = 1.;
      material->initialise_point(q.data(), layout, sigma0);
    }

    /// One step with velocity gradient @p L over @p dt.
    void
    step(const Tensor<2, dim> &L, const double dt)
    {
      Fields::store(L, q.data() + layout.velocity_gradient);
      Tensor<2, dim> dF = dt * L;
      for (unsigned int d = 0; d < dim; ++d)
        dF[d][d] += 1;
      q[layout.volume] *= determinant(dF);
      material->update_point_stress(q.data(), layout, dt);
    }

    /// A step whose increment I + dt L is @p dF exactly (dt = 1).
    void
    step_by(const Tensor<2, dim> &dF)
    {
      step(dF - unit_symmetric_tensor<dim>(), 1.);
    }

    double
    J() const
    {
      return q[layout.volume] * density / q[layout.mass];
    }

    /// Kirchhoff stress, full 3D.
    SymmetricTensor<2, 3>
    tau() const
    {
      return J() * material->cauchy_stress_3d(q.data(), layout);
    }

    double
    plastic_strain() const
    {
      return q[layout.plastic_strain];
    }

    static constexpr double        density = 2000;
    std::unique_ptr<Material<dim>> material;
    FieldLayout                    layout;
    std::vector<double>            q;
  };


} // namespace single_point

#endif
