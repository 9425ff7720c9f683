// The points' data are put back in visiting order in place
// (MaterialPoints::restore_memory_order): a disk of points whose storage
// was scrambled (a third of them moved to new slots at the end of deal.II's
// property pool) is re-packed. The program fails unless, afterwards, the
// points are visited in the same order as before with every datum
// unchanged bit for bit (so no sum of the step changes), their slots
// ascend along the visiting order (what the re-pack is for), and a
// second re-pack moves nothing. Then the disk is turned by 0.4 rad about
// its centre (most points change tile) and relocated: every point must
// be found in its new tile with its own data, and a re-pack must again
// keep order and data and sort the slots. Last, points moved a little
// behind the grid's faces: put back on the closed ones, lost through the
// open ones.
#include <deal.II/base/mpi.h>

#include <mpm/simulation.h>

#include <cmath>
#include <iostream>
#include <map>
#include <vector>

#include "scene.h"

using namespace dealii;

// What a point holds, in visiting order.
struct Snapshot
{
  std::vector<types::particle_index> ids;
  std::vector<double>                data; // location, reference, properties
  std::vector<unsigned int>          slots;
};

Snapshot
snapshot(const mpm::MaterialPoints<2> &points)
{
  Snapshot s;
  points.for_each_by_cell([&](const auto &p) {
    s.ids.push_back(p.get_id());
    s.slots.push_back(p.get_local_index());
    for (unsigned int d = 0; d < 2; ++d)
      s.data.push_back(p.get_location()[d]);
    for (unsigned int d = 0; d < 2; ++d)
      s.data.push_back(p.get_reference_location()[d]);
    for (const double x : p.get_properties())
      s.data.push_back(x);
  });
  return s;
}

bool
ascending(const std::vector<unsigned int> &slots)
{
  for (unsigned int i = 1; i < slots.size(); ++i)
    if (!(slots[i - 1] < slots[i]))
      return false;
  return true;
}

