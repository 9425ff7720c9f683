#ifndef mpm_bodies_body_parameters_h
#define mpm_bodies_body_parameters_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/background_grid.h>
#include <mpm/bodies/mesh_seeds.h>
#include <mpm/bodies/shape.h>
#include <mpm/materials/material.h>

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * One body of the scene: a shape filled with material points on a
   * lattice of n^dim points per grid cell, or the cells of a mesh file with
   * a point at each Gauss point.
   */
  /// The share of a body's loaded surface one point carries: its area
  /// vector N dA (zero off the surface) and where it lies relative to the
  /// point. The offset is set for a face of a lattice-filled shape only:
  /// there the surface lies half a spacing beyond the outer points, and
  /// loading it there rather than at the points removes the stress
  /// oscillation between the two points of a cell (column error 0.086 ->
  /// 0.032). A mesh body's face Gauss points hand their area to a point
  /// within a tenth of a mesh cell, and on the curved, grid-cutting faces
  /// measured (thick cylinder) the offset pushes load onto light nodes
  /// beyond the surface: 3.1 % error against 1.0 % without, so it is zero
  /// there.
  template <int dim>
  struct SurfaceShare
  {
    Tensor<1, dim> area, offset;
  };


  template <int dim>
  struct BodyParameters
  {
    /// Declares subsection "Body <index>" of section "Bodies".
    static void
    declare_parameters(ParameterHandler &prm, const unsigned int index);
    /// Parses that subsection, fills a mesh body's seeds and creates the
    /// body's material; @p grid places the body in the background grid.
    void
    parse_parameters(ParameterHandler          &prm,
                     const unsigned int         index,
                     const GridParameters<dim> &grid);

    std::string name;         ///< "Bodies/Body 0", for messages
    std::string density_text; ///< 'density' as the scene gives it
    std::string shape_name;   ///< the scene's 'shape'
    /// The closed-form shape; null for a body read from a mesh file.
    std::shared_ptr<const Shape<dim>> shape;
    /// A mesh body's points, sorted by grid cell; null for a shape.
    std::shared_ptr<const MeshSeeds<dim>> mesh_seeds;
    /// Keep only the part inside the grid (a body cut by symmetry planes);
    /// otherwise the whole body must lie inside.
    bool clip_to_grid;
    /// A box around the body (the box itself for shape 'box').
    Point<dim>               lower_corner, upper_corner;
    GridParameters<dim>      grid;
    unsigned int             particles_per_cell; ///< per direction
    double                   density;
    std::vector<std::string> initial_velocity; ///< one expression per component
    /// Displacement at t = 0 from the reference shape; "0" if none.
    std::vector<std::string> initial_displacement;
    /// Stress at t = 0, Cauchy, tension positive: expressions in x, y, z
    /// for xx; yy; zz; xy (2D), and yz; xz (3D); "0" if none.
    std::vector<std::string> initial_stress;
    /// Body force per unit mass, b(X, t): expressions in the initial
    /// position X = (x, y, z) and time t; null if zero.
    std::shared_ptr<FunctionParser<dim>> body_force;
    /// Pressure on the body's loaded surface, p(x, t); null if none.
    std::shared_ptr<FunctionParser<dim>> pressure;
    /// Traction (force per area) on the loaded surface, t(x, t); null if
    /// none.
    std::shared_ptr<FunctionParser<dim>> traction;
    /// A shape's loaded surface: the outer layer of points at a face of
    /// its bounding box (2 axis + 1 for the upper face), or the points
    /// where @p loaded_points is > 0; neither for a mesh body, whose
    /// surface is its 'pressure boundary ids'.
    std::string  loaded_surface; ///< as given
    unsigned int loaded_face = numbers::invalid_unsigned_int;
    std::shared_ptr<FunctionParser<dim>> loaded_points;
    /// A rigid body's prescribed velocity v(t) (expressions in t); null for
    /// a deformable body. A rigid body keeps its shape and moves with it,
    /// acting on the others through contact (see contact/multi_field.h).
    std::shared_ptr<FunctionParser<dim>> rigid_velocity;
    /// The scene's named constants, for every expression.
    std::map<std::string, double>  constants;
    std::string                    material_name;
    std::shared_ptr<Material<dim>> material;

    /// A mesh body with fewer points than the grid cells it covers (a
    /// coarse mesh with Gauss points): the warning to print; empty if not.
    std::string
    sparse_points_warning() const;

    /// Does the body start displaced from its shape?
    bool
    is_displaced() const;

    /// Does the body start with a stress?
    bool
    is_prestressed() const;

    /// The density J = V rho0 / m refers to: 0 for a rigid body, whose
    /// points keep their volume and have no stress to update.
    double
    deformable_density() const
    {
      return rigid_velocity ? 0. : density;
    }

    /// Does a pressure or traction act on the body's surface?
    bool
    has_surface_loads() const
    {
      return pressure || traction;
    }

    /// Call visit(x, xi, volume, surface) for each point this body seeds in
    /// the grid cell with lower corner @p cell_origin (x real, xi reference,
    /// surface: the SurfaceShare the point carries).
    template <typename Visitor>
    void
    for_each_seed(const Point<dim> &cell_origin, const Visitor &visit) const;

    /// How many points this body seeds in that cell (for load balance).
    unsigned int
    count_seeds(const Point<dim> &cell_origin) const;

  private:
    void
    parse_mesh(const ParameterHandler &prm);
    void
    parse_shape(const ParameterHandler &prm);
    /// The loaded surface and the pressure and traction on it.
    void
    parse_surface_loads(const ParameterHandler &prm);
    /// The surface a shape's seed at @p x of volume @p volume carries: none
    /// off the loaded surface. Points picked by an expression have no known
    /// normal: their area lies along x and their offset is zero (traction
    /// uses only the area's length, and pressure is refused there).
    SurfaceShare<dim>
    shape_seed_surface(const Point<dim> &x, const double volume) const;
    /// The first and one-past-last mesh seed in the grid cell at
    /// @p cell_origin.
    std::pair<unsigned int, unsigned int>
    mesh_seed_range(const Point<dim> &cell_origin) const;
  };


  /// BodyParameters::deformable_density() of each of @p bodies, in order
  /// (what the stages that guard J or weight a rigid body by its volume
  /// look up per point).
  template <int dim>
  inline std::vector<double>
  deformable_densities(const std::vector<BodyParameters<dim>> &bodies)
  {
    std::vector<double> densities;
    for (const auto &body : bodies)
      densities.push_back(body.deformable_density());
    return densities;
  }
} // namespace mpm

#endif
