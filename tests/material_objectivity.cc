// Objectivity of the material updates under rigid rotation.
//
// Linear elastic (rate form): a point with stress sigma0 spun by a pure spin
// L = W for time T must end with R(T) sigma0 R(T)^T, R the rotation by the
// angle omega T; the Hughes-Winget update rotates by a slightly different
// angle per step, 2 atan(omega dt/2), so that angle is what it must match.
// Neo-Hookean: for F = R U the stress must be R sigma(U) R^T.
// The program prints the errors and fails if one exceeds its bound.
#include <deal.II/base/parameter_handler.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/materials/material.h>
#include <mpm/materials/strain_measures.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace mpm;

namespace
{
  Tensor<2, 2>
  rotation(const double angle)
  {
    Tensor<2, 2> R;
    R[0][0] = R[1][1] = std::cos(angle);
    R[0][1]           = -std::sin(angle);
    R[1][0]           = std::sin(angle);
    return R;
  }

  /// One material point carrying every field a material may read.
  struct OnePoint
  {
    OnePoint()
      : particles(tria, mapping, 0)
    {
      GridGenerator::hyper_cube(tria);
      layout.mass                 = layout.add(1);
      layout.volume               = layout.add(1);
      layout.body                 = layout.add(1);
      layout.stress               = layout.add(3);
      layout.velocity_gradient    = layout.add(4);
      layout.deformation_gradient = layout.add(4);
      particles.initialize(tria, mapping, layout.n_properties);
      std::vector<double> p(layout.n_properties, 0.);
      p[layout.mass] = p[layout.volume] = 1;
      particles.insert_particle(Point<2>(0.5, 0.5),
                                Point<2>(0.5, 0.5),
                                0,
                                tria.begin_active(),
                                make_array_view(p));
    }

    double *
    properties()
    {
      return particles.begin()->get_properties().data();
    }

    Triangulation<2>              tria;
    MappingQ1<2>                  mapping;
    FieldLayout                   layout;
    Particles::ParticleHandler<2> particles;
  };

  std::unique_ptr<Material<2>>
  make(const std::string &name)
  {
    ParameterHandler prm;
    MaterialRegistry::declare_parameters(prm);
    prm.enter_subsection(name);
    prm.set("Young's modulus", "1000");
    prm.set("Poisson's ratio", "0.3");
    prm.leave_subsection();
    return MaterialRegistry::create<2>(name, prm, "test", {1.});
  }
} // namespace


int
main()
{
  bool ok = true;

  // Linear elastic: spin a prestressed point by a quarter turn and more.
  {
    OnePoint              point;
    const auto            material = make("linear elastic");
    const double          omega = 2., dt = 1e-3;
    const unsigned int    n_steps = 1000;
    SymmetricTensor<2, 2> sigma0;
    sigma0[0][0] = 100;
    sigma0[1][1] = -30;
    sigma0[0][1] = 20;
    Fields::store(sigma0, point.properties() + point.layout.stress);
    Tensor<2, 2> W;
    W[0][1] = -omega;
    W[1][0] = omega;
    Fields::store(W, point.properties() + point.layout.velocity_gradient);
    for (unsigned int i = 0; i < n_steps; ++i)
      material->update_stresses(
        point.particles, point.layout, 0, dt, MPI_COMM_SELF);
    const double       angle    = n_steps * 2 * std::atan(0.5 * omega * dt);
    const Tensor<2, 2> R        = rotation(angle);
    const Tensor<2, 2> expected = R * Tensor<2, 2>(sigma0) * transpose(R);
    const auto         sigma =
      Fields::symmetric<2>(point.properties() + point.layout.stress);
    const double error =
      (Tensor<2, 2>(sigma) - expected).norm() / sigma0.norm();
    // Invariants must be kept whatever the angle convention.
    const double invariant_error =
      std::abs(determinant(sigma) - determinant(sigma0)) /
        std::abs(determinant(sigma0)) +
      std::abs(trace(sigma) - trace(sigma0)) / sigma0.norm();
    std::cout << "linear elastic, rotation by " << angle
              << " rad: relative stress error " << error << ", invariant error "
              << invariant_error << std::endl;
    ok = ok && error < 1e-12 && invariant_error < 1e-12;
  }

  // Neo-Hookean: sigma(R U) = R sigma(U) R^T.
  {
    OnePoint     point;
    const auto   material = make("neo-Hookean");
    Tensor<2, 2> U;
    U[0][0] = 1.2;
    U[1][1] = 0.9;
    U[0][1] = U[1][0] = 0.05;
    auto stress_for   = [&](const Tensor<2, 2> &F) {
      Fields::store(F, point.properties() + point.layout.deformation_gradient);
      material->update_stresses(
        point.particles, point.layout, 0, 1e-3, MPI_COMM_SELF);
      return Tensor<2, 2>(
        Fields::symmetric<2>(point.properties() + point.layout.stress));
    };
    const Tensor<2, 2> sigma_U  = stress_for(U);
    const Tensor<2, 2> R        = rotation(0.7);
    const Tensor<2, 2> sigma_RU = stress_for(R * U);
    const double       error =
      (sigma_RU - R * sigma_U * transpose(R)).norm() / sigma_U.norm();
    const double rigid = stress_for(R).norm();
    std::cout << "neo-Hookean: relative error of sigma(RU) = R sigma(U) R^T: "
              << error << ", stress of a rigid rotation: " << rigid
              << std::endl;
    ok = ok && error < 1e-13 && rigid < 1e-10;
  }

  // The output's log strain (issue 33): for F = R U with U = diag(2, 1/2)
  // it is R diag(ln 2, -ln 2) R^T (plane strain: zz = 0), a rigid rotation
  // has none, and its equivalent deviatoric strain is that of the
  // principal strains (ln 2, -ln 2, 0): sqrt(2/3 * 2 ln^2 2) = 2 ln 2 / sqrt 3.
  {
    Tensor<2, 2> U;
    U[0][0]                 = 2.;
    U[1][1]                 = 0.5;
    const Tensor<2, 2>    R = rotation(0.7);
    SymmetricTensor<2, 3> e = log_strain<2>(R * U);
    Tensor<2, 2>          logU;
    logU[0][0]                  = std::log(2.);
    logU[1][1]                  = -std::log(2.);
    const Tensor<2, 2> expected = R * logU * transpose(R);
    double             error    = std::abs(e[2][2]);
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        error += std::abs(e[i][j] - expected[i][j]);
    const double rigid = log_strain<2>(R).norm();
    const double deviatoric_error =
      std::abs(deviatoric_strain(e) - 2 * std::log(2.) / std::sqrt(3.));
    // 3D: a stretch along a tilted axis, F = I + (lambda - 1) n n.
    Tensor<1, 3> n({1., 2., 2.});
    n /= n.norm();
    const Tensor<2, 3> F3 =
      unit_symmetric_tensor<3>() + 2. * outer_product(n, n);
    const SymmetricTensor<2, 3> e3 = log_strain<3>(F3);
    const double                error_3d =
      (Tensor<2, 3>(e3) - std::log(3.) * outer_product(n, n)).norm();
    std::cout << "log strain of R U: error " << error << ", of a rotation "
              << rigid << ", deviatoric strain error " << deviatoric_error
              << ", 3D stretch along (1, 2, 2)/3: error " << error_3d
              << std::endl;
    ok = ok && error < 1e-14 && rigid < 1e-14 && deviatoric_error < 1e-14 &&
         error_3d < 1e-14;
  }

  std::cout << (ok ? "passed" : "FAILED") << std::endl;
  return ok ? 0 : 1;
}
