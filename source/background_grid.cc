#include <deal.II/base/index_set.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_tools.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/background_grid.h>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <map>
#include <mpm/parameters.h>
#include <sstream>

namespace mpm
{
  namespace
  {
    /// MemAvailable of /proc/meminfo in bytes; 0 if it cannot be read.
    double
    available_memory_bytes()
    {
      std::ifstream meminfo("/proc/meminfo");
      std::string   key;
      double        kb;
      std::string   unit;
      while (meminfo >> key >> kb >> unit)
        if (key == "MemAvailable:")
          return kb * 1024.;
      return 0.;
    }
  } // namespace


  namespace
  {
    const char *face_names[] =
      {"x min", "x max", "y min", "y max", "z min", "z max"};
  }


  std::string
  face_name(const unsigned int face)
  {
    return face_names[face];
  }


  template <int dim>
  void
  GridParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Grid");
    prm.declare_entry("lower corner",
                      "0",
                      Patterns::Anything(),
                      "Lower corner of the box, one value per dimension "
                      "(comma-separated) or one value for all.");
    prm.declare_entry("upper corner",
                      "1",
                      Patterns::Anything(),
                      "Upper corner of the box.");
    prm.declare_entry("cells",
                      "16",
                      Patterns::Anything(),
                      "Number of cells in each direction (one value for "
                      "all, or one per dimension).");
    for (unsigned int f = 0; f < 6; ++f)
      prm.declare_entry(std::string("boundary ") + face_names[f],
                        "default",
                        Patterns::Selection(boundary_names.selection() +
                                            "|default"),
                        "Velocity condition on this face of the box: "
                        "default (free on the top face, y max in 2D and z "
                        "max in 3D, where a slope or a pile has nothing to "
                        "hold it; slip on the others), free, "
                        "fixed (all components zero), slip (normal "
                        "component zero), friction (Coulomb contact with "
                        "'friction coefficient': no flow into the face, "
                        "free separation, the tangential velocity reduced "
                        "by at most mu times the normal velocity removed, "
                        "never reversed) or absorbing (viscous dashpots "
                        "rho c_p on the normal and rho c_s on the tangential "
                        "velocity, from 'absorbing body', so that waves "
                        "leave the grid: the face of a half-space). Faces "
                        "beyond the dimension are ignored.");
    prm.declare_entry("friction coefficient",
                      "0.5",
                      Patterns::Anything(),
                      "Coulomb coefficient mu >= 0 of the faces of type "
                      "friction (tan of the basal friction angle).");
    prm.declare_entry("cells per tile",
                      "auto",
                      Patterns::Anything(),
                      "Grid cells per edge of a tile, the unit deal.II "
                      "stores, partitions and balances (T^dim cells): 1, 2, "
                      "4 or 8, dividing 'cells' in every direction, or auto "
                      "(the largest of 4, 2, 1 that does). Larger tiles "
                      "need less memory per cell (a tile costs about as "
                      "much as 16 material points) and coarser load "
                      "balancing; the answer does not depend on it.");
    prm.declare_entry("load imbalance limit",
                      "0.1",
                      Patterns::Anything(),
                      "With several MPI ranks: the largest imbalance of "
                      "work (a rank's work / the mean - 1; a point weighs "
                      "30 grid nodes) before the grid is repartitioned by "
                      "the points each tile holds, with the points moving "
                      "along (checked before every step; material that "
                      "travels leaves its first partition behind). 0: "
                      "never repartition.");
    prm.declare_entry("absorbing body",
                      "0",
                      Patterns::Anything(),
                      "Index of the body whose density and material (p- "
                      "and s-wave speeds of its small-strain moduli) set "
                      "the impedances of the absorbing faces: the body "
                      "that meets them.");
    prm.leave_subsection();
  }


  template <int dim>
  Tensor<1, dim>
  GridParameters<dim>::cell_size() const
  {
    Tensor<1, dim> h;
    for (unsigned int d = 0; d < dim; ++d)
      h[d] = (upper_corner[d] - lower_corner[d]) / n_cells[d];
    return h;
  }


  template <int dim>
  unsigned int
  GridParameters<dim>::locate(const Point<dim> &x, Point<dim> &reference) const
  {
    Tensor<1, dim> inverse_cell_size;
    for (unsigned int d = 0; d < dim; ++d)
      inverse_cell_size[d] = 1. / cell_size()[d];
    std::array<unsigned int, dim> cell;
    return locate_in_lattice<dim>(
             x, lower_corner, inverse_cell_size, n_cells, cell, reference)
             ? lexicographic_index<dim>(cell, n_cells)
             : numbers::invalid_unsigned_int;
  }


  template <int dim>
  bool
  GridParameters<dim>::put_back_behind_closed_face(
    Point<dim>     &x,
    Tensor<1, dim> &velocity) const
  {
    const auto closed = [this](const unsigned int face) {
      return closes_the_grid(boundary[face]);
    };
    const Tensor<1, dim> h = cell_size();
    Point<dim>           y = x;
    Tensor<1, dim>       v = velocity;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double behind_lower = lower_corner[d] - y[d];
        const double behind_upper = y[d] - upper_corner[d];
        // The lattice counts the upper face as outside: a point put back
        // there lands a hair inside.
        if (behind_lower > 0)
          {
            if (!closed(2 * d) || !(behind_lower < 0.25 * h[d]))
              return false;
            y[d] = lower_corner[d];
            v[d] = std::max(v[d], 0.);
          }
        else if (behind_upper >= 0)
          {
            if (!closed(2 * d + 1) || !(behind_upper < 0.25 * h[d]))
              return false;
            y[d] = upper_corner[d] - 1e-9 * h[d];
            v[d] = std::min(v[d], 0.);
          }
        else if (!(behind_lower <= 0 && behind_upper < 0))
          return false; // NaN
      }
    x        = y;
    velocity = v;
    return true;
  }


  /**
   * The number of coarse cells of the grid with tiles of @p T cells: the
   * tiles are the cells of a coarse mesh refined globally as often as
   * every direction's tile count is divisible by 2 (refinements), and
   * p4est keeps every coarse cell on every rank.
   */
  template <int dim>
  std::pair<std::array<unsigned int, dim>, unsigned int>
  coarse_mesh_of_tiles(const std::array<unsigned int, dim> &n_cells,
                       const unsigned int                   T)
  {
    std::array<unsigned int, dim> coarse;
    unsigned int                  refinements = 32;
    for (unsigned int d = 0; d < dim; ++d)
      {
        coarse[d]      = n_cells[d] / T;
        unsigned int k = 0;
        while (coarse[d] % (2u << k) == 0)
          ++k;
        refinements = std::min(refinements, k);
      }
    for (unsigned int d = 0; d < dim; ++d)
      coarse[d] >>= refinements;
    return {coarse, refinements};
  }


  /**
   * A grid that cannot fit stops here with the parameter named, instead of
   * ending in std::bad_alloc or taking the machine's memory. Measured
   * (peak resident memory less the points, one rank): the refined tiles
   * with their DoFs, tables and nodal vectors cost about 150 bytes per
   * grid cell in 2D and 200 in 3D, divided among the ranks; a coarse cell,
   * which every rank keeps, about 1 kB (2D) and 2 kB (3D).
   */
  template <int dim>
  void
  GridParameters<dim>::check_grid_fits_in_memory(
    const std::string &cells_text) const
  {
    double n = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n *= n_cells[d];
    const auto coarse   = coarse_mesh_of_tiles<dim>(n_cells, tile_size).first;
    double     n_coarse = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_coarse *= coarse[d];
    const double per_cell   = dim == 1 ? 100. : dim == 2 ? 150. : 200.;
    const double per_coarse = dim == 1 ? 300. : dim == 2 ? 1000. : 2000.;
    const double ranks_here =
      Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD); // upper bound
    const double needed    = n * per_cell + n_coarse * per_coarse * ranks_here;
    const double available = available_memory_bytes();
    if (n > 2147483647. || (available > 0 && needed > available))
      {
        std::ostringstream why;
        why << std::setprecision(3) << n << " cells need about " << needed / 1e9
            << " GB for the grid on this machine (" << per_cell
            << " bytes per cell, and " << per_coarse / 1e3 << " kB on each "
            << "rank for each of the " << n_coarse
            << " coarse cells), more than the " << available / 1e9
            << " GB available: use fewer cells, or cell counts divisible by "
               "a higher power of 2 (fewer coarse cells)";
        throw InputError("Grid/cells", cells_text, why.str());
      }
  }


  /// The tile size asked for by 'Grid/cells per tile' (see its
  /// documentation).
  template <int dim>
  unsigned int
  parse_tile_size(const std::string                   &text,
                  const std::array<unsigned int, dim> &n_cells)
  {
    const auto divides_all = [&](const unsigned int T) {
      for (unsigned int d = 0; d < dim; ++d)
        if (n_cells[d] % T != 0)
          return false;
      return true;
    };
    if (text == "auto")
      return divides_all(4) ? 4 : divides_all(2) ? 2 : 1;
    for (const unsigned int T : {1u, 2u, 4u, 8u})
      if (text == std::to_string(T))
        {
          if (!divides_all(T))
            throw InputError("Grid/cells per tile",
                             text,
                             "must divide 'Grid/cells' in every direction "
                             "(or use auto)");
          return T;
        }
    throw InputError("Grid/cells per tile", text, "must be 1, 2, 4, 8 or auto");
  }


  /**
   * A cell must be a size the arithmetic can work with: its area and volume,
   * and the sizes and masses of the points in it, normal numbers (a grid
   * 1e-308 m across had subnormal cells, and the run failed in an
   * eigensolver naming nothing, issue 32), and its corners apart in the
   * coordinates' precision.
   */
  template <int dim>
  void
  GridParameters<dim>::check_cells_are_resolved(
    const std::string &upper_corner_text) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double h = (upper_corner[d] - lower_corner[d]) / n_cells[d];
        const double coordinate =
          std::max(std::abs(lower_corner[d]), std::abs(upper_corner[d]));
        if (!(h >= 1e-50) || !(h >= 1e-10 * coordinate))
          {
            std::ostringstream msg;
            msg << "with 'Grid/lower corner' and 'Grid/cells' gives cells " << h
                << " m wide in direction " << d
                << ": a cell must be at least 1e-50 m and 1e-10 of its "
                   "corners' distance from the origin ("
                << 1e-10 * coordinate << " m here)";
            throw InputError("Grid/upper corner", upper_corner_text, msg.str());
          }
      }
  }


  template <int dim>
  void
  GridParameters<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Grid");
    lower_corner = Parse::point<dim>(prm, "Grid", "lower corner");
    upper_corner = Parse::point<dim>(prm, "Grid", "upper corner");
    // (Parse::point keeps them within 1e15: a corner at 1e308 overflowed
    // squared distances and cell volumes.)
    for (unsigned int d = 0; d < dim; ++d)
      if (!(upper_corner[d] > lower_corner[d]))
        throw InputError("Grid/upper corner",
                         prm.get("upper corner"),
                         "must exceed 'Grid/lower corner' in every direction");
    const auto cells = Parse::double_list(prm, "Grid", "cells", dim);
    for (unsigned int d = 0; d < dim; ++d)
      {
        if (cells[d] < 1 || cells[d] > 1e5 || cells[d] != std::floor(cells[d]))
          throw InputError("Grid/cells",
                           prm.get("cells"),
                           "must be whole numbers in [1, 100000]");
        n_cells[d] = static_cast<unsigned int>(cells[d]);
      }
    check_cells_are_resolved(prm.get("upper corner"));
    tile_size = parse_tile_size<dim>(prm.get("cells per tile"), n_cells);
    imbalance_limit =
      Parse::bounded_double(prm, "Grid", "load imbalance limit", 0, 1e300);
    check_grid_fits_in_memory(prm.get("cells"));
    for (unsigned int f = 0; f < 2 * dim; ++f)
      {
        const std::string kind =
          prm.get(std::string("boundary ") + face_names[f]);
        // The face above the scene is open unless the scene closes it.
        const bool top = dim > 1 && f == 2 * dim - 1;
        boundary[f]    = kind != "default" ? boundary_names.value(kind)
                         : top             ? BoundaryType::free
                                           : BoundaryType::slip;
      }
    friction_coefficient =
      Parse::bounded_double(prm, "Grid", "friction coefficient", 0, 1e300);
    const double body =
      Parse::bounded_double(prm, "Grid", "absorbing body", 0, 1000);
    if (body != std::floor(body))
      throw InputError("Grid/absorbing body",
                       prm.get("absorbing body"),
                       "must be a body index, a whole number >= 0");
    absorbing_body = static_cast<unsigned int>(body);
    prm.leave_subsection();
  }



  template <int dim>
  BackgroundGrid<dim>::BackgroundGrid(
    const GridParameters<dim>                             &parameters,
    MPI_Comm                                               comm,
    const std::function<unsigned int(const Point<dim> &)> &work_estimate,
    const std::string                                     &restart_file)
    : prm(parameters)
    , comm(comm)
    , work_estimate(work_estimate)
    , T(parameters.tile_size)
    , log2_T(parameters.tile_size == 1   ? 0
             : parameters.tile_size == 2 ? 1
             : parameters.tile_size == 4 ? 2
                                         : 3)
    // Equidistant support points: the DoFs of a tile are the grid's nodes.
    , fe(QIterated<1>(QTrapezoid<1>(), parameters.tile_size))
  {
    // p4est needs dim >= 2; a 1D grid is serial (verification problems).
    if constexpr (dim == 1)
      {
        if (Utilities::MPI::n_mpi_processes(comm) > 1)
          throw InputError("Simulation/dimension",
                           "1",
                           "runs on one MPI rank only (deal.II has no "
                           "distributed 1D triangulation)");
        tria = std::make_unique<Triangulation<dim>>();
      }
    else
      tria = std::make_unique<parallel::distributed::Triangulation<dim>>(comm);

    h = prm.cell_size();
    for (unsigned int d = 0; d < dim; ++d)
      {
        inv_h[d]   = 1. / h[d];
        n_tiles[d] = prm.n_cells[d] / T;
      }
    const auto [coarse, refinements] =
      coarse_mesh_of_tiles<dim>(prm.n_cells, T);
    std::vector<unsigned int> repetitions(coarse.begin(), coarse.end());
    // colorize: face f of the box gets boundary id f (x-, x+, y-, ...),
    // which the refined cells inherit.
    GridGenerator::subdivided_hyper_rectangle(
      *tria, repetitions, prm.lower_corner, prm.upper_corner, true);

    if constexpr (dim > 1)
      if (!restart_file.empty())
        // The refinement and the points come back with the partition; they
        // stay attached for MaterialPoints::restore(). deal.II 9.4 loads
        // with a uniform partition; restore_partition() puts back the work
        // partition once the points are unpacked.
        dynamic_cast<parallel::distributed::Triangulation<dim> &>(*tria).load(
          restart_file);
    if (restart_file.empty())
      {
        tria->refine_global(refinements);
        partition_by_work();
      }

    distribute_nodes();
  }


  template <int dim>
  bool
  BackgroundGrid<dim>::partitions_by_work() const
  {
    return dim > 1 && work_estimate &&
           Utilities::MPI::n_mpi_processes(comm) > 1;
  }


  template <int dim>
  void
  BackgroundGrid<dim>::partition_by_points(
    const std::function<unsigned int(
      const typename Triangulation<dim>::cell_iterator &)> &points_in_tile)
  {
    if constexpr (dim > 1)
      {
        // A point costs about 30 times a node per step; the nodes (one
        // per cell) keep every weight positive, so empty tiles count a
        // little.
        auto &p_tria =
          dynamic_cast<parallel::distributed::Triangulation<dim> &>(*tria);
        const unsigned int nodes_per_tile = Utilities::pow(T, dim);
        auto               connection     = p_tria.signals.weight.connect(
          [&](const typename Triangulation<dim>::cell_iterator &cell,
              const typename Triangulation<dim>::CellStatus) -> unsigned int {
            return nodes_per_tile + 30 * points_in_tile(cell);
          });
        p_tria.repartition();
        connection.disconnect();
      }
  }


  template <int dim>
  void
  BackgroundGrid<dim>::partition_by_work()
  {
    if (partitions_by_work())
      partition_by_points(
        [&](const typename Triangulation<dim>::cell_iterator &cell) {
          unsigned int n = 0;
          for_each_cell_of_tile(tile_of(cell),
                                [&](const CellCoordinates &,
                                    const Point<dim> &corner) {
                                  n += work_estimate(corner);
                                });
          return n;
        });
  }


  template <int dim>
  double
  BackgroundGrid<dim>::local_work(
    const Particles::ParticleHandler<dim, dim> &particles) const
  {
    return double(owned_tiles.size()) * Utilities::pow(T, dim) +
           30. * particles.n_locally_owned_particles();
  }


  template <int dim>
  void
  BackgroundGrid<dim>::repartition(
    Particles::ParticleHandler<dim, dim> &particles)
  {
    if (dim == 1 || Utilities::MPI::n_mpi_processes(comm) == 1)
      return;
    particles.prepare_for_coarsening_and_refinement();
    partition_by_points(
      [&](const typename Triangulation<dim>::cell_iterator &cell) {
        return particles.n_particles_in_cell(cell);
      });
    particles.unpack_after_coarsening_and_refinement();
    distribute_nodes();
  }


  template <int dim>
  void
  BackgroundGrid<dim>::restore_partition(
    Particles::ParticleHandler<dim, dim> &particles)
  {
    // The same weights on the same cells give p4est the same cuts as the
    // run that wrote the checkpoint, so every nodal sum at a rank boundary
    // runs in the same order and the restart is bit for bit (a uniform
    // partition differed in the momentum's last digits).
    if (!partitions_by_work())
      return;
    particles.prepare_for_coarsening_and_refinement();
    partition_by_work();
    particles.unpack_after_coarsening_and_refinement();
    distribute_nodes();
  }


  template <int dim>
  void
  BackgroundGrid<dim>::distribute_nodes()
  {
    dofs.reinit(*tria);
    dofs.distribute_dofs(fe);
    std::vector<types::global_dof_index> global_nodes;
    build_tile_tables(global_nodes);
    const IndexSet &owned = dofs.locally_owned_dofs();
    scalar_partitioner    = std::make_shared<Utilities::MPI::Partitioner>(
      owned, relevant_nodes(global_nodes), comm);
    n_owned_nodes = scalar_partitioner->locally_owned_size();

    // The tiles' nodes as local indices, and the owned nodes' places.
    const IndexSet &ghosts = scalar_partitioner->ghost_indices();
    tile_nodes.resize(global_nodes.size());
    owned_node_lattice.resize(n_owned_nodes);
    for (unsigned int t = 0; t < first_node_entry.size(); ++t)
      if (first_node_entry[t] != invalid)
        {
          const CellCoordinates first = first_cell_of_tile(t);
          for (unsigned int k = 0; k < Utilities::pow(T + 1, dim); ++k)
            {
              const auto    node  = global_nodes[first_node_entry[t] + k];
              unsigned int &local = tile_nodes[first_node_entry[t] + k];
              local = owned.is_element(node) || ghosts.is_element(node)
                        ? scalar_partitioner->global_to_local(node)
                        : invalid;
              if (local < n_owned_nodes)
                owned_node_lattice[local] = lattice_point(first, k, T + 1);
            }
        }

    build_node_blocks();
  }


  template <int dim>
  void
  BackgroundGrid<dim>::build_node_blocks()
  {
    const unsigned int n_block = Utilities::pow(T + 3, dim);
    first_block_entry.assign(first_node_entry.size(), invalid);
    node_blocks.clear();
    for (const unsigned int t : owned_tiles)
      {
        first_block_entry[t]        = node_blocks.size();
        const CellCoordinates first = first_cell_of_tile(t);
        for (unsigned int k = 0; k < n_block; ++k)
          {
            // The node, and the tile among t and its neighbours that holds
            // it (each tile has its own nodes and those of its upper faces).
            // The block starts one node before the tile's first: a node
            // before the grid's first wraps around and counts as outside.
            unsigned int    tile = 0, offset = 0;
            bool            in_grid = true;
            CellCoordinates node    = lattice_point(first, k, T + 3);
            for (unsigned int d = 0; d < dim; ++d)
              {
                --node[d];
                in_grid = in_grid && node[d] <= prm.n_cells[d];
              }
            if (in_grid)
              for (int d = dim - 1; d >= 0; --d)
                {
                  unsigned int u = first[d] >> log2_T;
                  if (node[d] < first[d])
                    --u;
                  else if (node[d] > first[d] + T)
                    ++u;
                  tile   = tile * n_tiles[d] + u;
                  offset = offset * (T + 1) + (node[d] - (u << log2_T));
                }
            node_blocks.push_back(
              in_grid && first_node_entry[tile] != invalid
                ? tile_nodes[first_node_entry[tile] + offset]
                : invalid);
          }
      }
    std::vector<unsigned int>().swap(tile_nodes);
  }


  template <int dim>
  void
  BackgroundGrid<dim>::build_tile_tables(
    std::vector<types::global_dof_index> &global_nodes)
  {
    unsigned int n_total = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_total *= n_tiles[d];
    tiles.assign(n_total, {});
    first_node_entry.assign(n_total, invalid);
    owned_tiles.clear();

    const std::vector<unsigned int> hierarchic =
      FETools::lexicographic_to_hierarchic_numbering<dim>(T);
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    // deal.II's order of the cells follows its refinement tree (a Morton
    // order of the tiles within each coarse cell): the points are stored
    // in it, and the loops visit the tiles in it.
    for (const auto &cell : tria->active_cell_iterators())
      if (cell->is_locally_owned() || cell->is_ghost())
        {
          const unsigned int index = tile_of(cell);
          tiles[index]             = cell;
          if (cell->is_locally_owned())
            owned_tiles.push_back(index);
          typename DoFHandler<dim>::active_cell_iterator(&*tria,
                                                         cell->level(),
                                                         cell->index(),
                                                         &dofs)
            ->get_dof_indices(dof_indices);
          first_node_entry[index] = global_nodes.size();
          for (const unsigned int i : hierarchic)
            global_nodes.push_back(dof_indices[i]);
        }
  }


  template <int dim>
  IndexSet
  BackgroundGrid<dim>::relevant_nodes(
    const std::vector<types::global_dof_index> &global_nodes) const
  {
    // A point in an owned tile reaches nodes up to one beyond the nodes of
    // that tile (the cubic B-spline: nodes i-1 ... i+2 of cell i). Only
    // those nodes of the ghost tiles are kept, so that messages carry what
    // the stencils touch rather than T layers of nodes.
    const auto is_owned_tile = [&](const CellCoordinates &t) {
      const unsigned int index = lexicographic_index<dim>(t, n_tiles);
      return first_node_entry[index] != invalid &&
             tiles[index]->is_locally_owned();
    };
    IndexSet                             relevant = dofs.locally_owned_dofs();
    std::vector<types::global_dof_index> reached;
    for (unsigned int t = 0; t < first_node_entry.size(); ++t)
      if (first_node_entry[t] != invalid && tiles[t]->is_ghost())
        {
          const CellCoordinates first = first_cell_of_tile(t);
          for (unsigned int k = 0; k < Utilities::pow(T + 1, dim); ++k)
            {
              const CellCoordinates node = lattice_point(first, k, T + 1);
              // The owned tiles whose nodes, widened by one, hold it: the
              // tiles around tile t in each direction.
              bool near = false;
              for (unsigned int e = 0; e < Utilities::pow(3u, dim) && !near;
                   ++e)
                {
                  CellCoordinates other;
                  bool            in   = true;
                  unsigned int    code = e;
                  for (unsigned int d = 0; d < dim; ++d, code /= 3)
                    {
                      const int o = static_cast<int>(first[d] / T) +
                                    static_cast<int>(code % 3) - 1;
                      const int lo = o * static_cast<int>(T) - 1;
                      const int hi = (o + 1) * static_cast<int>(T) + 1;
                      in = in && o >= 0 && o < static_cast<int>(n_tiles[d]) &&
                           static_cast<int>(node[d]) >= lo &&
                           static_cast<int>(node[d]) <= hi;
                      other[d] = o;
                    }
                  near = in && is_owned_tile(other);
                }
              if (near)
                reached.push_back(global_nodes[first_node_entry[t] + k]);
            }
        }
    std::sort(reached.begin(), reached.end());
    reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
    relevant.add_indices(reached.begin(), reached.end());
    relevant.compress();
    return relevant;
  }


  template <int dim>
  double
  BackgroundGrid<dim>::min_cell_size() const
  {
    double m = h[0];
    for (unsigned int d = 1; d < dim; ++d)
      m = std::min(m, h[d]);
    return m;
  }


  template <int dim>
  types::global_cell_index
  BackgroundGrid<dim>::n_cells() const
  {
    types::global_cell_index n = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n *= prm.n_cells[d];
    return n;
  }


  template <int dim>
  unsigned int
  BackgroundGrid<dim>::locate(const Point<dim> &x, Point<dim> &reference) const
  {
    CellCoordinates cell;
    return locate(x, cell, reference)
             ? lexicographic_index<dim>(cell, prm.n_cells)
             : invalid;
  }


  template <int dim>
  bool
  BackgroundGrid<dim>::contains(const Point<dim> &lower,
                                const Point<dim> &upper) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (lower[d] < prm.lower_corner[d] || upper[d] > prm.upper_corner[d])
        return false;
    return true;
  }


  template <int dim>
  double
  BackgroundGrid<dim>::node_support_volume(const unsigned int i) const
  {
    const CellCoordinates c      = owned_node_lattice[i];
    double                volume = 1;
    for (unsigned int d = 0; d < dim; ++d)
      volume *= (c[d] == 0 || c[d] == prm.n_cells[d] ? 0.5 : 1.) * h[d];
    return volume;
  }


  template <int dim>
  std::vector<unsigned int>
  BackgroundGrid<dim>::owned_nodes_in_box(const Point<dim> &lower,
                                          const Point<dim> &upper) const
  {
    // A node counts if it lies in the box up to a thousandth of a cell, so
    // that a box drawn on grid lines includes them.
    std::vector<unsigned int> nodes;
    for (unsigned int i = 0; i < n_owned_nodes; ++i)
      {
        const CellCoordinates c  = owned_node_lattice[i];
        bool                  in = true;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double x = prm.lower_corner[d] + c[d] * h[d];
            in =
              in && x >= lower[d] - 1e-3 * h[d] && x <= upper[d] + 1e-3 * h[d];
          }
        if (in)
          nodes.push_back(i);
      }
    return nodes;
  }


  template <int dim>
  std::shared_ptr<const Utilities::MPI::Partitioner>
  BackgroundGrid<dim>::make_partitioner(const unsigned int n_components) const
  {
    // Node i, component c has index n_components*i + c, so the local
    // numbering of this partitioner is n_components*(scalar local) + c.
    const auto &owned_nodes = scalar_partitioner->locally_owned_range();
    const auto &ghost_nodes = scalar_partitioner->ghost_indices();
    const auto  n           = n_components * owned_nodes.size();
    IndexSet    owned(n), ghosts(n);
    for (const auto i : owned_nodes)
      owned.add_range(n_components * i, n_components * (i + 1));
    for (const auto i : ghost_nodes)
      ghosts.add_range(n_components * i, n_components * (i + 1));
    owned.compress();
    ghosts.compress();
    return std::make_shared<Utilities::MPI::Partitioner>(owned, ghosts, comm);
  }


  template struct GridParameters<1>;
  template struct GridParameters<2>;
  template struct GridParameters<3>;
  template class BackgroundGrid<1>;
  template class BackgroundGrid<2>;
  template class BackgroundGrid<3>;
} // namespace mpm
