#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <deal.II/numerics/data_out.h>

#include <mpm/materials/strain_measures.h>
#include <mpm/output.h>
#include <mpm/parameters.h>
#include <mpm/point_vtu_writer.h>
#include <mpm/time_integrator.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>

namespace mpm
{
  namespace
  {
    using DCI = DataComponentInterpretation::DataComponentInterpretation;
    constexpr DCI scalar = DataComponentInterpretation::component_is_scalar;
    constexpr DCI vector =
      DataComponentInterpretation::component_is_part_of_vector;
    constexpr DCI tensor =
      DataComponentInterpretation::component_is_part_of_tensor;

    /// What a field's entry reads to make its arrays: the points' layout,
    /// their bodies, and whether the particles go to HDF5.
    template <int dim>
    struct FieldContext
    {
      const FieldLayout                      &l;
      const std::vector<BodyParameters<dim>> &bodies;
      bool                                    hdf5;
    };

    template <int dim>
    using PointIterator =
      typename Particles::ParticleHandler<dim>::particle_iterator;

    /// A one-value field computed from a point's properties by @p value.
    template <int dim, typename Value>
    PointField<dim>
    scalar_field(const std::string &name, const Value value)
    {
      return {name, 1, scalar, [value](const PointIterator<dim> &p, double *v) {
                v[0] = value(p->get_properties().data());
              }};
    }

    /// What makes an entry's arrays for a scene (see PointFieldEntry).
    template <int dim>
    using FieldMaker = std::function<void(const FieldContext<dim> &,
                                          std::vector<PointField<dim>> &)>;

    /// The maker of the one field that @p make returns for the context.
    template <int dim, typename Make>
    FieldMaker<dim>
    one_field(const Make make)
    {
      return
        [make](const FieldContext<dim> &c, std::vector<PointField<dim>> &out) {
          out.push_back(make(c));
        };
    }

    /// The maker of a vector field computed by @p value from a point (its
    /// iterator) and the layout.
    template <int dim>
    FieldMaker<dim>
    point_vector(const char *name,
                 Tensor<1, dim> (*value)(const PointIterator<dim> &,
                                         const FieldLayout &))
    {
      return one_field<dim>([name, value](const FieldContext<dim> &c) {
        return PointField<dim>{name,
                               dim,
                               vector,
                               [&l = c.l, value](const PointIterator<dim> &p,
                                                 double                   *v) {
                                 const Tensor<1, dim> x = value(p, l);
                                 for (unsigned int d = 0; d < dim; ++d)
                                   v[d] = x[d];
                               }};
      });
    }

    /// The maker of a field computed by @p invariant from each point's
    /// Cauchy stress in 3D (with the out-of-plane stress in 2D).
    template <int dim, typename Invariant>
    FieldMaker<dim>
    stress_invariant(const char *name, const Invariant invariant)
    {
      return one_field<dim>([name, invariant](const FieldContext<dim> &c) {
        return scalar_field<dim>(
          name, [&l = c.l, &bodies = c.bodies, invariant](const double *q) {
            return invariant(
              bodies[q[l.body]].material->cauchy_stress_3d(q, l));
          });
      });
    }

    /// The maker of a field the points store as one number at @p slot
    /// (mass, volume, body, plastic strain, ...): the value is written as
    /// it is stored, or 0 if the scene's points do not store it.
    template <int dim>
    FieldMaker<dim>
    stored_scalar(const char *name, unsigned int FieldLayout::*slot)
    {
      return one_field<dim>([name, slot](const FieldContext<dim> &c) {
        return scalar_field<dim>(name, [i = c.l.*slot](const double *q) {
          return i == FieldLayout::absent ? 0. : q[i];
        });
      });
    }

