#ifndef mpm_bodies_mesh_seeds_h
#define mpm_bodies_mesh_seeds_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <set>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /// Material points of a body read from a mesh: where, and how much volume.
  template <int dim>
  struct MeshSeeds
  {
    std::vector<Point<dim>> positions;
    std::vector<double>     volumes;
    /// With loaded boundaries: each point's share N dA of their area
    /// (outward normal), zero for points away from them; else empty.
    std::vector<Tensor<1, dim>> areas;
    /// The background-grid cell of each seed; the body sorts the seeds by
    /// it, so that a cell finds its seeds by binary search.
    std::vector<unsigned int> cells;
  };

  /**
   * Read the mesh @p file (any format deal.II's GridIn knows, chosen by the
   * file's extension: gmsh .msh, .vtk, .inp, .ucd, ...) and put a point at
   * each of the n^dim Gauss points of every cell whose material id is in
   * @p material_ids (all cells if empty), with the volume JxW of that
   * point. Gauss points lie inside their cells and integrate the cell's
   * volume exactly, so the body's mass is right for any cell shape.
   * @p path names the body's parameters in the InputError a missing or
   * unreadable file, or a material id no cell has, gives.
   */
  template <int dim>
  MeshSeeds<dim>
  seeds_from_mesh(const std::string                  &file,
                  const std::set<types::material_id> &material_ids,
                  const std::set<types::boundary_id> &loaded_boundary_ids,
                  const unsigned int                  n,
                  const std::string                  &path);

  /**
   * Read the mesh @p file as seeds_from_mesh() does, and put a point at
   * every node of the lattice of spacing @p spacing (offset by half a
   * spacing from @p origin: the grid's cells with n points per direction,
   * where the shapes put theirs) that lies in a cell of the mesh with the
   * material ids asked for, with the lattice's volume. The body then has
   * the grid's resolution whatever the mesh's; its boundary is the mesh's
   * to within half a spacing.
   */
  template <int dim>
  MeshSeeds<dim>
  lattice_seeds_in_mesh(const std::string                  &file,
                        const std::set<types::material_id> &material_ids,
                        const Point<dim>                   &origin,
                        const Tensor<1, dim>               &spacing,
                        const std::string                  &path);
} // namespace mpm

#endif
