// The shapes a body can take and the points of a body read from a mesh:
// inside/outside tests at chosen points, bounding boxes, the area or volume
// a lattice of points finds inside against the exact one, the scene errors
// of bad shapes, and the Gauss points of a gmsh mesh (quadrilaterals and
// triangles) against the exact area of its cells, region by region.
// Prints what it measured; exits non-zero if a bound is exceeded.
// Argument: the directory of the test meshes.
#include <deal.II/base/parameter_handler.h>

#include <mpm/bodies/mesh_seeds.h>
#include <mpm/bodies/shape.h>
#include <mpm/parameters.h>

#include <cmath>
#include <iostream>
#include <numeric>
#include <set>

#include "checks.h"

using namespace dealii;
using namespace mpm;

namespace
{
  using namespace checks;


  template <int dim>
  std::unique_ptr<Shape<dim>>
  make_shape(const std::vector<std::pair<std::string, std::string>> &settings)
  {
    ParameterHandler prm;
    prm.declare_entry("shape", "box");
    Shape<dim>::declare_parameters(prm);
    for (const auto &[key, value] : settings)
      prm.set(key, value);
    return Shape<dim>::create(prm, "Body");
  }


  /// The InputError message a shape gives, or "" if it is accepted.
  template <int dim>
  std::string
  shape_error(const std::vector<std::pair<std::string, std::string>> &settings)
  {
    try
      {
        make_shape<dim>(settings);
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }


  void
  check_error(const std::string &what,
              const std::string &message,
              const std::string &expected)
  {
    std::cout << "    (" << message << ")" << std::endl;
    check_true(what, message.find(expected) != std::string::npos);
  }


  /// Measure of the part of @p shape's bounding box that a lattice of
  /// n^dim cell-centred points finds inside.
  template <int dim>
  double
  lattice_measure(const Shape<dim> &shape, const unsigned int n)
  {
    const auto [lower, upper] = shape.bounding_box().get_boundary_points();
    double cell               = 1;
    for (unsigned int d = 0; d < dim; ++d)
      cell *= (upper[d] - lower[d]) / n;
    unsigned int inside = 0;
    for (unsigned int i = 0; i < Utilities::fixed_power<dim>(n); ++i)
      {
        Point<dim>   x;
        unsigned int rest = i;
        for (unsigned int d = 0; d < dim; ++d, rest /= n)
          x[d] = lower[d] + (rest % n + 0.5) * (upper[d] - lower[d]) / n;
        inside += shape.contains(x);
      }
    return inside * cell;
  }


  void
  test_polygon()
  {
    std::cout << "Polygon (2D)" << std::endl;
    // An L: the notch at (1, 1)-(2, 2) is outside.
    for (const std::string vertices :
         {"0,0; 2,0; 2,1; 1,1; 1,2; 0,2", "0,2; 1,2; 1,1; 2,1; 2,0; 0,0"})
      {
        const auto L =
          make_shape<2>({{"shape", "polygon"}, {"vertices", vertices}});
        check_true("L (" + vertices +
                     ") holds (0.5, 1.5) and (1.5, 0.5), "
                     "not (1.5, 1.5) or (2.5, 0.5)",
                   L->contains(Point<2>(0.5, 1.5)) &&
                     L->contains(Point<2>(1.5, 0.5)) &&
                     !L->contains(Point<2>(1.5, 1.5)) &&
                     !L->contains(Point<2>(2.5, 0.5)));
        check("L: lattice area - 3 (edges on lattice lines)",
              lattice_measure(*L, 64) - 3,
              1e-12);
      }
    const auto triangle =
      make_shape<2>({{"shape", "polygon"}, {"vertices", "0,0; 1,0; 0,1"}});
    const auto [lower, upper] = triangle->bounding_box().get_boundary_points();
    check("triangle: bounding box",
          lower.distance(Point<2>(0, 0)) + upper.distance(Point<2>(1, 1)),
          0);
    check("triangle: lattice area - 1/2 at n = 256 (O(1/n))",
          lattice_measure(*triangle, 256) - 0.5,
          1. / 256);

    check_error("a crossing polygon is refused",
                shape_error<2>(
                  {{"shape", "polygon"}, {"vertices", "0,0; 2,2; 2,0; 0,1"}}),
                "cross or touch: the polygon must be simple");
    check_error("two vertices are refused",
                shape_error<2>(
                  {{"shape", "polygon"}, {"vertices", "0,0; 1,1"}}),
                "at least 3 vertices");
    check_error("collinear vertices are refused",
                shape_error<2>(
                  {{"shape", "polygon"}, {"vertices", "0,0; 1,1; 2,2"}}),
                "zero area");
    check_error("a vertex with one coordinate is refused",
                shape_error<2>(
                  {{"shape", "polygon"}, {"vertices", "0,0; 1; 0,1"}}),
                "two coordinates per vertex");
    check_error("a polygon in 3D is refused",
                shape_error<3>({{"shape", "polygon"}}),
                "a polygon is a 2D shape");
  }


  void
  test_cylinder()
  {
    std::cout << "Cylinder (3D)" << std::endl;
    const double       R = 0.5, r = 0.2, L = 2;
    const auto         tube = make_shape<3>({{"shape", "cylinder"},
                                             {"center", "1, 1, 1"},
                                             {"axis", "1, 1, 1"},
                                             {"length", "2"},
                                             {"radius", "0.5"},
                                             {"inner radius", "0.2"}});
    const Tensor<1, 3> a    = Point<3>(1, 1, 1) / std::sqrt(3.);
    Tensor<1, 3>       across({1, -1, 0});
    across /= across.norm();
    const Point<3> c(1, 1, 1);
    check_true("holds a point between the radii, on the axis' middle",
               tube->contains(c + 0.35 * across));
    check_true("not the hole, nor beyond the ends or the outer radius",
               !tube->contains(c + 0.1 * across) &&
                 !tube->contains(c + 0.35 * across + 1.01 * a) &&
                 !tube->contains(c + 0.51 * across));
    check_true("holds a point just inside an end",
               tube->contains(c + 0.35 * across + 0.99 * a));
    const auto [lower, upper] = tube->bounding_box().get_boundary_points();
    const double extent = 0.5 * L / std::sqrt(3.) + R * std::sqrt(2. / 3.);
    check("bounding box: half-width - (L/2 a_x + R sqrt(1 - a_x^2))",
          0.5 * (upper[0] - lower[0]) - extent,
          1e-14);
    const double exact = numbers::PI * (R * R - r * r) * L;
    check("lattice volume / exact - 1 at n = 160",
          lattice_measure(*tube, 160) / exact - 1,
          0.01);
    check_error("a cylinder in 2D is refused",
                shape_error<2>({{"shape", "cylinder"}}),
                "a cylinder is a 3D shape");
    check_error("a zero axis is refused",
                shape_error<3>({{"shape", "cylinder"}, {"axis", "0"}}),
                "must be a non-zero vector");
  }


  void
  test_ball_and_box()
  {
    std::cout << "Ball and box" << std::endl;
    const auto ring = make_shape<2>({{"shape", "ball"},
                                     {"center", "0"},
                                     {"radius", "1"},
                                     {"inner radius", "0.5"}});
    check("ring: lattice area / exact - 1 at n = 400",
          lattice_measure(*ring, 400) / (numbers::PI * 0.75) - 1,
          0.002);
    check_error("a box with upper < lower is refused",
                shape_error<2>({{"shape", "box"},
                                {"lower corner", "1"},
                                {"upper corner", "0.5, 2"}}),
                "must exceed the lower corner");
  }


  std::string
  mesh_error(const std::string &file, const std::set<types::material_id> &ids)
  {
    try
      {
        seeds_from_mesh<2>(file, ids, {}, 2, "Body");
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }


  /**
   * 'mesh points = grid': the lattice nodes inside the mesh's cells. Every
   * point carries the lattice's volume, none is counted twice (a node on a
   * face shared by two cells), each lies in the ring of its material id,
   * and the volume found differs from the area of the cells by at most
   * half a spacing times the perimeter (6.7 m). The error is a counting
   * error, not monotone: at 0.1 the straight edges x = 0 and y = 0 lie on
   * the nodes' cell faces and it is 6e-4; at 0.03 they cut a third of a
   * spacing off the first row, -0.020.
   */
  void
  test_mesh_lattice(const std::string &directory, const double *area)
  {
    for (const std::string kind :
         {"quarter_annulus", "quarter_annulus_triangles"})
      {
        const std::string file = directory + "/" + kind + ".msh";
        for (const double s : {0.1, 0.03, 0.01})
          {
            const Tensor<1, 2> spacing({s, s});
            const auto         all = lattice_seeds_in_mesh<2>(
              file, {}, Point<2>(-0.5, -0.5), spacing, "Body");
            const double volume =
              std::accumulate(all.volumes.begin(), all.volumes.end(), 0.);
            const double      error = std::abs(volume - area[1] - area[2]);
            const std::string what =
              kind + ", lattice " + std::to_string(s).substr(0, 5);
            check(what + ": |volume - cell area| / (s/2 x perimeter)",
                  error / (0.5 * s * 6.72),
                  1);
            std::set<std::pair<long, long>> nodes;
            bool on_lattice = true, equal_volumes = true;
            for (unsigned int i = 0; i < all.positions.size(); ++i)
              {
                const double a = (all.positions[i][0] + 0.5) / s - 0.5;
                const double b = (all.positions[i][1] + 0.5) / s - 0.5;
                on_lattice = on_lattice && std::abs(a - std::round(a)) < 1e-9 &&
                             std::abs(b - std::round(b)) < 1e-9;
                equal_volumes =
                  equal_volumes && std::abs(all.volumes[i] - s * s) < 1e-15;
                nodes.emplace(std::lround(a), std::lround(b));
              }
            check_true(what + ": points on the lattice, each with s^2",
                       on_lattice && equal_volumes);
            check(what + ": points counted twice",
                  all.positions.size() - double(nodes.size()),
                  0);
          }
        for (const types::material_id id : {1, 2})
          {
            const auto part =
              lattice_seeds_in_mesh<2>(file,
                                       {id},
                                       Point<2>(-0.5, -0.5),
                                       Tensor<1, 2>({0.05, 0.05}),
                                       "Body");
            // The straight edges of the arcs (chords of 15 degrees) cut
            // inside each circle by at most r (1 - cos 7.5 deg) < 0.9 %.
            bool in_ring = !part.positions.empty();
            for (const auto &x : part.positions)
              in_ring = in_ring && (id == 1 ? x.norm() > 0.99 && x.norm() < 1.5
                                            : x.norm() > 1.48 && x.norm() < 2);
            check_true(kind + ", lattice, material id " + std::to_string(id) +
                         ": every point in its half of the ring",
                       in_ring);
          }
      }
  }


  void
  test_mesh(const std::string &directory)
  {
    std::cout << "Mesh bodies (gmsh 2.2, quarter annulus 1 <= r <= 2)"
              << std::endl;
    // Areas of the straight-edged cells, printed by
    // benchmarks/meshes/annulus.py when it wrote the meshes.
    const double area[3] = {0, 0.97057141913445266, 1.3587999867882341};
    for (const std::string kind :
         {"quarter_annulus", "quarter_annulus_triangles"})
      {
        const std::string file = directory + "/" + kind + ".msh";
        const bool triangles   = kind.find("triangles") != std::string::npos;
        for (const unsigned int n : {1u, 2u, 3u})
          {
            const auto   all = seeds_from_mesh<2>(file, {}, {}, n, "Body");
            const double volume =
              std::accumulate(all.volumes.begin(), all.volumes.end(), 0.);
            check(kind + ", " + std::to_string(n) +
                    " per direction: sum JxW - cell area",
                  volume - area[1] - area[2],
                  1e-13);
            if (!triangles)
              check(kind + ": points - 24 cells x n^2",
                    all.positions.size() - 24. * n * n,
                    0);
          }
        for (const types::material_id id : {1, 2})
          {
            const auto part = seeds_from_mesh<2>(file, {id}, {}, 2, "Body");
            check(kind + ", material id " + std::to_string(id) +
                    ": sum JxW - area of its cells",
                  std::accumulate(part.volumes.begin(),
                                  part.volumes.end(),
                                  0.) -
                    area[id],
                  1e-13);
            bool in_ring = true;
            for (const auto &x : part.positions)
              in_ring = in_ring && (id == 1 ? x.norm() < 1.5 : x.norm() > 1.5);
            check_true(kind + ", material id " + std::to_string(id) +
                         ": every point in its half of the ring",
                       in_ring);
          }
      }
    for (const std::string kind :
         {"quarter_annulus", "quarter_annulus_triangles"})
      {
        // The outward N dA of the inner arc (boundary id 10, r = 1) sums to
        // the chord turned outward, (-1, -1), on any polygonal arc.
        const auto loaded = seeds_from_mesh<2>(
          directory + "/" + kind + ".msh", {}, {10}, 2, "Body");
        Tensor<1, 2> total;
        unsigned int carriers = 0;
        for (unsigned int i = 0; i < loaded.areas.size(); ++i)
          if (loaded.areas[i].norm() > 0)
            {
              total += loaded.areas[i];
              ++carriers;
              all_ok = all_ok && loaded.positions[i].norm() < 1.25;
            }
        check(kind + ": sum of N dA over boundary id 10 - (-1, -1)",
              (total - Tensor<1, 2>({-1., -1.})).norm(),
              1e-13);
        check(kind + ": points carrying the load - 2 per face (6 faces)",
              carriers - 12.,
              0);
      }
    test_mesh_lattice(directory, area);
    const std::string file = directory + "/quarter_annulus.msh";
    check_error("an id no cell has names the ids present",
                mesh_error(file, {7}),
                "no cell of '" + file + "' has this material id; it has: 1, 2");
    check_error("a missing file is refused",
                mesh_error(directory + "/no_such_mesh.msh", {}),
                "cannot be opened for reading");
    check_error("an unknown extension lists the formats",
                mesh_error(directory + "/quarter_annulus.xyz", {}),
                "the extension must name a format deal.II's GridIn reads");
  }
} // namespace


int
main(int argc, char **argv)
{
  if (argc != 2)
    {
      std::cerr << "usage: test_body_shapes <directory of tests/meshes>"
                << std::endl;
      return 2;
    }
  test_polygon();
  test_cylinder();
  test_ball_and_box();
  test_mesh(argv[1]);
  std::cout << (all_ok ? "all checks passed" : "SOME CHECKS FAILED")
            << std::endl;
  return all_ok ? 0 : 1;
}