    /**
     * The maker of a symmetric tensor field computed by @p value from a
     * point's properties and the layout. deal.II's HDF5 filter writes a
     * field of more than 3 components as a vector of 3 (measured: the 2D
     * stress tensor came out as 3 columns), so in HDF5 the tensor goes as
     * its independent components, name_xx, name_yy, name_xy, ...
     */
    template <int dim, typename Value>
    FieldMaker<dim>
    symmetric_tensor_field(const char *name, const Value value)
    {
      return [name, value](const FieldContext<dim>      &c,
                           std::vector<PointField<dim>> &out) {
        const FieldLayout &l = c.l;
        if (!c.hdf5)
          {
            out.push_back({name,
                           dim * dim,
                           tensor,
                           [&l, value](const PointIterator<dim> &p, double *v) {
                             const SymmetricTensor<2, dim> t =
                               value(p->get_properties().data(), l);
                             for (unsigned int i = 0; i < dim; ++i)
                               for (unsigned int j = 0; j < dim; ++j)
                                 v[i * dim + j] = t[i][j];
                           }});
            return;
          }
        const std::vector<std::pair<unsigned int, unsigned int>> components =
          dim == 1 ? std::vector<std::pair<unsigned int, unsigned int>>{{0, 0}}
          : dim == 2
            ? std::vector<std::pair<unsigned int, unsigned int>>{{0, 0},
                                                                 {1, 1},
                                                                 {0, 1}}
            : std::vector<std::pair<unsigned int, unsigned int>>{
                {0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
        for (const auto &[i, j] : components)
          out.push_back(
            scalar_field<dim>(std::string(name) + "_" + "xyz"[i] + "xyz"[j],
                              [&l, value, i = i, j = j](const double *q) {
                                return value(q, l)[i][j];
                              }));
      };
    }


    /// The log strain of a point's deformation gradient (see log_strain()).
    template <int dim>
    SymmetricTensor<2, 3>
    point_log_strain(const double *q, const FieldLayout &l)
    {
      return log_strain<dim>(Fields::tensor<dim>(q + l.deformation_gradient));
    }


    /// One point field of 'Output/fields': its name there, what the help
    /// text says of it, whether the default list has it, and the arrays it
    /// adds to the particle files.
    template <int dim>
    struct PointFieldEntry
    {
      const char     *name;
      const char     *note;
      bool            by_default;
      FieldMaker<dim> add;
    };

    /**
     * Every point field a scene can ask for, in the order of the files. A
     * new field is one entry here (and, if it needs data the points do
     * not store yet, its request in point_fields_needed).
     */
    template <int dim>
    const std::vector<PointFieldEntry<dim>> &
    point_field_table()
    {
      using It = PointIterator<dim>;
      using F  = FieldContext<dim>;
      using P  = std::vector<PointField<dim>>;
      static const std::vector<PointFieldEntry<dim>> table = {
        {"velocity",
         "",
         true,
         point_vector<dim>("velocity",
                           [](const It &p, const FieldLayout &l) {
                             return Fields::vector<dim>(
                               p->get_properties().data() + l.velocity);
                           })},
        {"displacement",
         "",
         true,
         point_vector<dim>("displacement",
                           [](const It &p, const FieldLayout &l) {
                             // From the last reset of a stage, if any.
                             const unsigned int origin =
                               l.displacement_origin != FieldLayout::absent
                                 ? l.displacement_origin
                                 : l.initial_position;
                             return p->get_location() -
                                    Point<dim>(Fields::vector<dim>(
                                      p->get_properties().data() + origin));
                           })},
        {"stress",
         "",
         true,
         symmetric_tensor_field<dim>("stress",
                                     [](const double *q, const FieldLayout &l) {
                                       return Fields::symmetric<dim>(q +
                                                                     l.stress);
                                     })},
        {"J",
         "",
         true,
         [](const F &c, P &out) {
           out.push_back(scalar_field<dim>(
             "J", [&l = c.l, &bodies = c.bodies](const double *q) {
               return q[l.volume] * bodies[q[l.body]].density / q[l.mass];
             }));
         }},
        {"mass", "", true, stored_scalar<dim>("mass", &FieldLayout::mass)},
        {"volume",
         "",
         true,
         stored_scalar<dim>("volume", &FieldLayout::volume)},
        {"body", "", true, stored_scalar<dim>("body", &FieldLayout::body)},
        {"plastic strain",
         "equivalent, 0 for elastic bodies",
         false,
         stored_scalar<dim>("plastic_strain", &FieldLayout::plastic_strain)},
        {"opening",
         "the log volume a cohesionless body gained at zero stress, where "
         "its grains parted; 0 elsewhere",
         false,
         stored_scalar<dim>("opening", &FieldLayout::opening)},
        {"damage",
         "d, 0 for bodies without damage",
         false,
         stored_scalar<dim>("damage", &FieldLayout::damage)},
        {"pressure",
         "-tr(sigma)/3, with the out-of-plane stress in 2D",
         false,
         stress_invariant<dim>("pressure",
                               [](const SymmetricTensor<2, 3> &s) {
                                 return -trace(s) / 3.;
                               })},
        {"von Mises stress",
         "sqrt(3/2 s:s), likewise",
         false,
         stress_invariant<dim>("von_Mises_stress",
                               [](const SymmetricTensor<2, 3> &sigma) {
                                 const SymmetricTensor<2, 3> s =
                                   deviator(sigma);
                                 return std::sqrt(1.5 * (s * s));
                               })},
        {"strain",
         "log strain 1/2 ln(F F^T) from the initial configuration, "
         "in-plane components in 2D; a stage's 'reset displacements' "
         "leaves it",
         false,
         symmetric_tensor_field<dim>("strain",
                                     [](const double *q, const FieldLayout &l) {
                                       const SymmetricTensor<2, 3> e =
                                         point_log_strain<dim>(q, l);
                                       SymmetricTensor<2, dim> t;
                                       for (unsigned int i = 0; i < dim; ++i)
                                         for (unsigned int j = i; j < dim; ++j)
                                           t[i][j] = e[i][j];
                                       return t;
                                     })},
        {"deviatoric strain",
         "sqrt(2/3 e:e) of the log strain's deviator e: where the "
         "ground shears, the failure surface",
         false,
         one_field<dim>([](const F &c) {
           return scalar_field<dim>("deviatoric_strain",
                                    [&l = c.l](const double *q) {
                                      return deviatoric_strain(
                                        point_log_strain<dim>(q, l));
                                    });
         })}};
      return table;
    }


    /// The names of the point fields, joined by @p separator; only those
    /// of the default list if @p defaults_only, and with each one's note
    /// in parentheses if @p with_notes.
    std::string
    point_field_names(const std::string &separator,
                      const bool         defaults_only,
                      const bool         with_notes)
    {
      std::string names;
      for (const auto &entry : point_field_table<3>())
        if (entry.by_default || !defaults_only)
          {
            names += (names.empty() ? "" : separator) + entry.name;
            if (with_notes && entry.note[0] != '\0')
              names += std::string(" (") + entry.note + ")";
          }
      return names;
    }
  } // namespace


  void
  OutputParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("directory",
                      "output",
                      Patterns::Anything(),
                      "Directory for particles.pvd, grid.pvd, statistics.csv.");
    prm.declare_entry("interval",
                      "0.01",
                      Patterns::Anything(),
                      "Simulated time between outputs, >= 0 (0: every step). "
                      "Steps are shortened to land on output times.");
    prm.declare_entry(
      "fields",
      point_field_names(", ", true, false),
      Patterns::MultipleSelection(point_field_names("|", false, false)),
      "Particle fields written to VTU, any of: " +
        point_field_names(", ", false, true) +
        ". 'displacement' makes every point store its initial position, "
        "'strain' and 'deviatoric strain' its deformation gradient; "
        "pressure, von Mises stress and the strains are computed at output "
        "only.");
    prm.declare_entry(
      "particle format",
      "VTU",
      Patterns::Selection("VTU|HDF5"),
      "VTU (particles_NNNNN.vtu per output time, particles.pvd) or HDF5 "
      "(particles_NNNNN.h5 and its particles_NNNNN.xdmf per output time, "
      "particles.xdmf for all of them; open the .xdmf in ParaView with the "
      "XDMF reader). Either is one file per output time written by all "
      "ranks at once.");
    prm.declare_entry(
      "grid output",
      "false",
      Patterns::Bool(),
      "true or false: also write nodal mass and velocity on the "
      "grid (VTU, grid.pvd).");
    prm.declare_entry(
      "body extents",
      "false",
      Patterns::Bool(),
      "true or false: add to statistics.csv where each body reaches: the "
      "box around its material points, columns body<b>_<axis>_min and "
      "_max (the points' positions: the body's edge lies about half a "
      "point spacing further out), the fronts of 'front percentile' "
      "(_front_min, _front_max) and, with a 'front thickness', the "
      "deposit's edges (_deposit_min, _deposit_max). For runout, length "
      "and spread. A body without points (or without a deposit) leaves "
      "its fields empty.");
    prm.declare_entry(
      "front percentile",
      "99",
      Patterns::Anything(),
      "With 'body extents': the columns body<b>_<axis>_front_min and "
      "_front_max are the positions that this percentage of a body's "
      "points do not pass (within 1/64 of a cell), in [50, 100]; 100 is "
      "the furthest point. A runout front that a few points thrown ahead "
      "of the body cannot move.");
    prm.declare_entry(
      "front thickness",
      "0",
      Patterns::Anything(),
      "With 'body extents' and gravity along a grid axis: > 0 adds, for "
      "each other axis, columns body<b>_<axis>_deposit_min and _max, the "
      "furthest edges of a body where it is at least this thick along "
      "gravity, in m (in each column of grid cells, the volume of the "
      "body's points over the column's width, gaps closed, without the "
      "volume a cohesionless material gained by parting; the edge is "
      "that of the outermost point of such a column, each point a cube of "
      "its volume). 0: none.");
    prm.declare_entry("progress interval",
                      "2",
                      Patterns::Anything(),
                      "Wall-clock seconds between progress lines, >= 0.");
    prm.declare_entry(
      "existing output",
      "replace",
      Patterns::Selection("replace|refuse"),
      "What to do with the output of an earlier run in 'directory': "
      "replace (its frames, .pvd records, statistics.csv and timing.csv are "
      "removed first, so no stale frame stays beside the new ones; other "
      "files are left alone) or refuse (stop with an error).");
    prm.leave_subsection();
  }


  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory = prm.get("directory");
    if (directory.empty())
      throw InputError("Output/directory", "", "must not be empty");
    interval     = Parse::bounded_double(prm, "Output", "interval", 0, 1e300);
    fields       = Utilities::split_string_list(prm.get("fields"), ',');
    grid_output  = prm.get_bool("grid output");
    hdf5         = prm.get("particle format") == "HDF5";
    body_extents = prm.get_bool("body extents");
    front_percentile =
      Parse::bounded_double(prm, "Output", "front percentile", 50, 100);
    front_thickness =
      Parse::bounded_double(prm, "Output", "front thickness", 0, 1e300);
    replace_existing = prm.get("existing output") == "replace";
    progress_interval =
      Parse::bounded_double(prm, "Output", "progress interval", 0, 1e300);
    prm.leave_subsection();
  }


