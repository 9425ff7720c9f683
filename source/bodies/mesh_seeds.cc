#include <deal.II/base/quadrature.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <deal.II/base/bounding_box.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <mpm/bodies/mesh_seeds.h>
#include <mpm/parameters.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

namespace mpm
{
  namespace
  {
    /// The gist of a deal.II exception: its "Additional information" line.
    std::string
    gist(const std::string &what)
    {
      const auto i = what.find("Additional information:");
      if (i == std::string::npos)
        return Utilities::trim(what.substr(0, what.find('\n')));
      std::string rest = what.substr(i + 23);
      rest             = Utilities::trim(rest.substr(0, rest.find("\n\n")));
      for (auto &c : rest)
        if (c == '\n')
          c = ' ';
      return rest;
    }


    template <int dim>
    void
    read_mesh(const std::string  &file,
              const std::string  &path,
              Triangulation<dim> &mesh)
    {
      const std::string parameter = path + "/mesh file";
      std::string       extension = std::filesystem::path(file).extension();
      if (!extension.empty())
        extension.erase(0, 1);
      typename GridIn<dim>::Format format;
      try
        {
          format = GridIn<dim>::parse_format(extension);
        }
      catch (...)
        {
          throw InputError(parameter,
                           file,
                           "the extension must name a format deal.II's "
                           "GridIn reads: " +
                             GridIn<dim>::get_format_names());
        }
      std::ifstream in(file);
      if (!in)
        throw InputError(parameter, file, "cannot be opened for reading");
      GridIn<dim> reader;
      reader.attach_triangulation(mesh);
      try
        {
          reader.read(in, format);
        }
      catch (const std::exception &e)
        {
          throw InputError(parameter,
                           file,
                           "is not a valid ." + extension +
                             " mesh of dimension " + std::to_string(dim) +
                             ": " + gist(e.what()));
        }
    }


    /// Gauss points on the faces of cells of @p kind (a vertex in 1D).
    template <int dim>
    Quadrature<dim - 1>
    face_quadrature(const ReferenceCell &kind, const unsigned int n)
    {
      if constexpr (dim == 1)
        return QGauss<0>(n);
      else
        return kind.face_reference_cell(0)
          .template get_gauss_type_quadrature<dim - 1>(n);
    }


    /// FEValues for the Gauss points of one kind of cell (quadrilaterals,
    /// triangles, ...): a mesh may mix them.
    template <int dim>
    struct CellKind
    {
      CellKind(const ReferenceCell &kind, const unsigned int n)
        : element(kind)
        , values(kind.template get_default_linear_mapping<dim>(),
                 element,
                 kind.template get_gauss_type_quadrature<dim>(n),
                 update_quadrature_points | update_JxW_values)
        , face_values(kind.template get_default_linear_mapping<dim>(),
                      element,
                      face_quadrature<dim>(kind, n),
                      update_quadrature_points | update_JxW_values |
                        update_normal_vectors)
      {
      }
      FE_Nothing<dim>   element;
      FEValues<dim>     values;
      FEFaceValues<dim> face_values;
    };


    /// Hand the area of @p cell's loaded faces to its points, which are the
    /// last n_quadrature_points of @p seeds.
    template <int dim>
    void
    add_face_areas(
      const typename Triangulation<dim>::active_cell_iterator &cell,
      const std::set<types::boundary_id>                      &loaded,
      CellKind<dim>                                           &kind,
      MeshSeeds<dim>                                          &seeds,
      std::set<types::boundary_id>                            &seen_faces)
    {
      const unsigned int n_points = kind.values.n_quadrature_points;
      const unsigned int first    = seeds.positions.size() - n_points;
      seeds.areas.resize(seeds.positions.size());
      for (const unsigned int f : cell->face_indices())
        if (cell->at_boundary(f) && loaded.count(cell->face(f)->boundary_id()))
          {
            seen_faces.insert(cell->face(f)->boundary_id());
            kind.face_values.reinit(cell, f);
            for (unsigned int q = 0; q < kind.face_values.n_quadrature_points;
                 ++q)
              {
                const Point<dim> &x = kind.face_values.quadrature_point(q);
                unsigned int      nearest = first;
                for (unsigned int i = first + 1; i < first + n_points; ++i)
                  if (x.distance_square(seeds.positions[i]) <
                      x.distance_square(seeds.positions[nearest]))
                    nearest = i;
                seeds.areas[nearest] +=
                  kind.face_values.JxW(q) * kind.face_values.normal_vector(q);
              }
          }
    }
  } // namespace


