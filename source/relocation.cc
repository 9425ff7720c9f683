// Relocation of the material points after each step: the points that
// leave their tile move to the new one, on this rank or (sent in one
// exchange) on another; points that leave the grid are stopped, removed or
// put back by 'Simulation/out of grid'; and every so often the points are
// stored again in the order of the grid's tiles (restore_memory_order), so
// that the particle loops walk memory in order.
#include <deal.II/base/mpi.h>

#include <mpm/material_points.h>
#include <mpm/parameters.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace mpm
{
  namespace
  {
    /// A point in a buffer of doubles, as relocation moves and sends it:
    /// location (dim), reference location (dim), id (exact: ids are
    /// below 2^53), properties.
    template <int dim>
    void
    append_point(std::vector<double>           &to,
                 const Point<dim>              &x,
                 const Point<dim>              &xi,
                 const types::particle_index    id,
                 const ArrayView<const double> &properties)
    {
      for (unsigned int d = 0; d < dim; ++d)
        to.push_back(x[d]);
      for (unsigned int d = 0; d < dim; ++d)
        to.push_back(xi[d]);
      to.push_back(id);
      to.insert(to.end(), properties.begin(), properties.end());
    }

    /// The location (at @p q) or reference location (at @p q + dim) of a
    /// point stored by append_point().
    template <int dim>
    Point<dim>
    point_at(const double *q)
    {
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = q[d];
      return x;
    }
  } // namespace


  template <int dim>
  types::particle_index
  MaterialPoints<dim>::relocate(const OutOfGridPolicy policy)
  {
    // The points that leave their tile, in visiting order: to another tile
    // of this rank (their data are buffered as arrivals), out of the grid,
    // or to a neighbour rank's tile (their data packed in 'sent').
    Moves                 moves;
    std::string           failure;
    types::particle_index n_lost   = 0;
    bool                  far_away = false;
    // Per neighbour rank: location, id and properties of each point sent.
    std::map<unsigned int, std::vector<double>> sent;

    for (const unsigned int here : grid.locally_owned_tiles())
      {
        const auto        &tile = grid.tile(here);
        const unsigned int n    = particles.n_particles_in_cell(tile);
        if (n == 0)
          continue;
        auto p = particles.particles_in_cell(tile).begin();
        for (unsigned int i = 0; i < n; ++i, ++p)
          {
            typename BackgroundGrid<dim>::CellCoordinates cell;
            Point<dim>                                    xi;
            if (!grid.locate(p->get_location(), cell, xi) &&
                !put_back_on_closed_face(p, cell, xi))
              {
                // A NaN position is an unstable run, not a point that left:
                // it must never be removed quietly.
                const bool finite =
                  std::isfinite(p->get_location().norm_square());
                if (!finite || policy == OutOfGridPolicy::stop)
                  {
                    if (failure.empty())
                      failure = finite ? describe_leaving_point(p)
                                       : "material point " +
                                           std::to_string(p->get_id()) +
                                           " has a non-finite position; the "
                                           "run is unstable (try a smaller "
                                           "CFL number, MUSL, or damping)";
                    continue;
                  }
                moves.leave(p, here, false);
                ++n_lost;
                continue;
              }
            const unsigned int there = grid.tile_of(cell);
            if (there == here)
              {
                p->set_reference_location(grid.tile_reference(cell, xi));
                continue;
              }
            if (grid.tile(there).state() == IteratorState::valid &&
                grid.tile(there)->is_locally_owned())
              {
                moves.arrive(there,
                             p->get_location(),
                             grid.tile_reference(cell, xi),
                             p->get_id(),
                             p->get_properties());
                moves.leave(p, here, false);
              }
            else if (grid.tile(there).state() == IteratorState::valid &&
                     grid.tile(there)->is_ghost())
              {
                append_point(sent[grid.tile(there)->subdomain_id()],
                             p->get_location(),
                             p->get_reference_location(),
                             p->get_id(),
                             p->get_properties());
                moves.leave(p, here, true);
              }
            else
              far_away = true; // beyond the ghost layer: deal.II finds it
          }
      }

    raise_if_any_failed(failure, comm);

    // The calls below are collective (they count or exchange points over
    // all ranks), so every rank must take the same branch. A point that
    // went further than a neighbour's tile (a step longer than a tile:
    // not with a CFL number below 1) needs deal.II's sort, which finds
    // its rank but copies all the points' data; points that went to a
    // neighbour are sent there. A move within the rank changes no count,
    // and deal.II's count of them walks every point: it runs only when
    // points were lost (a checkpoint updates the counts before it packs
    // the points).
    int changes =
      (far_away ? 1 : 0) | (n_lost == 0 ? 0 : 2) | (sent.empty() ? 0 : 4);
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      MPI_Allreduce(MPI_IN_PLACE, &changes, 1, MPI_INT, MPI_BOR, comm);
    const bool full_sort = changes & 1;
    if (!full_sort && (changes & 4))
      receive_points(Utilities::MPI::some_to_some(comm, sent), moves);
    // Before a full sort, the points sent stay: the sort moves them.
    settle(moves, full_sort);

    if (full_sort)
      {
        particles.sort_particles_into_subdomains_and_cells();
        ++n_full_sorts;
        appended_since_repack = 0;
        // deal.II's sort recomputes every reference location by its own
        // mapping, which can differ from locate() in the last bit; the
        // bases read it, so a run would depend on when it sorted.
        for (auto &point : particles)
          {
            // (Every point is in the grid here: deal.II sorted it.)
            typename BackgroundGrid<dim>::CellCoordinates cell{};
            Point<dim>                                    xi;
            grid.locate(point.get_location(), cell, xi);
            point.set_reference_location(grid.tile_reference(cell, xi));
          }
      }
    else if (changes & 2)
      particles.update_cached_numbers();

    // A point moved to another tile is stored where the property pool had
    // room, far from its new neighbours; as points flow, every loop walks
    // memory at random (a settling block at nu = 0.35 ran at 2.3-2.9x the
    // cost per point-step of one at nu = 0). So once the moves since the
    // last re-pack pass a fraction of the points (settle() counts those
    // it appends; one written over a leaver keeps its slot), their data are put
    // back in visiting order (doc/performance.md). deal.II's sort (above) does
    // that too, but by a copy of all the points' data.
    if (appended_since_repack >
        memory_order_tolerance * particles.n_locally_owned_particles())
      {
        restore_memory_order();
        ++n_repacks;
        appended_since_repack = 0;
      }

    return Utilities::MPI::sum(n_lost, comm);
  }


  template <int dim>
  void
  MaterialPoints<dim>::Moves::leave(const iterator    &p,
                                    const unsigned int tile,
                                    const bool         to_other_rank)
  {
    leavers.push_back(p);
    leaver_tile.push_back(tile);
    to_rank.push_back(to_other_rank);
  }


  template <int dim>
  void
  MaterialPoints<dim>::Moves::arrive(const unsigned int             tile,
                                     const Point<dim>              &x,
                                     const Point<dim>              &xi,
                                     const types::particle_index    id,
                                     const ArrayView<const double> &properties)
  {
    arrivals.emplace_back(tile, data.size());
    append_point(data, x, xi, id, properties);
  }


  template <int dim>
  void
  MaterialPoints<dim>::receive_points(
    const std::map<unsigned int, std::vector<double>> &received,
    Moves                                             &moves) const
  {
    const unsigned int n = 2 * dim + 1 + fields.n_properties;
    std::string        failure;
    // In the order of the sending ranks, each in its visiting order: the
    // same points arrive in the same order whenever the run is repeated.
    for (const auto &[rank, data] : received)
      for (std::size_t k = 0; k + n <= data.size(); k += n)
        {
          const Point<dim> x = point_at<dim>(data.data() + k);
          // (The reference location is this rank's, from locate().)
          typename BackgroundGrid<dim>::CellCoordinates cell;
          Point<dim>                                    xi;
          const bool         inside = grid.locate(x, cell, xi);
          const unsigned int tile   = grid.tile_of(cell);
          if (!inside || grid.tile(tile).state() != IteratorState::valid ||
              !grid.tile(tile)->is_locally_owned())
            {
              // Rank 'rank' saw this rank own the point's tile: the
              // partitions disagree, which is a bug, not a user's error.
              std::ostringstream s;
              s << "internal error: rank " << rank << " sent a point at (" << x
                << ") to rank " << Utilities::MPI::this_mpi_process(comm)
                << ", which does not own its tile";
              failure = s.str();
              continue;
            }
          moves.arrive(tile,
                       x,
                       grid.tile_reference(cell, xi),
                       static_cast<types::particle_index>(data[k + 2 * dim]),
                       make_array_view(data.data() + k + 2 * dim + 1,
                                       data.data() + k + n));
        }
    raise_if_any_failed(failure, comm);
  }


  template <int dim>
  void
  MaterialPoints<dim>::settle(Moves &moves, const bool keep_sent)
  {
    // The result must not depend on where a point's data are stored, only
    // on its place in its tile, which is as if each tile got its arrivals
    // appended in order and then lost its leavers from the last: a leaver
    // takes the last arrival still appended. So the last arrivals are
    // written over the last leavers' data, in their slots (which keeps a
    // flow's data near their neighbours'), the remaining arrivals are
    // appended, and the remaining leavers removed from the last.
    const unsigned int np      = fields.n_properties;
    auto               by_tile = [](const auto &a, const auto &b) {
      return a.first < b.first;
    };
    std::stable_sort(moves.arrivals.begin(), moves.arrivals.end(), by_tile);
    // Tiles with leavers, in visiting order, each with its range of them.
    std::vector<std::pair<unsigned int, std::pair<std::size_t, std::size_t>>>
      leaving;
    for (std::size_t i = 0; i < moves.leavers.size(); ++i)
      {
        if (leaving.empty() || leaving.back().first != moves.leaver_tile[i])
          leaving.push_back({moves.leaver_tile[i], {i, i}});
        leaving.back().second.second = i + 1;
      }
    std::stable_sort(leaving.begin(), leaving.end(), by_tile);

    auto next_leaving = leaving.begin();
    for (auto a = moves.arrivals.begin();
         a != moves.arrivals.end() || next_leaving != leaving.end();)
      {
        // The next tile (by index) with arrivals or leavers.
        const unsigned int tile =
          a == moves.arrivals.end()
            ? next_leaving->first
            : (next_leaving == leaving.end()
                 ? a->first
                 : std::min(a->first, next_leaving->first));
        auto a_end = a;
        while (a_end != moves.arrivals.end() && a_end->first == tile)
          ++a_end;
        std::vector<std::size_t> out; // leavers of the tile, in order
        if (next_leaving != leaving.end() && next_leaving->first == tile)
          {
            for (std::size_t i = next_leaving->second.first;
                 i < next_leaving->second.second;
                 ++i)
              if (!(keep_sent && moves.to_rank[i]))
                out.push_back(i);
            ++next_leaving;
          }
        std::size_t n_in = a_end - a, n_out = out.size();
        // Last arrival over last leaver.
        while (n_in > 0 && n_out > 0)
          {
            const double *q = moves.data.data() + (a + n_in - 1)->second;
            auto         &p = moves.leavers[out[n_out - 1]];
            p->set_location(point_at<dim>(q));
            p->set_reference_location(point_at<dim>(q + dim));
            p->set_id(static_cast<types::particle_index>(q[2 * dim]));
            std::copy(q + 2 * dim + 1,
                      q + 2 * dim + 1 + np,
                      p->get_properties().begin());
            --n_in;
            --n_out;
          }
        for (std::size_t k = 0; k < n_in; ++k)
          {
            const double *q = moves.data.data() + (a + k)->second;
            particles.insert_particle(
              point_at<dim>(q),
              point_at<dim>(q + dim),
              static_cast<types::particle_index>(q[2 * dim]),
              grid.tile(tile),
              make_array_view(q + 2 * dim + 1, q + 2 * dim + 1 + np));
            // Stored wherever the pool had room: counts to the re-pack.
            ++appended_since_repack;
          }
        for (std::size_t k = n_out; k > 0; --k)
          particles.remove_particle(moves.leavers[out[k - 1]]);
        a = a_end;
      }
  }


  template <int dim>
  types::particle_index
  MaterialPoints<dim>::restore_memory_order()
  {
    using Handle           = typename Particles::PropertyPool<dim>::Handle;
    constexpr Handle none  = std::numeric_limits<Handle>::max();
    const auto      &tiles = grid.locally_owned_tiles();

    if (particles.n_locally_owned_particles() == 0)
      return 0;
    // The slot of every point in visiting order (its handle, which deal.II
    // gives as its local index), and where each tile's points begin.
    std::vector<Handle>       slot_of;
    std::vector<unsigned int> tile_begin(tiles.size() + 1, 0);
    slot_of.reserve(particles.n_locally_owned_particles());
    Handle n_slots = 0;
    for (unsigned int q = 0; q < tiles.size(); ++q)
      {
        tile_begin[q] = slot_of.size();
        for (const auto &p : particles.particles_in_cell(grid.tile(tiles[q])))
          {
            slot_of.push_back(p.get_local_index());
            n_slots = std::max<Handle>(n_slots, slot_of.back() + 1);
          }
      }
    tile_begin.back() = slot_of.size();

    // Point j belongs in the j-th smallest of these slots. wanted_by[s] is
    // the point that belongs in slot s (free slots, and any other rank's
    // ghosts, are none and stay where they are).
    std::vector<Handle> wanted_by(n_slots, none);
    for (const Handle s : slot_of)
      wanted_by[s] = 0;
    for (Handle s = 0, j = 0; s < n_slots; ++s)
      if (wanted_by[s] != none)
        wanted_by[s] = j++;

    // Moving a point: insert a copy of it in its tile, which takes the
    // pool's last freed slot, then remove it, which frees its old slot and
    // puts the copy (the tile's last point) in its place in the tile.
    std::vector<double> buffer(fields.n_properties);
    auto                move = [&](const unsigned int j) {
      const unsigned int q =
        std::upper_bound(tile_begin.begin(), tile_begin.end(), j) -
        tile_begin.begin() - 1;
      const auto tile = grid.tile(tiles[q]);
      auto       p = particles.particles_in_cell(tile).begin();
      std::advance(p, j - tile_begin[q]);
      // Copies: the arguments must not point into the pool it writes.
      const auto properties = p->get_properties();
      std::copy(properties.begin(), properties.end(), buffer.begin());
      const Point<dim> x  = p->get_location();
      const Point<dim> xi = p->get_reference_location();
      particles.insert_particle(
        x, xi, p->get_id(), tile, make_array_view(buffer));
      particles.remove_particle(p);
    };

    // Each cycle of the permutation goes through one free slot: its first
    // point moves there, each point then into the slot the previous one
    // freed, and the first into the last freed slot, which frees the
    // spare again. A point inserted and removed at once makes sure there
    // is one (the pool's last freed slot, or a new one at its end).
    particles.remove_particle(particles.insert_particle(
      Point<dim>(), Point<dim>(), 0, grid.tile(tiles[0]), {}));
    types::particle_index n_moved = 0;
    std::vector<bool>     done(slot_of.size(), false);
    for (unsigned int first = 0; first < slot_of.size(); ++first)
      {
        if (done[first] || wanted_by[slot_of[first]] == first)
          continue;
        move(first); // to the spare slot
        for (Handle freed = slot_of[first];;)
          {
            const Handle next = wanted_by[freed];
            done[next]        = true;
            move(next);
            ++n_moved;
            if (next == first)
              break;
            freed = slot_of[next];
          }
      }
    return n_moved;
  }


  template <int dim>
  bool
  MaterialPoints<dim>::put_back_on_closed_face(
    typename Particles::ParticleHandler<dim>::particle_iterator &p,
    typename BackgroundGrid<dim>::CellCoordinates               &cell,
    Point<dim>                                                  &xi)
  {
    Point<dim>     x = p->get_location();
    double        *q = p->get_properties().data();
    Tensor<1, dim> v = Fields::vector<dim>(q + fields.velocity);
    if (!grid.parameters().put_back_behind_closed_face(x, v) ||
        !grid.locate(x, cell, xi))
      return false;
    p->set_location(x);
    Fields::store(v, q + fields.velocity);
    return true;
  }


  template <int dim>
  std::string
  MaterialPoints<dim>::describe_leaving_point(
    const typename Particles::ParticleHandler<dim>::particle_iterator &p) const
  {
    std::ostringstream s;
    s << "material point " << p->get_id() << " of body "
      << p->get_properties()[fields.body] << " left the grid at ("
      << p->get_location() << ") with velocity ("
      << Fields::vector<dim>(p->get_properties().data() + fields.velocity)
      << "). Enlarge the grid, make its faces slip or fixed, or set "
         "'Simulation/out of grid = remove'.";
    return s.str();
  }


  // Members of MaterialPoints defined here, instantiated for each dimension
  // (the class itself is instantiated in material_points.cc).
#define MPM_INSTANTIATE(dim)                                    \
  template types::particle_index MaterialPoints<dim>::relocate( \
    const OutOfGridPolicy);                                     \
  template types::particle_index MaterialPoints<dim>::restore_memory_order();
  MPM_INSTANTIATE(1)
  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace mpm