bool
check(const char *what, const Snapshot &before, const Snapshot &after)
{
  // Bitwise: == on doubles (no NaN among the data).
  const bool same     = before.ids == after.ids && before.data == after.data;
  const bool in_order = ascending(after.slots);
  std::cout << what << ": " << after.ids.size() << " points, "
            << (same ? "same order and data" : "ORDER OR DATA CHANGED")
            << ", slots " << (in_order ? "ascending" : "NOT ASCENDING")
            << std::endl;
  return same && in_order;
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ParameterHandler                 prm;
  mpm::declare_scene_parameters(prm, 1);
  prm.parse_input_from_string(
    tests::disk_scene(64,
                      "",
                      "  set boundary y min = fixed\n"
                      "  set boundary y max = slip\n"
                      "  set boundary x max = free\n"));
  const MPI_Comm                      comm = MPI_COMM_WORLD;
  mpm::GridParameters<2>              grid_parameters;
  std::vector<mpm::BodyParameters<2>> bodies(1);
  grid_parameters.parse_parameters(prm);
  bodies[0].parse_parameters(prm, 0, grid_parameters);
  mpm::BackgroundGrid<2> grid(grid_parameters, comm);
  mpm::MaterialPoints<2> points(grid, bodies, mpm::FieldRequests(), comm);
  points.generate();
  auto &handler = points.handler();
  bool  ok      = ascending(snapshot(points).slots);
  std::cout << "after generation: slots "
            << (ok ? "ascending" : "NOT ASCENDING") << std::endl;

  // Scramble: every third point, in visiting order, is copied into a new
  // slot and its old one freed (as relocation does with a point that
  // changes tile), so that the data no longer follow the visiting order.
  {
    std::vector<typename Particles::ParticleHandler<2>::particle_iterator>
                 chosen;
    unsigned int i = 0;
    for (const unsigned int t : grid.locally_owned_tiles())
      for (auto p = handler.particles_in_cell(grid.tile(t)).begin();
           p != handler.particles_in_cell(grid.tile(t)).end();
           ++p, ++i)
        if (i % 3 == 0)
          chosen.push_back(p);
    // Copies appended at the end of each tile, then the originals removed
    // from the back, which keeps the iterators still to be used valid.
    std::vector<double> buffer(points.layout().n_properties);
    for (const auto &p : chosen)
      {
        std::copy(p->get_properties().begin(),
                  p->get_properties().end(),
                  buffer.begin());
        const Point<2> x = p->get_location(), xi = p->get_reference_location();
        handler.insert_particle(x,
                                xi,
                                p->get_id(),
                                p->get_surrounding_cell(),
                                make_array_view(buffer));
      }
    for (auto p = chosen.rbegin(); p != chosen.rend(); ++p)
      handler.remove_particle(*p);
  }
  const Snapshot scrambled = snapshot(points);
  ok                       = !ascending(scrambled.slots) && ok;
  const auto n_moved       = points.restore_memory_order();
  std::cout << "re-pack moved " << n_moved << " points" << std::endl;
  ok = check("after re-pack", scrambled, snapshot(points)) && n_moved > 0 && ok;
  const auto n_again = points.restore_memory_order();
  std::cout << "second re-pack moved " << n_again << " points" << std::endl;
  ok = n_again == 0 && ok;

  // Turn the disk: most points change tile. Relocation writes a point
  // that arrives in a tile over the data of one that left it (in its
  // slot) where it can, so every point must end up in its new tile with
  // its own data, and a re-pack then restores the order.
  std::map<types::particle_index, std::vector<double>> expected;
  for (auto &p : handler)
    {
      const Tensor<1, 2> r = p.get_location() - Point<2>(0.5, 0.5);
      const double       c = std::cos(0.4), s = std::sin(0.4);
      p.set_location(
        Point<2>(0.5 + c * r[0] - s * r[1], 0.5 + s * r[0] + c * r[1]));
      auto &e = expected[p.get_id()];
      e       = {p.get_location()[0], p.get_location()[1]};
      e.insert(e.end(), p.get_properties().begin(), p.get_properties().end());
    }
  points.relocate(mpm::OutOfGridPolicy::stop);
  unsigned int n_found = 0, n_right = 0;
  for (const unsigned int t : grid.locally_owned_tiles())
    for (const auto &p : handler.particles_in_cell(grid.tile(t)))
      {
        ++n_found;
        typename mpm::BackgroundGrid<2>::CellCoordinates cell;
        Point<2>                                         xi;
        std::vector<double> data = {p.get_location()[0], p.get_location()[1]};
        data.insert(data.end(),
                    p.get_properties().begin(),
                    p.get_properties().end());
        const auto e = expected.find(p.get_id());
        if (grid.locate(p.get_location(), cell, xi) &&
            grid.tile_of(cell) == t &&
            p.get_reference_location() == grid.tile_reference(cell, xi) &&
            e != expected.end() && e->second == data)
          {
            ++n_right;
            expected.erase(e); // each id once
          }
      }
  std::cout << "after turning and relocation: " << n_found << " points, "
            << n_right << " in their tiles with their own data" << std::endl;
  ok = n_found == scrambled.ids.size() && n_right == n_found && ok;
  const Snapshot turned = snapshot(points);
  points.restore_memory_order();
  ok = check("re-packed after relocation", turned, snapshot(points)) && ok;

  // Points a little behind a closed face are put back on it without
  // their velocity out through it (a point on a no-slip floor takes a
  // share of the nodes' motion above it and can cross the floor by a
  // fraction of a step); behind an open face, or far behind a closed
  // one, they are outside. The floor (y = 0) is fixed, the top slip,
  // the right side free; h = 1/64.
  {
    const double h = 1. / 64;
    struct Case
    {
      Point<2>     x;
      Tensor<1, 2> v;
      bool         kept;
      Point<2>     x_kept;
      Tensor<1, 2> v_kept;
    };
    const auto vec = [](const double a, const double b) {
      Tensor<1, 2> v;
      v[0] = a, v[1] = b;
      return v;
    };
    const std::vector<Case> cases = {
      {Point<2>(0.3, -0.1 * h), vec(1, -1), true, Point<2>(0.3, 0), vec(1, 0)},
      {Point<2>(0.4, -0.3 * h), vec(1, -1), false, {}, {}},
      {Point<2>(0.5, 1 + 0.1 * h),
       vec(-1, 2),
       true,
       Point<2>(0.5, 1 - 1e-9 * h),
       vec(-1, 0)},
      {Point<2>(1 + 0.1 * h, 0.5), vec(1, 0), false, {}, {}}};
    std::map<types::particle_index, const Case *> moved;
    auto                                          p = handler.begin();
    for (const Case &c : cases)
      {
        p->set_location(c.x);
        mpm::Fields::store(c.v,
                           p->get_properties().data() +
                             points.layout().velocity);
        moved[p->get_id()] = &c;
        ++p;
      }
    const auto   n_lost = points.relocate(mpm::OutOfGridPolicy::remove);
    unsigned int n_kept = 0;
    for (const auto &q : handler)
      {
        const auto c = moved.find(q.get_id());
        if (c == moved.end())
          continue;
        const Tensor<1, 2> v = mpm::Fields::vector<2>(
          q.get_properties().data() + points.layout().velocity);
        if (c->second->kept && q.get_location() == c->second->x_kept &&
            v == c->second->v_kept)
          ++n_kept;
      }
    std::cout << "points behind faces: " << n_kept
              << " put back on closed faces, " << n_lost << " lost"
              << std::endl;
    ok = n_kept == 2 && n_lost == 2 && ok;
  }
  std::cout << (ok ? "passed" : "FAILED") << std::endl;
  return ok ? 0 : 1;
}