  template <int dim>
  MeshSeeds<dim>
  seeds_from_mesh(const std::string                  &file,
                  const std::set<types::material_id> &material_ids,
                  const std::set<types::boundary_id> &loaded_boundary_ids,
                  const unsigned int                  n,
                  const std::string                  &path)
  {
    Triangulation<dim> mesh;
    read_mesh(file, path, mesh);

    MeshSeeds<dim>                                          seeds;
    std::map<ReferenceCell, std::unique_ptr<CellKind<dim>>> kinds;
    std::set<types::material_id>                            seen;
    std::set<types::boundary_id>                            seen_faces;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        seen.insert(cell->material_id());
        if (!material_ids.empty() &&
            material_ids.count(cell->material_id()) == 0)
          continue;
        auto &kind = kinds[cell->reference_cell()];
        if (!kind)
          {
            // deal.II has Gauss rules on simplices (and wedges, pyramids)
            // for a few orders only; it asserts beyond them, so ask first.
            const ReferenceCell shape   = cell->reference_cell();
            const unsigned int  highest = shape.is_hyper_cube() ? 10
                                          : shape == ReferenceCells::Pyramid ? 2
                                                                             : 4;
            if (n > highest)
              throw InputError(path + "/particles per cell",
                               std::to_string(n),
                               "deal.II has no Gauss rule of this order on "
                               "the mesh's " +
                                 shape.to_string() + " cells; use at most " +
                                 std::to_string(highest));
            kind = std::make_unique<CellKind<dim>>(shape, n);
          }
        kind->values.reinit(cell);
        for (unsigned int q = 0; q < kind->values.n_quadrature_points; ++q)
          {
            const double volume = kind->values.JxW(q);
            if (!(volume > 0))
              throw InputError(path + "/mesh file",
                               file,
                               "cell " + std::to_string(cell->index()) +
                                 " is inverted or degenerate (Jacobian "
                                 "determinant <= 0 at a Gauss point)");
            seeds.positions.push_back(kind->values.quadrature_point(q));
            seeds.volumes.push_back(volume);
          }
        if (!loaded_boundary_ids.empty())
          add_face_areas(cell, loaded_boundary_ids, *kind, seeds, seen_faces);
      }
    for (const auto id : loaded_boundary_ids)
      if (seen_faces.count(id) == 0)
        throw InputError(path + "/pressure boundary ids",
                         std::to_string(id),
                         "no boundary face of the body's cells in '" + file +
                           "' has this boundary id");
    for (const auto id : material_ids)
      if (seen.count(id) == 0)
        {
          std::string present;
          for (const auto s : seen)
            present += (present.empty() ? "" : ", ") + std::to_string(s);
          throw InputError(path + "/mesh material ids",
                           std::to_string(id),
                           "no cell of '" + file +
                             "' has this material id; it has: " + present);
        }
    return seeds;
  }



  namespace
  {
    /// Does @p x lie in @p cell (up to a relative tolerance on the
    /// reference coordinates)? Simplices by their barycentric coordinates,
    /// the other cells through their linear mapping.
    template <int dim>
    bool
    cell_contains(const typename Triangulation<dim>::active_cell_iterator &cell,
                  const Point<dim>                                        &x)
    {
      constexpr double    tolerance = 1e-10;
      const ReferenceCell kind      = cell->reference_cell();
      if (kind.is_simplex())
        {
          // x = v0 + sum_i lambda_i (v_i - v0).
          Tensor<2, dim> edges;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int d = 0; d < dim; ++d)
              edges[d][i] = cell->vertex(i + 1)[d] - cell->vertex(0)[d];
          const Tensor<1, dim> lambda = invert(edges) * (x - cell->vertex(0));
          double               sum    = 0;
          for (unsigned int i = 0; i < dim; ++i)
            {
              if (lambda[i] < -tolerance)
                return false;
              sum += lambda[i];
            }
          return sum <= 1 + tolerance;
        }
      try
        {
          const Point<dim> xi = kind.template get_default_linear_mapping<dim>()
                                  .transform_real_to_unit_cell(cell, x);
          return kind.contains_point(xi, tolerance);
        }
      catch (const typename Mapping<dim>::ExcTransformationFailed &)
        {
          return false; // far outside a distorted cell
        }
    }
  } // namespace


  template <int dim>
  MeshSeeds<dim>
  lattice_seeds_in_mesh(const std::string                  &file,
                        const std::set<types::material_id> &material_ids,
                        const Point<dim>                   &origin,
                        const Tensor<1, dim>               &spacing,
                        const std::string                  &path)
  {
    Triangulation<dim> mesh;
    read_mesh(file, path, mesh);
    double volume = 1;
    for (unsigned int d = 0; d < dim; ++d)
      volume *= spacing[d];
    // A lattice node on a face shared by two cells is taken once.
    std::set<std::array<long, dim>> taken;
    MeshSeeds<dim>                  seeds;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        if (!material_ids.empty() &&
            material_ids.count(cell->material_id()) == 0)
          continue;
        const BoundingBox<dim> box = cell->bounding_box();
        std::array<long, dim>  first, last;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const auto [low, high] =
              std::make_pair(box.get_boundary_points().first[d],
                             box.get_boundary_points().second[d]);
            first[d] = std::ceil((low - origin[d]) / spacing[d] - 0.5);
            last[d]  = std::floor((high - origin[d]) / spacing[d] - 0.5);
          }
        bool empty = false;
        for (unsigned int d = 0; d < dim; ++d)
          empty |= first[d] > last[d];
        if (empty)
          continue; // a cell between two lattice nodes
        std::array<long, dim> index = first;
        while (index[dim - 1] <= last[dim - 1])
          {
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = origin[d] + (index[d] + 0.5) * spacing[d];
            if (taken.count(index) == 0 && cell_contains<dim>(cell, x))
              {
                taken.insert(index);
                seeds.positions.push_back(x);
                seeds.volumes.push_back(volume);
              }
            // The next lattice node of the box, first index fastest.
            unsigned int d = 0;
            while (d < dim && ++index[d] > last[d])
              {
                if (d + 1 < dim)
                  index[d] = first[d];
                ++d;
              }
          }
      }
    return seeds;
  }

  template MeshSeeds<1>
  seeds_from_mesh<1>(const std::string &,
                     const std::set<types::material_id> &,
                     const std::set<types::boundary_id> &,
                     const unsigned int,
                     const std::string &);
  template MeshSeeds<2>
  seeds_from_mesh<2>(const std::string &,
                     const std::set<types::material_id> &,
                     const std::set<types::boundary_id> &,
                     const unsigned int,
                     const std::string &);
  template MeshSeeds<3>
  seeds_from_mesh<3>(const std::string &,
                     const std::set<types::material_id> &,
                     const std::set<types::boundary_id> &,
                     const unsigned int,
                     const std::string &);
  template MeshSeeds<1>
  lattice_seeds_in_mesh<1>(const std::string &,
                           const std::set<types::material_id> &,
                           const Point<1> &,
                           const Tensor<1, 1> &,
                           const std::string &);
  template MeshSeeds<2>
  lattice_seeds_in_mesh<2>(const std::string &,
                           const std::set<types::material_id> &,
                           const Point<2> &,
                           const Tensor<1, 2> &,
                           const std::string &);
  template MeshSeeds<3>
  lattice_seeds_in_mesh<3>(const std::string &,
                           const std::set<types::material_id> &,
                           const Point<3> &,
                           const Tensor<1, 3> &,
                           const std::string &);
} // namespace mpm
