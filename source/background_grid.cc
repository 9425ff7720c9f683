#include <deal.II/base/index_set.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_tools.h>

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
                        "slip",
                        Patterns::Selection(
                          "free|fixed|slip|friction|absorbing"),
                        "Velocity condition on this face of the box: free, "
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
    return locate_in_lattice<dim>(
      x, lower_corner, inverse_cell_size, n_cells, reference);
  }


  /**
   * Every cell of the grid is a coarse cell, and p4est keeps every coarse
   * cell on every rank: the grid's memory per rank does not fall with the
   * number of ranks. Measured (peak resident memory of a run, less its
   * points): about 1.6 kB per cell in 2D and 2.5 kB in 3D. A grid that
   * cannot fit stops here with the parameter named, instead of ending in
   * std::bad_alloc or taking the machine's memory.
   */
  template <int dim>
  void
  GridParameters<dim>::check_grid_fits_in_memory(
    const std::string &cells_text) const
  {
    double n = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n *= n_cells[d];
    const double bytes_per_cell = dim == 1 ? 500. : dim == 2 ? 1600. : 2500.;
    const double ranks_here =
      Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD); // upper bound
    const double needed    = n * bytes_per_cell * ranks_here;
    const double available = available_memory_bytes();
    if (n > 2147483647. || (available > 0 && needed > available))
      {
        std::ostringstream why;
        why << std::setprecision(3) << n << " cells need about " << needed / 1e9
            << " GB for the grid on this machine (" << bytes_per_cell / 1e3
            << " kB per cell on each rank; every rank holds every cell), "
            << "more than the " << available / 1e9
            << " GB available: use fewer cells";
        throw InputError("Grid/cells", cells_text, why.str());
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
    check_grid_fits_in_memory(prm.get("cells"));
    for (unsigned int f = 0; f < 2 * dim; ++f)
      {
        const std::string b = prm.get(std::string("boundary ") + face_names[f]);
        boundary[f]         = (b == "free"       ? BoundaryType::free
                               : b == "fixed"    ? BoundaryType::fixed
                               : b == "slip"     ? BoundaryType::slip
                               : b == "friction" ? BoundaryType::friction
                                                 : BoundaryType::absorbing);
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
    , fe(1)
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

    // Every cell a coarse cell. A coarse mesh refined globally would save
    // memory (p4est keeps every coarse cell on every rank: 12% less peak
    // memory on 1 rank, 28% on 2, for a 512^2 grid), but deal.II's particle
    // loops then ran 1.7-1.9x slower, even a loop that touches no grid
    // data; see doc/performance.md.
    std::vector<unsigned int> repetitions(prm.n_cells.begin(),
                                          prm.n_cells.end());
    // colorize: face f of the box gets boundary id f (x-, x+, y-, ...).
    GridGenerator::subdivided_hyper_rectangle(
      *tria, repetitions, prm.lower_corner, prm.upper_corner, true);

    if constexpr (dim > 1)
      {
        if (!restart_file.empty())
          // The points stay attached for MaterialPoints::restore(). deal.II
          // 9.4 loads with a uniform partition; restore_partition() puts
          // back the work partition once the points are unpacked.
          dynamic_cast<parallel::distributed::Triangulation<dim> &>(*tria).load(
            restart_file);
        else
          partition_by_work();
      }

    h = prm.cell_size();
    for (unsigned int d = 0; d < dim; ++d)
      inv_h[d] = 1. / h[d];
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
  BackgroundGrid<dim>::partition_by_work()
  {
    if constexpr (dim > 1)
      if (partitions_by_work())
        {
          // The +1 keeps every weight positive and lets empty cells count a
          // little (a point costs about 30 times a node per step).
          auto &p_tria =
            dynamic_cast<parallel::distributed::Triangulation<dim> &>(*tria);
          auto connection = p_tria.signals.weight.connect(
            [&](const typename Triangulation<dim>::cell_iterator &cell,
                const typename Triangulation<dim>::CellStatus) -> unsigned int {
              return 1 + 30 * work_estimate(cell->vertex(0));
            });
          p_tria.repartition();
          connection.disconnect();
        }
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
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dofs, relevant);
    scalar_partitioner =
      std::make_shared<Utilities::MPI::Partitioner>(dofs.locally_owned_dofs(),
                                                    relevant,
                                                    comm);
    n_owned_nodes = scalar_partitioner->locally_owned_size();

    owned_cells.clear();
    node_constraints.clear();
    node_frictions.clear();
    node_dashpots.clear();
    build_cell_tables();
    build_node_constraints();
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
  unsigned int
  BackgroundGrid<dim>::locate(const Point<dim> &x, Point<dim> &reference) const
  {
    return locate_in_lattice<dim>(
      x, prm.lower_corner, inv_h, prm.n_cells, reference);
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
  void
  BackgroundGrid<dim>::build_cell_tables()
  {
    unsigned int n_total = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_total *= prm.n_cells[d];
    cells.resize(n_total);
    cartesian_index_of_active_cell.assign(tria->n_active_cells(), invalid);
    unsigned int n_nodes = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_nodes *= prm.n_cells[d] + 1;
    local_node_of_cartesian.assign(n_nodes, invalid);

    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : tria->active_cell_iterators())
      {
        Point<dim>         reference;
        const unsigned int index = locate(cell->center(), reference);
        cells[index]             = cell;
        cartesian_index_of_active_cell[cell->active_cell_index()] = index;
        if (cell->is_artificial())
          continue;
        if (cell->is_locally_owned())
          owned_cells.push_back(index);
        // FE_Q(1) numbers its dofs like the vertices: lexicographically,
        // bit d of v set for the upper vertex in direction d.
        typename DoFHandler<dim>::active_cell_iterator dof_cell(&*tria,
                                                                cell->level(),
                                                                cell->index(),
                                                                &dofs);
        dof_cell->get_dof_indices(dof_indices);
        const auto c = cell_coordinates(index);
        for (unsigned int v = 0; v < dof_indices.size(); ++v)
          {
            unsigned int node = 0, stride = 1;
            for (unsigned int d = 0; d < dim; ++d)
              {
                node += (c[d] + ((v >> d) & 1u)) * stride;
                stride *= prm.n_cells[d] + 1;
              }
            local_node_of_cartesian[node] =
              scalar_partitioner->global_to_local(dof_indices[v]);
          }
      }
    // Lexicographic order keeps neighbouring cells, and so the nodal data
    // they touch, close in memory during the particle loops.
    std::sort(owned_cells.begin(), owned_cells.end());
  }


  template <int dim>
  void
  BackgroundGrid<dim>::build_node_constraints()
  {
    std::vector<unsigned int> mask(n_owned_nodes, 0u);
    std::vector<unsigned int> friction_faces(n_owned_nodes, 0u);
    // Per owned node, the area share of each absorbing face (a face's
    // area is split equally among its 2^(dim-1) vertices). An owned node's
    // faces may belong to ghost cells, so those are visited too; the
    // masks only need one face of each kind and are the same either way.
    std::map<std::pair<unsigned int, unsigned int>, double> dashpot_area;
    std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned() || cell->is_ghost())
        for (const unsigned int f : cell->face_indices())
          if (cell->at_boundary(f))
            {
              const unsigned int id   = cell->face(f)->boundary_id();
              unsigned int       bits = 0;
              if (prm.boundary[id] == BoundaryType::friction)
                {
                  cell->face(f)->get_dof_indices(face_dofs);
                  for (const auto dof : face_dofs)
                    if (scalar_partitioner->in_local_range(dof))
                      friction_faces[scalar_partitioner->global_to_local(
                        dof)] |= 1u << id;
                  continue;
                }
              if (prm.boundary[id] == BoundaryType::absorbing)
                {
                  double share = 1;
                  for (unsigned int d = 0; d < dim; ++d)
                    if (d != id / 2)
                      share *= 0.5 * h[d];
                  cell->face(f)->get_dof_indices(face_dofs);
                  for (const auto dof : face_dofs)
                    if (scalar_partitioner->in_local_range(dof))
                      dashpot_area[{scalar_partitioner->global_to_local(dof),
                                    id}] += share;
                  continue;
                }
              if (prm.boundary[id] == BoundaryType::fixed)
                bits = (1u << dim) - 1;
              else if (prm.boundary[id] == BoundaryType::slip)
                bits = 1u << (id / 2);
              if (bits == 0)
                continue;
              cell->face(f)->get_dof_indices(face_dofs);
              for (const auto dof : face_dofs)
                if (scalar_partitioner->in_local_range(dof))
                  mask[scalar_partitioner->global_to_local(dof)] |= bits;
            }
    for (unsigned int i = 0; i < n_owned_nodes; ++i)
      {
        if (mask[i] != 0)
          node_constraints.emplace_back(i, mask[i]);
        if (friction_faces[i] != 0)
          node_frictions.emplace_back(i, friction_faces[i]);
      }
    for (const auto &[node_and_face, area] : dashpot_area)
      node_dashpots.push_back(
        {node_and_face.first, node_and_face.second, area});
  }


  template <int dim>
  std::vector<unsigned int>
  BackgroundGrid<dim>::owned_nodes_in_box(const Point<dim> &lower,
                                          const Point<dim> &upper) const
  {
    // A node counts if it lies in the box up to a thousandth of a cell, so
    // that a box drawn on grid lines includes them.
    std::vector<bool>                    inside(n_owned_nodes, false);
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(cell_dofs);
          for (const unsigned int v : cell->vertex_indices())
            {
              const Point<dim> x  = cell->vertex(v);
              bool             in = true;
              for (unsigned int d = 0; d < dim; ++d)
                in = in && x[d] >= lower[d] - 1e-3 * h[d] &&
                     x[d] <= upper[d] + 1e-3 * h[d];
              // FE_Q(1): the DoF of vertex v is the v-th of the cell.
              if (in && scalar_partitioner->in_local_range(cell_dofs[v]))
                inside[scalar_partitioner->global_to_local(cell_dofs[v])] =
                  true;
            }
        }
    std::vector<unsigned int> nodes;
    for (unsigned int i = 0; i < n_owned_nodes; ++i)
      if (inside[i])
        nodes.push_back(i);
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
