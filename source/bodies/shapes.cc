#include <deal.II/base/utilities.h>

#include <mpm/bodies/shape.h>
#include <mpm/parameters.h>

#include <cmath>
#include <sstream>

namespace mpm
{
  namespace
  {
    /// The radii of a round shape and of its hole (0: none), read and
    /// checked once for the ball and the cylinder.
    struct Radii
    {
      Radii(const ParameterHandler &prm, const std::string &path)
        : outer(Parse::bounded_double(prm, path, "radius", 0, 1e300, true))
        , inner(Parse::bounded_double(prm,
                                      path,
                                      "inner radius",
                                      0,
                                      outer,
                                      false,
                                      true))
      {
      }

      /// Is a point at squared distance @p r2 from the centre (or axis)
      /// in the material?
      bool
      admit(const double r2) const
      {
        return r2 < outer * outer && r2 >= inner * inner;
      }

      const double outer, inner;
    };


    template <int dim>
    class Box : public Shape<dim>
    {
    public:
      Box(const ParameterHandler &prm, const std::string &path)
        : lower(Parse::point<dim>(prm, path, "lower corner"))
        , upper(Parse::point<dim>(prm, path, "upper corner"))
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (!(upper[d] > lower[d]))
            throw InputError("parameters '" + path + "/lower corner', '" +
                             path + "/upper corner' = '" +
                             prm.get("lower corner") + "', '" +
                             prm.get("upper corner") +
                             "': the upper corner must exceed the lower corner "
                             "in every direction");
      }

      bool
      contains(const Point<dim> &x) const override
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (x[d] < lower[d] || x[d] > upper[d])
            return false;
        return true;
      }

      BoundingBox<dim>
      bounding_box() const override
      {
        return BoundingBox<dim>({lower, upper});
      }

      std::vector<std::string>
      extent_parameters() const override
      {
        return {"lower corner", "upper corner"};
      }