  bool
  OutputParameters::writes(const std::string &name) const
  {
    return std::find(fields.begin(), fields.end(), name) != fields.end();
  }



  namespace
  {
    /// Material points as zero-dimensional patches for DataOutBase.
    template <int dim>
    class ParticlePatches : public DataOutInterface<0, dim>
    {
    public:
      std::vector<DataOutBase::Patch<0, dim>> patches;
      std::vector<std::string>                names;
      std::vector<DataComponentInterpretation::DataComponentInterpretation>
        interpretation;

      void
      add_field(
        const std::string &name,
        const unsigned int n_components,
        const DataComponentInterpretation::DataComponentInterpretation kind)
      {
        for (unsigned int c = 0; c < n_components; ++c)
          {
            names.push_back(name);
            interpretation.push_back(kind);
          }
      }

    private:
      const std::vector<DataOutBase::Patch<0, dim>> &
      get_patches() const override
      {
        return patches;
      }
      std::vector<std::string>
      get_dataset_names() const override
      {
        return names;
      }
      std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
      get_nonscalar_data_ranges() const override
      {
        std::vector<
          std::tuple<unsigned int,
                     unsigned int,
                     std::string,
                     DataComponentInterpretation::DataComponentInterpretation>>
          ranges;
        for (unsigned int i = 0; i < names.size();)
          {
            unsigned int j = i;
            while (j + 1 < names.size() && names[j + 1] == names[i])
              ++j;
            if (interpretation[i] !=
                DataComponentInterpretation::component_is_scalar)
              ranges.emplace_back(i, j, names[i], interpretation[i]);
            i = j + 1;
          }
        return ranges;
      }
    };


