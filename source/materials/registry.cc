#include <mpm/materials/pointwise.h>

#include <vector>

namespace mpm
{
  namespace
  {
    /// The registry itself: one line per model.
    const std::vector<MaterialEntry> &
    registry()
    {
      static const std::vector<MaterialEntry> entries = {
        Elastic::linear_elastic(),
        Elastic::neo_hookean(),
        LogStrainModels::hencky_elastic(),
        LogStrainModels::von_mises(),
        LogStrainModels::drucker_prager(),
        LogStrainModels::mohr_coulomb(),
        LogStrainModels::maxwell_viscoelastic(),
        Fluids::newtonian_fluid()};
      return entries;
    }
  } // namespace


  template <int dim>
  void
  Material<dim>::initialise_point(double                      *properties,
                                  const FieldLayout           &layout,
                                  const SymmetricTensor<2, 3> &sigma0) const
  {
    Fields::store(Fields::in_plane<dim>(sigma0), properties + layout.stress);
  }


  ElasticConstants::ElasticConstants(ParameterHandler  &prm,
                                     const std::string &path)
  {
    const double E = Parse::bounded_double(
      prm, path, "Young's modulus", 0., largest_input, true);
    const double nu =
      Parse::bounded_double(prm, path, "Poisson's ratio", -1., 0.5, true, true);
    lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
    mu     = E / (2. * (1. + nu));
    given  = Parse::given(prm, path, "Young's modulus") + ", " +
            Parse::given(prm, path, "Poisson's ratio");
  }


  void
  ElasticConstants::declare(ParameterHandler &prm)
  {
    prm.declare_entry("Young's modulus",
                      "1e6",
                      Patterns::Anything(),
                      "Young's modulus E in Pa, in (0, 1e15] (diamond: "
                      "1.2e12; beyond, the energies overflow).");
    prm.declare_entry("Poisson's ratio",
                      "0.3",
                      Patterns::Anything(),
                      "Poisson's ratio, in (-1, 0.5) for these "
                      "compressible models. In 2D the models are plane "
                      "strain.");
  }


  namespace MaterialRegistry
  {
    std::string
    names()
    {
      std::string s;
      for (const auto &e : registry())
        s += (s.empty() ? "" : "|") + std::string(e.name);
      return s;
    }


    void
    declare_parameters(ParameterHandler &prm)
    {
      for (const auto &e : registry())
        {
          prm.enter_subsection(e.name);
          e.declare(prm);
          prm.leave_subsection();
        }
    }


    template <int dim>
    std::unique_ptr<Material<dim>>
    create(const std::string     &name,
           ParameterHandler      &prm,
           const std::string     &path,
           const MaterialContext &context)
    {
      for (const auto &e : registry())
        if (name == e.name)
          {
            prm.enter_subsection(name);
            std::unique_ptr<Material<dim>> m;
            const std::string              here = path + "/" + name;
            if constexpr (dim == 1)
              m = e.create_1d(prm, here, context);
            else if constexpr (dim == 2)
              m = e.create_2d(prm, here, context);
            else
              m = e.create_3d(prm, here, context);
            prm.leave_subsection();
            return m;
          }
      throw InputError(path + "/material",
                       name,
                       "known materials are " + names());
    }


    template std::unique_ptr<Material<1>>
    create<1>(const std::string &,
              ParameterHandler &,
              const std::string &,
              const MaterialContext &);
    template std::unique_ptr<Material<2>>
    create<2>(const std::string &,
              ParameterHandler &,
              const std::string &,
              const MaterialContext &);
    template std::unique_ptr<Material<3>>
    create<3>(const std::string &,
              ParameterHandler &,
              const std::string &,
              const MaterialContext &);
  } // namespace MaterialRegistry

  template class Material<1>;
  template class Material<2>;
  template class Material<3>;
} // namespace mpm
