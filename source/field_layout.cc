#include <mpm/field_layout.h>

namespace mpm
{
  FieldRequests &
  FieldRequests::operator|=(const FieldRequests &other)
  {
    initial_position |= other.initial_position;
    displacement_origin |= other.displacement_origin;
    deformation_gradient |= other.deformation_gradient;
    affine_velocity |= other.affine_velocity;
    elastic_left_cauchy_green |= other.elastic_left_cauchy_green;
    plastic_strain |= other.plastic_strain;
    opening |= other.opening;
    damage |= other.damage;
    nonlocal_softening |= other.nonlocal_softening;
    surface_area |= other.surface_area;
    surface_offset |= other.surface_offset;
    point_load |= other.point_load;
    wall_slips = std::max(wall_slips, other.wall_slips);
    macro_step |= other.macro_step;
    mean_stress_correction |= other.mean_stress_correction;
    return *this;
  }


  template <int dim>
  FieldLayout
  assemble_layout(const FieldRequests &requests)
  {
    FieldLayout l;
    auto        add = [&l](const std::string &name, const unsigned int n) {
      l.description.emplace_back(name, n);
      return l.add(n);
    };
    l.mass     = add("mass", 1);
    l.volume   = add("volume", 1);
    l.body     = add("body", 1);
    l.velocity = add("velocity", dim);
    l.stress = add("stress", SymmetricTensor<2, dim>::n_independent_components);
    l.velocity_gradient = add("velocity gradient", dim * dim);
    if (requests.deformation_gradient)
      l.deformation_gradient = add("deformation gradient", dim * dim);
    if (requests.initial_position)
      l.initial_position = add("initial position", dim);
    if (requests.displacement_origin)
      l.displacement_origin = add("displacement origin", dim);
    if (requests.affine_velocity)
      l.affine_velocity = add("affine velocity", dim * dim);
    if (requests.elastic_left_cauchy_green)
      l.elastic_left_cauchy_green =
        add("elastic left Cauchy-Green", Fields::n_embedded<dim>);
    if (requests.plastic_strain)
      l.plastic_strain = add("plastic strain", 1);
    if (requests.opening)
      l.opening = add("opening", 1);
    if (requests.damage)
      {
        l.damage         = add("damage", 1);
        l.damage_history = add("damage history", 1);
      }
    if (requests.nonlocal_softening)
      l.nonlocal_softening = add("nonlocal softening", 2);
    if (requests.surface_area)
      l.surface_area = add("surface area", dim);
    if (requests.surface_offset)
      {
        l.surface_offset = add("surface offset", dim);
        l.load_moment    = add("load moment", dim * dim);
      }
    if (requests.point_load)
      l.point_load = add("point load", dim);
    if (requests.wall_slips > 0)
      l.wall_slip = add("wall slip", dim * requests.wall_slips);
    if (requests.macro_step)
      l.macro_step = add("macro step", dim + dim * dim);
    if (requests.mean_stress_correction)
      l.mean_stress_correction = add("F-bar mean stress", 1);
    return l;
  }


  template FieldLayout
  assemble_layout<1>(const FieldRequests &);
  template FieldLayout
  assemble_layout<2>(const FieldRequests &);
  template FieldLayout
  assemble_layout<3>(const FieldRequests &);
} // namespace mpm