    /// Where frames are written before they are moved into the output
    /// directory, complete.
    const char *const partial = ".partial";

    /// The diagnosis for an output directory that cannot be used.
    std::string
    unwritable(const std::string &directory)
    {
      return InputError("Output/directory",
                        directory,
                        "cannot be created or written")
        .what();
    }

    /// The number of a frame file (particles_00012.0.vtu: 12); -1 for the
    /// program's other files and for files not its own.
    int
    frame_number(const std::filesystem::path &file)
    {
      const std::string name = file.filename().string();
      const auto        ext  = file.extension();
      for (const std::string base : {"particles_", "grid_"})
        if (name.rfind(base, 0) == 0 &&
            (ext == ".vtu" || ext == ".pvtu" || ext == ".h5" || ext == ".xdmf"))
          return std::atoi(name.c_str() + base.size());
      return -1;
    }

    /// Is @p file one this program writes into its output directory (the
    /// partial directory aside)?
    bool
    is_own_output(const std::filesystem::path &file)
    {
      const std::string name = file.filename().string();
      return frame_number(file) >= 0 || name == "particles.pvd" ||
             name == "particles.xdmf" || name == "grid.pvd" ||
             name == "statistics.csv" || name == "timing.csv";
    }

    /// Create @p directory and an empty partial directory in it.
    std::string
    make_directories(const std::string &directory)
    {
      std::error_code error;
      std::filesystem::create_directories(directory, error);
      if (!error)
        std::filesystem::remove_all(directory + "/" + partial, error);
      if (!error)
        std::filesystem::create_directory(directory + "/" + partial, error);
      return error || !std::filesystem::is_directory(directory + "/" + partial)
               ? unwritable(directory)
               : "";
    }

