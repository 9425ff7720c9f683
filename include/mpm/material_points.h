#ifndef mpm_material_points_h
#define mpm_material_points_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/background_grid.h>
#include <mpm/bodies/mesh_seeds.h>
#include <mpm/bodies/shape.h>
#include <mpm/field_layout.h>
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

    /// Does the body start displaced from its shape?
    bool
    is_displaced() const;

    /// Does the body start with a stress?
    bool
    is_prestressed() const;

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


  /// What to do with a material point that leaves the grid.
  enum class OutOfGridPolicy
  {
    stop,  ///< stop the run with a message naming the particle
    remove ///< delete it and count it in the statistics
  };


  /**
   * The material points: deal.II's ParticleHandler, the scene's field
   * layout, and the two operations that manage particles as a set:
   * filling bodies at the start, and relocating points after they moved.
   */
  template <int dim>
  class MaterialPoints
  {
  public:
    MaterialPoints(const BackgroundGrid<dim>              &grid,
                   const std::vector<BodyParameters<dim>> &bodies,
                   const FieldRequests                    &requests,
                   MPI_Comm                                comm);

    Particles::ParticleHandler<dim> &
    handler()
    {
      return particles;
    }
    const Particles::ParticleHandler<dim> &
    handler() const
    {
      return particles;
    }
    const FieldLayout &
    layout() const
    {
      return fields;
    }
    const std::vector<BodyParameters<dim>> &
    bodies() const
    {
      return body_list;
    }

    /// Fill every body with points; fails if a body gets none, or if an
    /// initial stress gives a point a state outside @p J_bounds (the run's
    /// guard on V / V0) or one that is not finite.
    void
    generate(const bool                   may_overlap = false,
             const std::array<double, 2> &J_bounds    = {
                  {0., std::numeric_limits<double>::infinity()}});

    /// Instead of generate(): take the points back from the checkpoint the
    /// grid was loaded from, with the smallest point mass of the
    /// generation.
    void
    restore(const double minimum_point_mass);

    /**
     * Call @p f with every locally owned point, tile by tile in the grid's
     * order (the order of the step's loops). The handler's own order
     * differs after a restart (points come back sorted by cell), and sums
     * that cancel, like the momentum, would then differ in their last bits.
     */
    template <typename Function>
    void
    for_each_by_cell(const Function &f) const
    {
      for (const unsigned int index : grid.locally_owned_tiles())
        for (const auto &p : particles.particles_in_cell(grid.tile(index)))
          f(p);
    }

    /**
     * Put points back in their tiles after their positions changed: move
     * those that left their tile (a point that changes cell within its
     * tile stays where it is stored), send those that reached a neighbour
     * rank's tile there, and only if one went further run deal.II's
     * collective sort. Returns the number of points
     * removed because they left the grid (policy remove); with policy stop it
     * throws RunError naming the first such point.
     */
    types::particle_index
    relocate(const OutOfGridPolicy policy);

    /// How often relocation ran deal.II's collective sort (a point reached
    /// another rank's cell).
    unsigned int
    n_collective_sorts() const
    {
      return n_full_sorts;
    }

    /**
     * Put the points' data back in the order the step's loops visit them
     * (for_each_by_cell), in place: each point that is out of order moves
     * once, through one free slot of deal.II's property pool, and keeps
     * its place in its tile, so no sum changes by a bit. Local to the
     * rank. Returns the number of points moved. relocate() calls it once
     * the points appended since the last re-pack pass a fraction of them.
     */
    types::particle_index
    restore_memory_order();

    /// How often relocation re-packed the points' data (on this rank).
    unsigned int
    n_memory_repacks() const
    {
      return n_repacks;
    }

    /// Smallest point mass in the scene (for the small-mass guard).
    double
    min_particle_mass() const
    {
      return minimum_mass;
    }

  private:
    /// The scene's requests plus what the bodies' materials store.
    FieldLayout
    assemble_layout(FieldRequests requests) const;
    /// Give a new point at @p x of @p body its material's initial state,
    /// with the initial stress @p stress (null: none).
    /// A failure is noted in state_failure (raised collectively).
    void
    initialise_state(const BodyParameters<dim> &body,
                     FunctionParser<dim>       *stress,
                     const Point<dim>          &x,
                     double                    *properties);
    /// Throw a std::domain_error if the state a point of @p body starts
    /// with is one the first step would stop on.
    void
    check_initial_state(const BodyParameters<dim> &body,
                        const double              *properties) const;
    /// Apply the initial displacement to the point with reference position
    /// @p X and properties @p properties (F, volume); return where it starts.
    /// A displacement that inverts the body or moves the point out of the
    /// grid is noted in state_failure.
    Point<dim>
    displace(const FunctionParser<dim> &displacement,
             const Point<dim>          &X,
             double                    *properties);
    /// What relocate() found: the points that leave their tile (in
    /// visiting order, with their tiles, and whether they went to another
    /// rank) and the data of those that arrive in a tile of this rank
    /// (location, reference location, id, properties).
    struct Moves
    {
      using iterator =
        typename Particles::ParticleHandler<dim>::particle_iterator;
      void
      leave(const iterator    &p,
            const unsigned int tile,
            const bool         to_other_rank);
      void
      arrive(const unsigned int             tile,
             const Point<dim>              &x,
             const Point<dim>              &xi,
             const types::particle_index    id,
             const ArrayView<const double> &properties);

      std::vector<iterator>                             leavers;
      std::vector<unsigned int>                         leaver_tile;
      std::vector<bool>                                 to_rank;
      std::vector<std::pair<unsigned int, std::size_t>> arrivals; // tile, at
      std::vector<double>                               data;
    };
    /// Add the points other ranks sent to this one in relocate() (per
    /// rank, each as relocate() buffers a point) to @p moves.
    void
    receive_points(const std::map<unsigned int, std::vector<double>> &received,
                   Moves &moves) const;
    /// Carry out @p moves (without the points sent to other ranks if
    /// @p keep_sent).
    void
    settle(Moves &moves, const bool keep_sent);
    std::string
    describe_leaving_point(
      const typename Particles::ParticleHandler<dim>::particle_iterator &p)
      const;
    /// GridParameters::put_back_behind_closed_face() for point @p p; true
    /// if it was put back, with its @p cell and reference location @p xi.
    bool
    put_back_on_closed_face(
      typename Particles::ParticleHandler<dim>::particle_iterator &p,
      typename BackgroundGrid<dim>::CellCoordinates               &cell,
      Point<dim>                                                  &xi);

    const BackgroundGrid<dim> &grid;
    /// A diagnosis if the point @p x of body @p b lies inside another
    /// body's shape (mesh bodies are not checked), else empty.
    std::string
    overlap_at(const unsigned int b, const Point<dim> &x) const;

    const std::vector<BodyParameters<dim>> body_list;
    MPI_Comm                               comm;
    const FieldLayout                      fields;
    Particles::ParticleHandler<dim>        particles;
    double                                 minimum_mass;
    unsigned int                           n_full_sorts = 0;
    unsigned int                           n_repacks    = 0;
    /// Points appended to a tile (stored wherever the pool had room)
    /// since their data were last put in visiting order, and the fraction
    /// of the points beyond which relocate() does it again.
    types::particle_index   appended_since_repack  = 0;
    static constexpr double memory_order_tolerance = 0.05;
    std::string             state_failure;
    std::array<double, 2>   J_bounds;
  };
} // namespace mpm

#endif
