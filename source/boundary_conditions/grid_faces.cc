#include <mpm/boundary_conditions/grid_faces.h>
#include <mpm/grid/nodal_layout.h>
#include <mpm/parameters.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace mpm
{


  template <int dim>
  GridFaces<dim>::GridFaces(const BackgroundGrid<dim>              &grid,
                            const std::vector<BodyParameters<dim>> &bodies)
    : grid(grid)
  {
    const auto &boundary = grid.parameters().boundary;
    if (std::count(boundary.begin(), boundary.end(), BoundaryType::absorbing) ==
        0)
      return;
    const unsigned int b = grid.parameters().absorbing_body;
    if (b >= bodies.size())
      throw InputError("Grid/absorbing body",
                       std::to_string(b),
                       "must be the index of a body, < " +
                         std::to_string(bodies.size()));
    const auto &body = bodies[b];
    normal_impedance =
      std::sqrt(body.density * body.material->p_wave_modulus());
    shear_impedance = std::sqrt(body.density * body.material->shear_modulus());
  }


  template <int dim>
  void
  GridFaces<dim>::reinit()
  {
    constrained_nodes.clear();
    friction_nodes.clear();
    pressed_faces.clear();
    absorbing_nodes.clear();
    closed_face_nodes.clear();
    const GridParameters<dim> &prm = grid.parameters();
    const Tensor<1, dim>      &h   = grid.cell_size();
    // An owned node lies on face f (x min, x max, y min, ...) if its index
    // in direction f / 2 is the first or the last.
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        const auto   c    = grid.owned_node_coordinates(i);
        unsigned int mask = 0, friction_faces = 0, closed_axes = 0;
        for (unsigned int f = 0; f < 2 * dim; ++f)
          {
            const unsigned int d = f / 2;
            if (c[d] != (f % 2 == 0 ? 0 : prm.n_cells[d]))
              continue;
            if (closes_the_grid(prm.boundary[f]))
              closed_axes |= 1u << d;
            switch (prm.boundary[f])
              {
                case BoundaryType::fixed:
                  mask |= (1u << dim) - 1;
                  break;
                case BoundaryType::slip:
                  mask |= 1u << d;
                  break;
                case BoundaryType::friction:
                  friction_faces |= 1u << f;
                  break;
                  case BoundaryType::absorbing: {
                    // The node's share of the face: half a cell in each
                    // tangential direction on either side of it.
                    double area = 1;
                    for (unsigned int e = 0; e < dim; ++e)
                      if (e != d)
                        area *=
                          (c[e] == 0 || c[e] == prm.n_cells[e] ? 0.5 : 1.) *
                          h[e];
                    absorbing_nodes.push_back({i, f, area});
                    break;
                  }
                case BoundaryType::free:
                  break;
              }
          }
        if (mask != 0)
          constrained_nodes.emplace_back(i, mask);
        if (friction_faces != 0)
          friction_nodes.emplace_back(i, friction_faces);
        if (closed_axes != 0)
          closed_face_nodes.emplace_back(i, closed_axes);
      }
  }


  template <int dim>
  void
  GridFaces<dim>::keep_contact_normals_in_faces(
    double            *data,
    const unsigned int n_fields,
    const unsigned int per_field) const
  {
    for (const auto &[i, axes] : closed_face_nodes)
      for (unsigned int f = 0; f < n_fields; ++f)
        {
          double *gradient =
            data + per_field * NodalLayout<dim>::slot_of(i, f, n_fields);
          for (unsigned int d = 0; d < dim; ++d)
            if (axes & (1u << d))
              gradient[d] = 0;
        }
  }


  template <int dim>
  void
  GridFaces<dim>::apply(double            *u,
                        const unsigned int n_fields,
                        const unsigned int slot,
                        const double       dt,
                        WorkAccount       *work,
                        const bool         for_strain_rate)
  {
    using Layout                 = NodalLayout<dim>;
    constexpr unsigned int width = Layout::n_velocities;
    for (const auto &[i, mask] : constrained_nodes)
      for (unsigned int f = 0; f < n_fields; ++f)
        {
          double *node = u + width * Layout::slot_of(i, f, n_fields);
          for (unsigned int d = 0; d < dim; ++d)
            if (mask & (1u << d))
              {
                if (work != nullptr)
                  work->face_constraint += impulse_work(node[Layout::node_mass],
                                                        node[slot + d],
                                                        0.,
                                                        node[Layout::v_old + d],
                                                        0.);
                node[slot + d] = 0;
              }
        }
    const double mu = grid.parameters().friction_coefficient;
    // The force update (dt > 0) records where the faces pressed.
    if (dt > 0)
      pressed_faces.assign(friction_nodes.size() * n_fields, 0);
    const bool hold = for_strain_rate && !pressed_faces.empty();
    for (unsigned int k = 0; k < friction_nodes.size(); ++k)
      for (unsigned int f = 0; f < n_fields; ++f)
        {
          const auto [i, faces] = friction_nodes[k];
          double *node          = u + width * Layout::slot_of(i, f, n_fields);
          for (unsigned int face = 0; face < 2 * dim; ++face)
            if (faces & (1u << face))
              {
                const bool pressed =
                  coulomb_contact_of_node(node, slot, face, mu, work);
                if (dt > 0 && pressed)
                  pressed_faces[k * n_fields + f] |= 1u << face;
                else if (hold &&
                         (pressed_faces[k * n_fields + f] & (1u << face)))
                  node[slot + face / 2] = 0;
              }
        }
    if (!(dt > 0))
      return;
    // The absorbing faces' dashpots act at the force update: the force
    // -A Z v (Z = rho c_p on the normal, rho c_s on the tangential
    // components) taken implicitly, m (v - v*) = -dt A Z v, so
    // v = v* / (1 + dt A Z / m): stable for any nodal mass, and a light
    // node is simply held.
    for (const AbsorbingNode &a : absorbing_nodes)
      for (unsigned int f = 0; f < n_fields; ++f)
        {
          double      *node = u + width * Layout::slot_of(a.node, f, n_fields);
          const double m    = node[Layout::node_mass];
          if (!(m > 0))
            continue;
          const double normal = 1. / (1. + dt * a.area * normal_impedance / m);
          const double shear  = 1. / (1. + dt * a.area * shear_impedance / m);
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double before = node[slot + d];
              node[slot + d] *= (d == a.face / 2) ? normal : shear;
              if (work != nullptr)
                work->face_constraint += impulse_work(m,
                                                      before,
                                                      node[slot + d],
                                                      node[Layout::v_old + d],
                                                      node[slot + d]);
            }
        }
  }


  template <int dim>
  bool
  GridFaces<dim>::has_unilateral_face(const GridParameters<dim> &prm)
  {
    return std::any_of(prm.boundary.begin(), prm.boundary.end(), is_unilateral);
  }


  template <int dim>
  bool
  GridFaces<dim>::coulomb_contact_of_node(double            *node,
                                          const unsigned int slot,
                                          const unsigned int face,
                                          const double       mu,
                                          WorkAccount       *work)
  {
    double *v = node + slot;
    if (work == nullptr)
      return apply_coulomb_contact(v, face, mu);
    // The normal impulse is the constraint's, the tangential one
    // friction's.
    const unsigned int axis = face / 2;
    double             before[dim];
    std::copy(v, v + dim, before);
    const bool   pressed = apply_coulomb_contact(v, face, mu);
    const double m       = node[NodalLayout<dim>::node_mass];
    for (unsigned int d = 0; d < dim; ++d)
      (d == axis ? work->face_constraint : work->face_friction) += impulse_work(
        m, before[d], v[d], node[NodalLayout<dim>::v_old + d], v[d]);
    return pressed;
  }


  template <int dim>
  bool
  GridFaces<dim>::apply_coulomb_contact(double            *v,
                                        const unsigned int face,
                                        const double       mu)
  {
    // The face's outward normal is +-e_axis. Only a velocity into the face
    // is in contact; its removal is the normal impulse (per unit mass), and
    // friction takes at most mu times that from the tangential velocity.
    const unsigned int axis   = face / 2;
    const double       sign   = (face % 2 == 0) ? -1. : 1.;
    const double       inward = sign * v[axis];
    if (!(inward > 0))
      return false;
    v[axis]              = 0;
    double tangential_sq = 0;
    for (unsigned int d = 0; d < dim; ++d)
      if (d != axis)
        tangential_sq += v[d] * v[d];
    if (tangential_sq == 0)
      return true;
    const double tangential = std::sqrt(tangential_sq);
    const double scale      = std::max(0., 1. - mu * inward / tangential);
    for (unsigned int d = 0; d < dim; ++d)
      if (d != axis)
        v[d] *= scale;
    return true;
  }


  template class GridFaces<1>;
  template class GridFaces<2>;
  template class GridFaces<3>;
} // namespace mpm