    /**
     * Make @p directory ready for a run: create it, and remove (or refuse)
     * an earlier run's output in it. Returns a diagnosis, empty if fine.
     */
    std::string
    prepare_directory(const std::string &directory, const bool replace)
    {
      if (const std::string failure = make_directories(directory);
          !failure.empty())
        return failure;
      std::error_code                    error;
      std::vector<std::filesystem::path> old;
      for (const auto &entry :
           std::filesystem::directory_iterator(directory, error))
        if (is_own_output(entry.path()))
          old.push_back(entry.path());
      if (!old.empty() && !replace)
        return InputError("Output/existing output",
                          "refuse",
                          "'" + directory +
                            "' holds the output of an earlier run (" +
                            old.front().filename().string() +
                            "); choose another directory or 'replace'")
          .what();
      for (const auto &path : old)
        std::filesystem::remove(path, error);
      return "";
    }

    /**
     * Make @p directory ready to continue a run from a checkpoint taken
     * at time @p time after @p frames frames: frames the run wrote after
     * the checkpoint and rows of statistics.csv after @p time go (the
     * restarted run writes them again). Returns a diagnosis, empty if fine.
     */
    std::string
    resume_directory(const std::string &directory,
                     const unsigned int frames,
                     const double       time)
    {
      if (const std::string failure = make_directories(directory);
          !failure.empty())
        return failure;
      std::error_code error;
      for (const auto &entry :
           std::filesystem::directory_iterator(directory, error))
        if (frame_number(entry.path()) >= static_cast<int>(frames))
          std::filesystem::remove(entry.path(), error);
      const std::string        statistics = directory + "/statistics.csv";
      std::ifstream            in(statistics);
      std::vector<std::string> kept;
      std::string              line;
      while (std::getline(in, line))
        {
          const auto first = line.find(',');
          const auto second =
            first == std::string::npos ? first : line.find(',', first + 1);
          // The header, and the rows up to the checkpoint (the time is the
          // second column, written with 12 digits).
          if (kept.empty() || (second != std::string::npos &&
                               std::strtod(line.c_str() + first + 1, nullptr) <=
                                 time * (1 + 1e-11)))
            kept.push_back(line);
        }
      if (kept.empty())
        return InputError("--restart",
                          statistics,
                          "is missing or empty: the run's output must stay "
                          "in 'Output/directory' to continue it")
          .what();
      std::ofstream out(statistics);
      for (const auto &k : kept)
        out << k << '\n';
      return "";
    }

    /// Write a PVD record next to its files, atomically: a reader (or a
    /// later crash) never sees a half-written file.
    void
    write_pvd(const std::string                                 &file,
              const std::vector<std::pair<double, std::string>> &entries)
    {
      {
        std::ofstream out(file + ".tmp");
        DataOutBase::write_pvd_record(out, entries);
      }
      std::filesystem::rename(file + ".tmp", file);
    }

    /**
     * The XDMF collection of all output times, atomically like the PVD
     * record: each frame's own .xdmf (which deal.II writes for its .h5)
     * is included by XInclude, so the collection needs nothing but the
     * names and can be written again after a restart.
     */
    void
    write_xdmf_collection(
      const std::string                                 &file,
      const std::vector<std::pair<double, std::string>> &entries)
    {
      {
        std::ofstream out(file + ".tmp");
        out << "<?xml version=\"1.0\" ?>\n"
            << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
            << "<Xdmf Version=\"2.0\" "
               "xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
            << "  <Domain>\n"
            << "    <Grid Name=\"particles\" GridType=\"Collection\" "
               "CollectionType=\"Temporal\">\n";
        for (const auto &[time, name] : entries)
          out << "      <xi:include href=\"" << name
              << "\" xpointer=\"xpointer(//Xdmf/Domain/Grid/Grid)\"/>\n";
        out << "    </Grid>\n  </Domain>\n</Xdmf>\n";
      }
      std::filesystem::rename(file + ".tmp", file);
    }

    /// The .xdmf of a frame without points: its time, no geometry.
    void
    write_empty_xdmf(const std::string &file, const double time)
    {
      std::ofstream out(file);
      out << "<?xml version=\"1.0\" ?>\n"
          << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
          << "<Xdmf Version=\"2.0\">\n"
          << "  <Domain>\n"
          << "    <Grid Name=\"CellTime\" GridType=\"Collection\" "
             "CollectionType=\"Temporal\">\n"
          << "      <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
          << "        <Time Value=\"" << time << "\"/>\n"
          << "        <Topology TopologyType=\"Polyvertex\" "
             "NumberOfElements=\"0\"/>\n"
          << "      </Grid>\n"
          << "    </Grid>\n"
          << "  </Domain>\n"
          << "</Xdmf>\n";
    }
  } // namespace



