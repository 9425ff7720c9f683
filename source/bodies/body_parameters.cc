#include <deal.II/base/function_parser.h>

#include <mpm/bodies/body_parameters.templates.h>
#include <mpm/parameters.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace mpm
{
  namespace
  {
    /// The side of the square (cubic) cell of a grid cell's area (volume):
    /// the width of a shear band one cell wide, whatever its angle across
    /// cells that need not be square.
    template <int dim>
    double
    square_cell_size(const GridParameters<dim> &grid)
    {
      const Tensor<1, dim> h      = grid.cell_size();
      double               volume = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        volume *= h[d];
      return std::pow(volume, 1. / dim);
    }


    /// A comma-separated list of mesh ids (material or boundary) in
    /// (whole numbers >= 0); empty gives an empty set.
    std::set<unsigned int>
    id_list(const ParameterHandler &prm,
            const std::string      &path,
            const std::string      &entry)
    {
      const std::string      text = prm.get(entry);
      std::set<unsigned int> ids;
      for (const auto &item : Utilities::split_string_list(text, ','))
        {
          int id = -1;
          try
            {
              id = Utilities::string_to_int(item);
            }
          catch (...)
            {
            }
          if (id < 0)
            throw InputError(path + "/" + entry,
                             text,
                             "must be a comma-separated list of whole "
                             "numbers >= 0");
          ids.insert(static_cast<unsigned int>(id));
        }
      return ids;
    }
  } // namespace


  template <int dim>
  void
  BodyParameters<dim>::declare_parameters(ParameterHandler  &prm,
                                          const unsigned int index)
  {
    prm.enter_subsection("Bodies");
    prm.enter_subsection("Body " + std::to_string(index));
    prm.declare_entry("shape",
                      "box",
                      Patterns::Selection("box|ball|cylinder|polygon|mesh"),
                      "Shape of the body: box (lower/upper corner), ball "
                      "(center/radius; a disk in 2D), cylinder (3D: center, "
                      "axis, length, radius), polygon (2D: vertices) or "
                      "mesh (the cells of 'mesh file').");
    Shape<dim>::declare_parameters(prm);
    prm.declare_entry(
      "mesh file",
      "",
      Patterns::Anything(),
      "Mesh: a file deal.II's GridIn reads (gmsh .msh, .vtk, .inp, .ucd, "
      "...; format by extension), relative to the scene file's directory. "
      "Quadrilaterals, hexahedra and simplices. A point sits at each of the "
      "'particles per cell'^dim Gauss points of a cell, with that point's "
      "share JxW of the cell's volume.");
    prm.declare_entry(
      "mesh points",
      "grid",
      Patterns::Selection("grid|Gauss points"),
      "Mesh: where the points go. grid: on the grid's lattice inside the "
      "mesh's cells, 'particles per cell' per grid cell and direction (the "
      "body has the grid's resolution whatever the mesh's). Gauss points: "
      "at the 'particles per cell'^dim Gauss points of each mesh cell, each "
      "with its share JxW of the cell (the cell's volume exactly; a coarse "
      "mesh gives few points); needed for 'pressure boundary ids'.");
    prm.declare_entry("mesh material ids",
                      "",
                      Patterns::Anything(),
                      "Mesh: the material ids of the cells this body takes "
                      "(comma-separated; empty: all). Bodies that read the "
                      "same file with different ids give each region of "
                      "the mesh its own material.");
    prm.declare_entry(
      "pressure boundary ids",
      "",
      Patterns::Anything(),
      "Mesh: boundary ids of the faces that 'pressure' loads (comma-"
      "separated; empty: none). Each face's area goes to the nearest "
      "points of its cell, which carry the load from then on.");
    prm.declare_entry(
      "loaded surface",
      "",
      Patterns::Anything(),
      "Shape: the points that carry 'pressure' and 'traction': a face of the "
      "body's bounding box, 'x min', 'x max', 'y min', 'y max', 'z min' or "
      "'z max' (the outer layer of points there, each carrying its share of "
      "the face's area), or an expression in x, y, z that is > 0 on the "
      "points to load (each carrying the area V^((dim-1)/dim); traction "
      "only, as it gives no normal). Empty: none. A mesh body names its "
      "loaded faces in 'pressure boundary ids'.");
    prm.declare_entry(
      "pressure",
      "0",
      Patterns::Anything(),
      "Pressure in Pa on the loaded surface ('pressure boundary ids' or "
      "'loaded surface'), positive pushing on the body: an expression in x, "
      "y, z (current position of the loaded point) and t, e.g. a ramp "
      "'p0*t/T'. A dead load: it keeps the direction and area of the "
      "surface at t = 0, right while the surface turns and stretches "
      "little.");
    prm.declare_entry(
      "traction",
      "0",
      Patterns::Anything(),
      "Traction (force per area, Pa) on the loaded surface: one expression "
      "per component separated by ';' (or one for all), in x, y, z (current "
      "position of the loaded point) and t; applied at the points (seed "
      "001), on the area of t = 0 (a dead load).");
    prm.declare_entry("clip to grid",
                      "false",
                      Patterns::Bool(),
                      "Keep only the part of the body inside the grid, for "
                      "a body cut by symmetry planes on grid faces (a "
                      "quarter cylinder); false: the whole body must lie "
                      "inside the grid.");
    prm.declare_entry("particles per cell",
                      "2",
                      Patterns::Anything(),
                      "Material points per grid cell and direction, in "
                      "[1, 10]; for a mesh body, Gauss points per mesh cell "
                      "and direction.");
    prm.declare_entry("density",
                      "1000",
                      Patterns::Anything(),
                      "Initial mass density in kg/m^3, > 0.");
    prm.declare_entry("initial velocity",
                      "0",
                      Patterns::Anything(),
                      "Initial velocity: one expression per component "
                      "separated by ';' (or one for all), in the variables "
                      "x, y, z of the initial position; pi is known. "
                      "Example: '0.1*sin(pi*x/50)'.");
    prm.declare_entry("initial displacement",
                      "0",
                      Patterns::Anything(),
                      "Displacement u0(X) of the body at t = 0 from its shape "
                      "(the reference configuration): one expression per "
                      "component in x, y, z (or one for all). Points start at "
                      "X + u0 with F = I + grad u0 and the stress of that F; "
                      "needs a material whose stress follows from F "
                      "(neo-Hookean).");
    prm.declare_entry(
      "initial stress",
      "0",
      Patterns::Anything(),
      "Cauchy stress at t = 0 in Pa, tension positive: expressions in x, y, "
      "z separated by ';' for the components xx; yy; zz (1D), xx; yy; zz; xy "
      "(2D, plane strain: zz is the out-of-plane stress) or xx; yy; zz; xy; "
      "yz; xz (3D); e.g. a geostatic state 'K0*rho*g*(y-H); rho*g*(y-H); "
      "K0*rho*g*(y-H); 0' with constants. The material starts with the "
      "state that carries it (elastic strain); a plastic material must "
      "hold it inside its yield surface.");
    prm.declare_entry("body force",
                      "0",
                      Patterns::Anything(),
                      "Body force per unit mass (besides gravity), in m/s^2: "
                      "one expression per component separated by ';' (or "
                      "one for all), in the initial position x, y, z of the "
                      "point and time t, e.g. for manufactured solutions. "
                      "Non-zero makes every point store its initial position.");
    prm.declare_entry("rigid velocity",
                      "",
                      Patterns::Anything(),
                      "Empty for a deformable body. Otherwise the body is "
                      "rigid and moves with this velocity: one expression "
                      "per component separated by ';' (or one for all), in "
                      "t (a footing, a penetrometer, a tool). It gets a "
                      "velocity field of its own and acts on the other "
                      "bodies through contact (section Contact); its force "
                      "on them is written to statistics.csv "
                      "(rigid<N>_force_x, ...). Its material is not used "
                      "except for the density, which sets its mass.");
    prm.declare_entry("material",
                      "linear elastic",
                      Patterns::Selection(MaterialRegistry::names()),
                      "Constitutive model, one of: " +
                        MaterialRegistry::names() +
                        ". Its parameters are read from the subsection of the "
                        "same name.");
    MaterialRegistry::declare_parameters(prm);
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  BodyParameters<dim>::parse_parameters(ParameterHandler          &prm,
                                        const unsigned int         index,
                                        const GridParameters<dim> &grid)
  {
    name       = "Bodies/Body " + std::to_string(index);
    constants  = Parse::constants(prm);
    this->grid = grid;
    prm.enter_subsection("Bodies");
    prm.enter_subsection("Body " + std::to_string(index));
    particles_per_cell = static_cast<unsigned int>(
      Parse::bounded_double(prm, name, "particles per cell", 1, 10));
    if (particles_per_cell != prm.get_double("particles per cell"))
      throw InputError(name + "/particles per cell",
                       prm.get("particles per cell"),
                       "must be a whole number in [1, 10]");
    clip_to_grid = prm.get_bool("clip to grid");
    shape_name   = prm.get("shape");
    if (shape_name == "mesh")
      parse_mesh(prm);
    else
      parse_shape(prm);
    parse_surface_loads(prm);
    density      = Parse::bounded_double(prm, name, "density", 0, 1e300, true);
    density_text = prm.get("density");
    initial_velocity =
      Parse::expression_list(prm, "initial velocity", dim, name);
    initial_displacement =
      Parse::expression_list(prm, "initial displacement", dim, name);
    initial_stress   = Parse::expression_list(prm,
                                            "initial stress",
                                            dim == 1   ? 3
                                              : dim == 2 ? 4
                                                         : 6,
                                            name);
    const auto force = Parse::expression_list(prm, "body force", dim, name);
    if (!Parse::is_zero(force))
      body_force =
        Parse::vector_function<dim>(force, constants, name + "/body force");
    if (!prm.get("rigid velocity").empty())
      rigid_velocity = Parse::vector_function<dim>(
        Parse::expression_list(prm, "rigid velocity", dim, name),
        constants,
        name + "/rigid velocity");
    material_name = prm.get("material");
    material      = MaterialRegistry::create<dim>(material_name,
                                             prm,
                                             name,
                                             {density, square_cell_size(grid)});
    if (is_displaced() && !material->needs_deformation_gradient())
      throw InputError(name + "/initial displacement",
                       prm.get("initial displacement"),
                       "needs a material whose stress follows from F "
                       "(neo-Hookean); '" +
                         material_name + "' has no reference state");
    if (is_prestressed() && !material->accepts_initial_stress())
      throw InputError(name + "/initial stress",
                       prm.get("initial stress"),
                       "'" + material_name +
                         "' takes its stress from F alone and cannot start "
                         "stressed; use a model with an elastic state "
                         "(linear elastic, Hencky elastic, the plastic "
                         "models)");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  BodyParameters<dim>::parse_shape(const ParameterHandler &prm)
  {
    shape           = Shape<dim>::create(prm, name);
    const auto box  = shape->bounding_box();
    lower_corner    = box.get_boundary_points().first;
    upper_corner    = box.get_boundary_points().second;
    const bool fits = BoundingBox<dim>({grid.lower_corner, grid.upper_corner})
                        .point_inside(lower_corner) &&
                      BoundingBox<dim>({grid.lower_corner, grid.upper_corner})
                        .point_inside(upper_corner);
    if (!fits && !clip_to_grid)
      {
        std::ostringstream s;
        const auto         names = shape->extent_parameters();
        s << "parameter" << (names.size() > 1 ? "s" : "");
        for (unsigned int i = 0; i < names.size(); ++i)
          s << (i > 0 ? ", '" : " '") << name << "/" << names[i] << "'";
        s << ": the body spans (" << lower_corner << ") to (" << upper_corner
          << "); it must lie inside the grid box ('Grid/lower corner' to "
             "'Grid/upper corner'), or set 'clip to grid' to keep the part "
             "inside";
        throw InputError(s.str());
      }
  }


  template <int dim>
  void
  BodyParameters<dim>::parse_surface_loads(const ParameterHandler &prm)
  {
    const std::string surface    = prm.get("loaded surface");
    loaded_surface               = surface;
    const std::string ids        = prm.get("pressure boundary ids");
    bool              has_normal = false;
    if (mesh_seeds)
      {
        if (!surface.empty())
          throw InputError(name + "/loaded surface",
                           surface,
                           "is for shapes: a mesh body names its loaded "
                           "faces in 'pressure boundary ids'");
        has_normal = !mesh_seeds->areas.empty();
      }
    else
      {
        if (!ids.empty())
          throw InputError(name + "/pressure boundary ids",
                           ids,
                           "are faces of a mesh: needs shape 'mesh' (a "
                           "shape names its loaded surface in 'loaded "
                           "surface')");
        const std::vector<std::string> faces = {
          "x min", "x max", "y min", "y max", "z min", "z max"};
        const auto face = std::find(faces.begin(), faces.end(), surface);
        if (face != faces.end())
          {
            loaded_face = face - faces.begin();
            if (loaded_face >= 2 * dim)
              throw InputError(name + "/loaded surface",
                               surface,
                               "names an axis this " + std::to_string(dim) +
                                 "D scene does not have");
            has_normal = true;
          }
        else if (!surface.empty())
          loaded_points = Parse::vector_function<dim>({surface},
                                                      constants,
                                                      name + "/loaded surface");
      }
    const bool has_surface = has_normal || loaded_points;

    const std::string p = prm.get("pressure");
    if (!Parse::is_zero({p}))
      {
        if (!has_normal)
          throw InputError(name + "/pressure",
                           p,
                           has_surface
                             ? "needs a surface with a normal: a face of the "
                               "bounding box ('y max', ...) or a mesh's "
                               "'pressure boundary ids'; use 'traction' on "
                               "points picked by an expression"
                             : "needs a loaded surface: 'loaded surface' for a "
                               "shape, 'pressure boundary ids' for a mesh");
        pressure =
          Parse::vector_function<dim>({p}, constants, name + "/pressure");
      }
    const auto t = Parse::expression_list(prm, "traction", dim, name);
    if (!Parse::is_zero(t))
      {
        if (!has_surface)
          throw InputError(name + "/traction",
                           prm.get("traction"),
                           "needs a loaded surface: 'loaded surface' for a "
                           "shape, 'pressure boundary ids' for a mesh");
        traction =
          Parse::vector_function<dim>(t, constants, name + "/traction");
      }
  }


  template <int dim>
  SurfaceShare<dim>
  BodyParameters<dim>::shape_seed_surface(const Point<dim> &x,
                                          const double      volume) const
  {
    SurfaceShare<dim> s;
    if (loaded_face != numbers::invalid_unsigned_int)
      {
        // The outer layer of the lattice: its points lie half a spacing
        // inside the face, the next layer one and a half.
        const unsigned int axis  = loaded_face / 2;
        const bool         upper = loaded_face % 2 == 1;
        const double spacing     = grid.cell_size()[axis] / particles_per_cell;
        const double depth =
          upper ? upper_corner[axis] - x[axis] : x[axis] - lower_corner[axis];
        if (depth < spacing)
          {
            const double sign = upper ? 1. : -1.;
            s.area[axis]      = sign * volume / spacing;
            s.offset[axis]    = sign * depth;
          }
      }
    else if (loaded_points && loaded_points->value(x) > 0)
      s.area[0] = std::pow(volume, (dim - 1.) / dim);
    return s;
  }


  template <int dim>
  void
  BodyParameters<dim>::parse_mesh(const ParameterHandler &prm)
  {
    const std::string file = prm.get("mesh file");
    if (file.empty())
      throw InputError(name + "/mesh file",
                       "",
                       "shape 'mesh' needs the name of a mesh file");
    const auto material_ids = id_list(prm, name, "mesh material ids");
    const auto loaded_ids   = id_list(prm, name, "pressure boundary ids");
    const bool on_grid      = prm.get("mesh points") == "grid";
    if (on_grid && !loaded_ids.empty())
      throw InputError(name + "/pressure boundary ids",
                       prm.get("pressure boundary ids"),
                       "needs 'mesh points' = Gauss points (the faces' areas "
                       "go to the Gauss points of their cells)");
    Tensor<1, dim> spacing = grid.cell_size();
    spacing /= particles_per_cell;
    MeshSeeds<dim> read =
      on_grid ? lattice_seeds_in_mesh<dim>(
                  file, material_ids, grid.lower_corner, spacing, name)
              : seeds_from_mesh<dim>(
                  file, material_ids, loaded_ids, particles_per_cell, name);

    // Sort by grid cell; drop (clip) or refuse the points outside the grid.
    std::vector<unsigned int> order, cells(read.positions.size());
    for (unsigned int i = 0; i < read.positions.size(); ++i)
      {
        Point<dim> xi;
        cells[i] = grid.locate(read.positions[i], xi);
        if (cells[i] != numbers::invalid_unsigned_int)
          order.push_back(i);
        else if (!clip_to_grid)
          {
            std::ostringstream s;
            s << "has a point at (" << read.positions[i]
              << ") outside the grid box: the body must lie inside it (or "
                 "set 'clip to grid' to keep the part inside)";
            throw InputError(name + "/mesh file", file, s.str());
          }
      }
    std::stable_sort(order.begin(),
                     order.end(),
                     [&](const unsigned int a, const unsigned int b) {
                       return cells[a] < cells[b];
                     });
    auto seeds = std::make_shared<MeshSeeds<dim>>();
    for (const unsigned int i : order)
      {
        seeds->positions.push_back(read.positions[i]);
        seeds->volumes.push_back(read.volumes[i]);
        seeds->cells.push_back(cells[i]);
        if (!read.areas.empty())
          seeds->areas.push_back(read.areas[i]);
      }
    if (seeds->positions.empty())
      throw InputError(name + "/mesh file",
                       file,
                       "no cell of the mesh (with the material ids asked "
                       "for) lies inside the grid");
    const BoundingBox<dim> box(seeds->positions);
    lower_corner = box.get_boundary_points().first;
    upper_corner = box.get_boundary_points().second;
    mesh_seeds   = seeds;
  }


  template <int dim>
  std::pair<unsigned int, unsigned int>
  BodyParameters<dim>::mesh_seed_range(const Point<dim> &cell_origin) const
  {
    Point<dim> middle = cell_origin, xi;
    for (unsigned int d = 0; d < dim; ++d)
      middle[d] += 0.5 * grid.cell_size()[d];
    const unsigned int cell  = grid.locate(middle, xi);
    const auto        &cells = mesh_seeds->cells;
    const auto range = std::equal_range(cells.begin(), cells.end(), cell);
    return {range.first - cells.begin(), range.second - cells.begin()};
  }


  template <int dim>
  unsigned int
  BodyParameters<dim>::count_seeds(const Point<dim> &cell_origin) const
  {
    if (mesh_seeds)
      {
        const auto [first, last] = mesh_seed_range(cell_origin);
        return last - first;
      }
    unsigned int n = 0;
    for_each_seed(cell_origin,
                  [&n](const auto &, const auto &, auto, auto) { ++n; });
    return n;
  }


  template <int dim>
  std::string
  BodyParameters<dim>::sparse_points_warning() const
  {
    if (!mesh_seeds)
      return "";
    double volume = 0, cell_volume = 1;
    for (const double v : mesh_seeds->volumes)
      volume += v;
    for (unsigned int d = 0; d < dim; ++d)
      cell_volume *= grid.cell_size()[d];
    const double      cells    = volume / cell_volume;
    const std::size_t n_points = mesh_seeds->positions.size();
    if (!(n_points < cells))
      return "";
    std::ostringstream s;
    s << name << " has " << n_points << " points for the about "
      << std::round(cells)
      << " grid cells its mesh covers (fewer than one per cell: the body is "
         "coarser than the grid); set its 'mesh points' = grid, or raise "
         "'particles per cell'";
    return s.str();
  }


  template <int dim>
  bool
  BodyParameters<dim>::is_displaced() const
  {
    return !Parse::is_zero(initial_displacement);
  }


  template <int dim>
  bool
  BodyParameters<dim>::is_prestressed() const
  {
    return !Parse::is_zero(initial_stress);
  }


  template struct BodyParameters<1>;
  template struct BodyParameters<2>;
  template struct BodyParameters<3>;
} // namespace mpm
