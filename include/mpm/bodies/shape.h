#ifndef mpm_bodies_shape_h
#define mpm_bodies_shape_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The region a body fills with material points, given in closed form:
   * box, ball (a hole makes a ring or shell), cylinder (3D) or polygon (2D).
   * A body read from a mesh file has no Shape: its points are the mesh's
   * quadrature points (see bodies/mesh_seeds.h).
   */
  template <int dim>
  class Shape
  {
  public:
    virtual ~Shape() = default;

    /// The entries of every shape, in the current (body) subsection.
    static void
    declare_parameters(ParameterHandler &prm);

    /// The shape named by 'shape' in the current subsection; @p path
    /// ("Bodies/Body 0") names the parameters in messages. Throws
    /// InputError for a shape that does not exist in @p dim dimensions.
    static std::unique_ptr<Shape<dim>>
    create(const ParameterHandler &prm, const std::string &path);

    virtual bool
    contains(const Point<dim> &x) const = 0;

    /// A box that holds the whole shape.
    virtual BoundingBox<dim>
    bounding_box() const = 0;

    /// The parameters that set the shape's extent, for messages.
    virtual std::vector<std::string>
    extent_parameters() const = 0;

    /// The radius of the round surface the body can roll on (ball,
    /// cylinder); 0 for a shape whose edge has corners.
    virtual double
    rolling_radius() const
    {
      return 0;
    }
  };
} // namespace mpm

#endif