  template <int dim>
  Output<dim>::Output(const OutputParameters         &parameters,
                      const BackgroundGrid<dim>      &grid,
                      const MaterialPoints<dim>      &points,
                      const TimeIntegrator<dim>      &integrator,
                      const Tensor<1, dim>           &gravity,
                      const std::vector<std::string> &extra_columns,
                      MPI_Comm                        comm,
                      const RunState                 *resume)
    : prm(parameters)
    , grid(grid)
    , points(points)
    , integrator(integrator)
    , gravity(gravity)
    , comm(comm)
    , is_root(Utilities::MPI::this_mpi_process(comm) == 0)
  {
    // Checked on the root, raised on every rank (a throw on the root
    // alone left the others waiting in the next collective call).
    std::string failure;
    if (resume != nullptr)
      {
        counter = resume->get("output_counter");
        // From the checkpoint's time, not its next output time: a restart
        // may change the interval (the saved time belongs to the old one).
        next_time      = output_time_after(resume->get("time"));
        particle_files = resume->particle_files;
        grid_files     = resume->grid_files;
      }
    if (is_root)
      {
        failure =
          resume != nullptr
            ? resume_directory(prm.directory, counter, resume->get("time"))
            : prepare_directory(prm.directory, prm.replace_existing);
        if (failure.empty())
          {
            statistics_file.open(prm.directory + "/statistics.csv",
                                 resume != nullptr ? std::ios::app
                                                   : std::ios::out);
            if (!statistics_file)
              failure = unwritable(prm.directory);
          }
      }
    raise_if_any_failed(failure, comm, true);
    if (is_root && resume != nullptr)
      {
        // The records as of the checkpoint: frames written after it are
        // gone.
        if (prm.hdf5)
          write_xdmf_collection(prm.directory + "/particles.xdmf",
                                particle_files);
        else
          write_pvd(prm.directory + "/particles.pvd", particle_files);
        if (!grid_files.empty())
          write_pvd(prm.directory + "/grid.pvd", grid_files);
      }
    if (is_root && resume == nullptr)
      {
        const char *axis[] = {"x", "y", "z"};
        statistics_file << "step,time,dt,kinetic_energy,strain_energy,"
                           "gravitational_energy,total_energy";
        for (unsigned int d = 0; d < dim; ++d)
          statistics_file << ",momentum_" << axis[d];
        if (dim == 2)
          statistics_file << ",angular_momentum_z";
        if (dim == 3)
          statistics_file
            << ",angular_momentum_x,angular_momentum_y,angular_momentum_z";
        statistics_file << ",mass,particles,removed";
        for (const auto &c : extra_columns)
          statistics_file << "," << c;
        statistics_file << ",wall_seconds\n";
      }
    MPI_Barrier(comm);
  }


  template <int dim>
  void
  Output<dim>::write(const Statistics<dim>     &s,
                     const std::vector<double> &extra,
                     const double               wall_seconds)
  {
    if (is_root)
      {
        auto &f = statistics_file;
        f << integrator.step_number() << std::setprecision(12) << ","
          << integrator.time() << "," << integrator.last_time_step() << ","
          << s.kinetic_energy << "," << s.strain_energy << ","
          << s.gravitational_energy << "," << s.total_energy();
        for (unsigned int d = 0; d < dim; ++d)
          f << "," << s.momentum[d];
        if (dim > 1)
          for (unsigned int d = 0; d < s.angular_momentum.dimension; ++d)
            f << "," << s.angular_momentum[d];
        f << "," << s.mass << "," << s.n_particles << ","
          << integrator.n_removed_particles();
        // Only a body's extents can be missing (a body without points);
        // their fields stay empty rather than hold inf.
        for (const double e : extra)
          {
            f << ",";
            if (std::isfinite(e))
              f << e;
          }
        f << "," << std::setprecision(4) << wall_seconds << std::endl;
      }
    write_particles();
    if (prm.grid_output)
      write_grid();
    ++counter;
    next_time = output_time_after(integrator.time());
  }


  template <int dim>
  double
  Output<dim>::output_time_after(const double t) const
  {
    // The multiples of the interval, counted from t = 0 whatever the
    // frame counter says: after a restart with another interval the frames
    // carry on the new interval's times (before, counter * interval: a
    // finer interval wrote a frame every step until the counter caught
    // up).
    return prm.interval > 0 ? multiple_after(t, prm.interval) : 0;
  }


  template <int dim>
  std::vector<typename Output<dim>::PointField>
  Output<dim>::point_fields() const
  {
    const FieldContext<dim> context{points.layout(), points.bodies(), prm.hdf5};
    std::vector<PointField> fields;
    for (const auto &entry : point_field_table<dim>())
      if (prm.writes(entry.name))
        entry.add(context, fields);
    return fields;
  }


  template <int dim>
  void
  Output<dim>::write_particles()
  {
    const std::vector<PointField> fields = point_fields();
    if (prm.hdf5)
      write_hdf5_particles(fields);
    else
      write_vtu_particles(fields);
  }


