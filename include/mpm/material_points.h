#ifndef mpm_material_points_h
#define mpm_material_points_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/background_grid.h>
#include <mpm/bodies/body_parameters.h>
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

    /// A stage resets displacements: every point's current position becomes
    /// the origin its displacement output counts from (nothing if the
    /// points do not store one).
    void
    reset_displacement_origin();

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