    private:
      const Point<dim> lower, upper;
    };


    /// A ball, or with an inner radius a ring (2D) or shell (3D).
    template <int dim>
    class Ball : public Shape<dim>
    {
    public:
      Ball(const ParameterHandler &prm, const std::string &path)
        : center(Parse::point<dim>(prm, path, "center"))
        , radii(prm, path)
      {
      }

      bool
      contains(const Point<dim> &x) const override
      {
        return radii.admit(x.distance_square(center));
      }

      BoundingBox<dim>
      bounding_box() const override
      {
        Point<dim> lower = center, upper = center;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lower[d] -= radii.outer;
            upper[d] += radii.outer;
          }
        return BoundingBox<dim>({lower, upper});
      }

      std::vector<std::string>
      extent_parameters() const override
      {
        return {"center", "radius"};
      }

      double
      rolling_radius() const override
      {
        return radii.outer;
      }

    private:
      const Point<dim> center;
      const Radii      radii;
    };


    /// A circular cylinder of any axis (3D), hollow with an inner radius.
    class Cylinder : public Shape<3>
    {
    public:
      Cylinder(const ParameterHandler &prm, const std::string &path)
        : center(Parse::point<3>(prm, path, "center"))
        , axis(Parse::vector<3>(prm, path, "axis"))
        , length(Parse::bounded_double(prm, path, "length", 0, 1e300, true))
        , radii(prm, path)
      {
        if (!(axis.norm() > 0))
          throw InputError(path + "/axis",
                           prm.get("axis"),
                           "must be a non-zero vector");
        axis /= axis.norm();
      }

      bool
      contains(const Point<3> &x) const override
      {
        const Tensor<1, 3> r     = x - center;
        const double       along = r * axis;
        return std::abs(along) <= 0.5 * length &&
               radii.admit((r - along * axis).norm_square());
      }

      BoundingBox<3>
      bounding_box() const override
      {
        Point<3> lower = center, upper = center;
        for (unsigned int d = 0; d < 3; ++d)
          {
            // The end disks' extent plus half the length along the axis.
            const double a = std::abs(axis[d]);
            const double e = 0.5 * length * a +
                             radii.outer * std::sqrt(std::max(0., 1 - a * a));
            lower[d] -= e;
            upper[d] += e;
          }
        return BoundingBox<3>({lower, upper});
      }

      std::vector<std::string>
      extent_parameters() const override
      {
        return {"center", "radius"};
      }

      double
      rolling_radius() const override
      {
        return radii.outer;
      }

    private:
      const Point<3> center;
      Tensor<1, 3>   axis;
      const double   length;
      const Radii    radii;
    };


    /// A simple polygon (2D), vertices in order, either orientation.
    class Polygon : public Shape<2>
    {
    public:
      Polygon(const ParameterHandler &prm, const std::string &path)
      {
        const std::string text = prm.get("vertices");
        const auto        bad  = [&](const std::string &why) {
          return InputError(path + "/vertices", text, why);
        };
        for (const auto &v : Utilities::split_string_list(text, ';'))
          {
            const auto xy = Utilities::split_string_list(v, ',');
            if (xy.size() != 2)
              throw bad("must be 'x0, y0; x1, y1; ...' (two coordinates "
                        "per vertex, vertices separated by ';')");
            try
              {
                vertices.emplace_back(Parse::number(xy[0]),
                                      Parse::number(xy[1]));
              }
            catch (...)
              {
                throw bad("the coordinates must be numbers");
              }
            if (!std::isfinite(vertices.back().norm()))
              throw bad("the coordinates must be finite");
          }
        if (vertices.size() < 3)
          throw bad("a polygon needs at least 3 vertices");
        check_simple(bad);
        double twice_area = 0;
        for (unsigned int i = 0; i < vertices.size(); ++i)
          twice_area += cross(vertices[i], vertex(i + 1));
        if (!(std::abs(twice_area) > 0))
          throw bad("the polygon has zero area");
      }

      bool
      contains(const Point<2> &x) const override
      {
        // Crossing number: a ray in +x crosses the boundary an odd number
        // of times from inside. Half-open edge test: no double counting.
        bool inside = false;
        for (unsigned int i = 0; i < vertices.size(); ++i)
          {
            const Point<2> &a = vertices[i];
            const Point<2> &b = vertex(i + 1);
            if ((a[1] > x[1]) != (b[1] > x[1]))
              {
                const double crossing =
                  a[0] + (x[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                if (x[0] < crossing)
                  inside = !inside;
              }
          }
        return inside;
      }

      BoundingBox<2>
      bounding_box() const override
      {
        return BoundingBox<2>(vertices);
      }

      std::vector<std::string>
      extent_parameters() const override
      {
        return {"vertices"};
      }

    private:
      std::vector<Point<2>> vertices;

      const Point<2> &
      vertex(const unsigned int i) const
      {
        return vertices[i % vertices.size()];
      }

      static double
      cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
      {
        return a[0] * b[1] - a[1] * b[0];
      }

      /// Do the closed segments pq and rs share a point?
      static bool
      segments_meet(const Point<2> &p,
                    const Point<2> &q,
                    const Point<2> &r,
                    const Point<2> &s)
      {
        const double d1 = cross(q - p, r - p), d2 = cross(q - p, s - p);
        const double d3 = cross(s - r, p - r), d4 = cross(s - r, q - r);
        if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) &&
            ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
          return true;
        // Touching or collinear overlap: an end point on the other segment.
        const auto on = [](const Point<2> &a,
                           const Point<2> &b,
                           const Point<2> &c,
                           const double    d) {
          return d == 0 && std::min(a[0], b[0]) <= c[0] &&
                 c[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= c[1] &&
                 c[1] <= std::max(a[1], b[1]);
        };
        return on(p, q, r, d1) || on(p, q, s, d2) || on(r, s, p, d3) ||
               on(r, s, q, d4);
      }

      /// Non-adjacent edges must not meet: a crossing polygon has no
      /// well-defined inside.
      template <typename Error>
      void
      check_simple(const Error &bad) const
      {
        const unsigned int n = vertices.size();
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = i + 2; j < n; ++j)
            if (!(i == 0 && j == n - 1) && segments_meet(vertex(i),
                                                         vertex(i + 1),
                                                         vertex(j),
                                                         vertex(j + 1)))
              throw bad("edges " + std::to_string(i) + " and " +
                        std::to_string(j) +
                        " cross or touch: the polygon must be simple");
      }
    };


    template <int dim>
    std::unique_ptr<Shape<dim>>
    make_dimension_specific(const std::string      &name,
                            const ParameterHandler &prm,
                            const std::string      &path)
    {
      if constexpr (dim == 3)
        if (name == "cylinder")
          return std::make_unique<Cylinder>(prm, path);
      if constexpr (dim == 2)
        if (name == "polygon")
          return std::make_unique<Polygon>(prm, path);
      throw InputError(path + "/shape",
                       name,
                       name == "cylinder"
                         ? "a cylinder is a 3D shape (in 2D, a box or a "
                           "polygon is its section)"
                         : "a polygon is a 2D shape");
    }
  } // namespace


  template <int dim>
  void
  Shape<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "lower corner",
      "0.25",
      Patterns::Anything(),
      "Box: lower corner, one value per dimension or one for all.");
    prm.declare_entry("upper corner",
                      "0.75",
                      Patterns::Anything(),
                      "Box: upper corner.");
    prm.declare_entry("center",
                      "0.5",
                      Patterns::Anything(),
                      "Ball: center. Cylinder: the middle of its axis.");
    prm.declare_entry("radius",
                      "0.25",
                      Patterns::Anything(),
                      "Ball, cylinder: radius, > 0.");
    prm.declare_entry("inner radius",
                      "0",
                      Patterns::Anything(),
                      "Ball, cylinder: radius of a hole at the centre, in "
                      "[0, radius): a ring in 2D, a spherical shell or a "
                      "tube in 3D.");
    prm.declare_entry("axis",
                      "0, 0, 1",
                      Patterns::Anything(),
                      "Cylinder: direction of the axis, any non-zero vector.");
    prm.declare_entry("length",
                      "0.5",
                      Patterns::Anything(),
                      "Cylinder: length along the axis, > 0.");
    prm.declare_entry("vertices",
                      "0.25, 0.25; 0.75, 0.25; 0.5, 0.75",
                      Patterns::Anything(),
                      "Polygon: its vertices in order (either orientation), "
                      "'x0, y0; x1, y1; ...', at least 3; edges must not "
                      "cross.");
  }


  template <int dim>
  std::unique_ptr<Shape<dim>>
  Shape<dim>::create(const ParameterHandler &prm, const std::string &path)
  {
    const std::string name = prm.get("shape");
    if (name == "box")
      return std::make_unique<Box<dim>>(prm, path);
    if (name == "ball")
      return std::make_unique<Ball<dim>>(prm, path);
    return make_dimension_specific<dim>(name, prm, path);
  }


  template class Shape<1>;
  template class Shape<2>;
  template class Shape<3>;
} // namespace mpm