  /**
   * The VTU of the points, streamed field by field (PointVtuWriter): VTK
   * wants 3 components for a vector and 9 for a tensor, so 2D ones are
   * padded with zeros.
   */
  template <int dim>
  void
  Output<dim>::write_vtu_particles(const std::vector<PointField> &fields)
  {
    const auto &handler = points.handler();
    const auto  fill    = [&](const unsigned int  n_values,
                          const unsigned int  n_written,
                          const auto         &values,
                          std::vector<float> &out) {
      out.assign(n_written * handler.n_locally_owned_particles(), 0.f);
      std::vector<double> v(n_values);
      std::size_t         k = 0;
      for (auto p = handler.begin(); p != handler.end(); ++p, k += n_written)
        {
          values(p, v.data());
          if (n_values == dim * dim && dim > 1)
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                out[k + 3 * i + j] = v[i * dim + j];
          else
            for (unsigned int c = 0; c < n_values; ++c)
              out[k + c] = v[c];
        }
    };
    using Point = typename Particles::ParticleHandler<dim>::particle_iterator;
    const PointVtuWriter               writer(comm,
                                handler.n_locally_owned_particles(),
                                [&](std::vector<float> &out) {
                                  fill(
                                    dim,
                                    3,
                                    [](const Point &p, double *v) {
                                      for (unsigned int d = 0; d < dim; ++d)
                                        v[d] = p->get_location()[d];
                                    },
                                    out);
                                });
    std::vector<PointVtuWriter::Field> vtu_fields;
    for (const PointField &f : fields)
      {
        const unsigned int n_written =
          f.kind == DataComponentInterpretation::component_is_part_of_vector ? 3
          : f.kind == DataComponentInterpretation::component_is_part_of_tensor
            ? 9
            : f.n_values;
        vtu_fields.push_back(
          {f.name, n_written, [&, n_written](std::vector<float> &out) {
             fill(f.n_values, n_written, f.values, out);
           }});
      }
    // One .vtu per output time whatever the number of ranks, written into
    // the partial directory and moved out once complete (the .vtu first,
    // the .pvtu that names it next, the .pvd record last), so a run killed
    // at any moment leaves only complete frames, each listed in the .pvd
    // or not at all.
    const std::string frame =
      "particles_" + Utilities::int_to_string(counter, 5);
    const std::string partial_directory = prm.directory + "/" + partial + "/";
    writer.write(partial_directory + frame + ".0.vtu",
                 vtu_fields,
                 integrator.time(),
                 integrator.step_number());
    if (is_root)
      {
        PointVtuWriter::write_pvtu(partial_directory + frame + ".pvtu",
                                   frame + ".0.vtu",
                                   vtu_fields);
        publish_frame(frame + ".pvtu");
        particle_files.emplace_back(integrator.time(), frame + ".pvtu");
        write_pvd(prm.directory + "/particles.pvd", particle_files);
      }
  }


  template <int dim>
  void
  Output<dim>::write_hdf5_particles(const std::vector<PointField> &fields)
  {
    ParticlePatches<dim> out;
    for (const PointField &f : fields)
      out.add_field(f.name, f.n_values, f.kind);
    out.patches.reserve(points.handler().n_locally_owned_particles());
    std::vector<double> v;
    for (auto p = points.handler().begin(); p != points.handler().end(); ++p)
      {
        DataOutBase::Patch<0, dim> patch;
        patch.vertices[0] = p->get_location();
        patch.patch_index = out.patches.size();
        patch.data.reinit(out.names.size(), 1);
        unsigned int c = 0;
        for (const PointField &f : fields)
          {
            v.resize(f.n_values);
            f.values(p, v.data());
            for (const double value : v)
              patch.data(c++, 0) = value;
          }
        out.patches.push_back(std::move(patch));
      }
    write_hdf5_files(out, out.patches.size(), "particles", particle_files);
  }


  template <int dim>
  void
  Output<dim>::write_grid()
  {
    const auto partitioner = grid.make_partitioner(1);
    std::vector<LinearAlgebra::distributed::Vector<double>> fields(
      1 + dim, LinearAlgebra::distributed::Vector<double>(partitioner));
    for (unsigned int i = 0; i < grid.n_locally_owned_nodes(); ++i)
      {
        fields[0].local_element(i) = integrator.nodal_state().mass(i);
        for (unsigned int d = 0; d < dim; ++d)
          fields[1 + d].local_element(i) =
            integrator.nodal_state().velocity(i, d);
      }
    DataOut<dim> data_out;
    data_out.attach_dof_handler(grid.dof_handler());
    const char *names[] = {"mass", "velocity_x", "velocity_y", "velocity_z"};
    for (unsigned int c = 0; c < 1 + dim; ++c)
      {
        fields[c].update_ghost_values();
        data_out.add_data_vector(fields[c], names[c]);
      }
    // One patch subdivision per grid cell of a tile: the patches' points
    // are the grid's nodes.
    data_out.build_patches(grid.tile_size());
    write_files(data_out, "grid", grid_files);
  }


  template <int dim>
  template <int patch_dim>
  void
  Output<dim>::write_files(DataOutInterface<patch_dim, dim>            &out,
                           const std::string                           &base,
                           std::vector<std::pair<double, std::string>> &records)
  {
    DataOutBase::VtkFlags flags;
    flags.time  = integrator.time();
    flags.cycle = integrator.step_number();
    // deal.II's default, best_compression, made output 10x slower than a
    // step of the whole scene for about the same file size.
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    out.set_flags(flags);
    // One .vtu per output time whatever the number of ranks (n_groups = 1),
    // written into the partial directory and moved out once complete (the
    // .vtu first, the .pvtu that names it next, the .pvd record last), so
    // a run killed at any moment leaves only complete frames, each listed
    // in the .pvd or not at all.
    const std::string partial_directory = prm.directory + "/" + partial + "/";
    const std::string name              = out.write_vtu_with_pvtu_record(
      partial_directory, base, counter, comm, 5, 1);
    // The .vtu is closed by every rank (collective MPI-IO) when this
    // returns; the .pvtu is the root's.
    if (is_root)
      {
        publish_frame(name);
        records.emplace_back(integrator.time(), name);
        write_pvd(prm.directory + "/" + base + ".pvd", records);
      }
  }


  /**
   * deal.II 9.4 hands HDF5 a null buffer for a rank without points, which
   * HDF5 refuses ('no output buffer') while the other ranks wait in the
   * collective write: a 3D block on 2 ranks, one of them empty, hung. So
   * only the ranks that have points write the .h5 and the .xdmf, on a
   * communicator of their own; a frame without any point gets an .xdmf of
   * no points and no .h5.
   */
  template <int dim>
  void
  Output<dim>::write_hdf5_files(
    DataOutInterface<0, dim>                    &out,
    const std::size_t                            n_local_points,
    const std::string                           &base,
    std::vector<std::pair<double, std::string>> &records)
  {
    const std::string frame = base + "_" + Utilities::int_to_string(counter, 5);
    const std::string partial_directory = prm.directory + "/" + partial + "/";
    const bool        writes            = n_local_points > 0;
    const std::size_t n_points = Utilities::MPI::sum(n_local_points, comm);
    MPI_Comm          writers;
    MPI_Comm_split(comm,
                   writes ? 0 : MPI_UNDEFINED,
                   Utilities::MPI::this_mpi_process(comm),
                   &writers);
    if (writes)
      {
        // Points are not merged (no duplicate vertices to filter); the
        // data are written with every component of a vector or tensor
        // together.
        DataOutBase::DataOutFilter filter(
          DataOutBase::DataOutFilterFlags(false, true));
        out.write_filtered_data(filter);
        out.write_hdf5_parallel(filter,
                                partial_directory + frame + ".h5",
                                writers);
        // The frame's .xdmf names its .h5 relative to itself.
        const std::vector<XDMFEntry> entry = {out.create_xdmf_entry(
          filter, frame + ".h5", integrator.time(), writers)};
        out.write_xdmf_file(entry,
                            partial_directory + frame + ".xdmf",
                            writers);
        MPI_Comm_free(&writers);
      }
    else if (is_root && n_points == 0)
      write_empty_xdmf(partial_directory + frame + ".xdmf", integrator.time());
    // The files are complete before the root moves them.
    MPI_Barrier(comm);
    if (is_root)
      {
        publish_frame(frame + ".xdmf");
        records.emplace_back(integrator.time(), frame + ".xdmf");
        write_xdmf_collection(prm.directory + "/" + base + ".xdmf", records);
      }
  }


  /**
   * The data files of a frame go first and the file that names them last,
   * so that a run killed at any moment leaves only complete frames.
   */
  template <int dim>
  void
  Output<dim>::publish_frame(const std::string &name) const
  {
    const std::string partial_directory = prm.directory + "/" + partial + "/";
    for (const auto &entry :
         std::filesystem::directory_iterator(partial_directory))
      if (entry.path().filename() != name)
        std::filesystem::rename(entry.path(),
                                prm.directory + "/" +
                                  entry.path().filename().string());
    std::filesystem::rename(partial_directory + name,
                            prm.directory + "/" + name);
  }


  template <int dim>
  void
  Output<dim>::save_state(RunState &state) const
  {
    state.values["output_counter"] = counter;
    state.particle_files           = particle_files;
    state.grid_files               = grid_files;
  }


  template class Output<1>;
  template class Output<2>;
  template class Output<3>;
} // namespace mpm
