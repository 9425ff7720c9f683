#include <deal.II/distributed/tria.h>

#include <mpm/background_grid.h>
#include <mpm/checkpoint.h>
#include <mpm/material_points.h>
#include <mpm/parameters.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace mpm
{
  void
  CheckpointParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpoint");
    prm.declare_entry(
      "interval",
      "0",
      Patterns::Anything(),
      "Simulated time between checkpoints, >= 0 (0: none by time). A "
      "checkpoint is written at the first output time at or after each "
      "multiple (the force meters are reset there), and holds the whole "
      "state: 'dealii-mpm scene.prm --restart DIR' continues the run, bit "
      "for bit on the same number of ranks.");
    prm.declare_entry("wall interval",
                      "0",
                      Patterns::Anything(),
                      "Wall-clock seconds between checkpoints, >= 0 (0: "
                      "none by wall time); written at the next output time.");
    prm.declare_entry("directory",
                      "",
                      Patterns::Anything(),
                      "Where the checkpoint is kept (the latest only). "
                      "Empty: 'checkpoint' inside 'Output/directory'.");
    prm.leave_subsection();
  }


  void
  CheckpointParameters::parse_parameters(ParameterHandler  &prm,
                                         const std::string &output_directory)
  {
    prm.enter_subsection("Checkpoint");
    interval = Parse::bounded_double(prm, "Checkpoint", "interval", 0, 1e300);
    wall_interval =
      Parse::bounded_double(prm, "Checkpoint", "wall interval", 0, 1e300);
    directory = prm.get("directory");
    if (directory.empty())
      directory = output_directory + "/checkpoint";
    prm.leave_subsection();
  }


  double
  RunState::get(const std::string &key) const
  {
    const auto it = values.find(key);
    if (it == values.end())
      throw InputError("--restart",
                       key,
                       "is missing from the checkpoint's state.txt");
    return it->second;
  }


  double
  RunState::share_of_rank(const std::string &key, MPI_Comm comm) const
  {
    return Utilities::MPI::this_mpi_process(comm) == 0 ? get(key) : 0.;
  }


  void
  RunState::write(const std::string &file) const
  {
    std::ofstream out(file);
    out << std::hexfloat;
    for (const auto &[key, value] : values)
      out << "value " << key << ' ' << value << '\n';
    for (const auto &[list, records] :
         {std::make_pair("particles", &particle_files),
          std::make_pair("grid", &grid_files)})
      for (const auto &[time, name] : *records)
        out << "frame " << list << ' ' << time << ' ' << name << '\n';
    for (const auto &[path, value] : scene)
      out << "entry " << path << " = " << value << '\n';
    if (!out)
      throw RunError("cannot write the checkpoint file " + file);
  }


  RunState
  RunState::read(const std::string &file)
  {
    std::ifstream in(file);
    RunState      s;
    std::string   line;
    while (std::getline(in, line))
      {
        // "entry <path> = <value>": path and value may hold blanks.
        if (line.rfind("entry ", 0) == 0)
          {
            const auto equals = line.find(" = ");
            if (equals != std::string::npos)
              s.scene[line.substr(6, equals - 6)] = line.substr(equals + 3);
            continue;
          }
        std::istringstream words(line);
        std::string        kind, key, number;
        words >> kind >> key >> number;
        // hexfloat reads through strtod (istream's >> does not parse it).
        const double value = std::strtod(number.c_str(), nullptr);
        if (kind == "value")
          s.values[key] = value;
        else if (kind == "frame")
          {
            std::string name;
            words >> name;
            (key == "particles" ? s.particle_files : s.grid_files)
              .emplace_back(value, name);
          }
      }
    return s;
  }


  namespace Checkpoint
  {
    std::string
    grid_file(const std::string &checkpoint)
    {
      return checkpoint + "/grid";
    }


    template <int dim>
    void
    save(const std::string   &directory,
         BackgroundGrid<dim> &grid,
         MaterialPoints<dim> &points,
         const RunState      &state,
         MPI_Comm             comm)
    {
      namespace fs        = std::filesystem;
      const bool  root    = Utilities::MPI::this_mpi_process(comm) == 0;
      const auto  partial = directory + ".partial";
      const auto  old     = directory + ".old";
      std::string failure;
      if (root)
        {
          std::error_code error;
          fs::remove_all(partial, error);
          fs::create_directories(partial, error);
          if (error)
            failure = "cannot create the checkpoint directory " + partial;
        }
      raise_if_any_failed(failure, comm);
      if constexpr (dim == 1)
        {
          Assert(false, ExcNotImplemented());
        }
      else
        {
          points.handler().update_cached_numbers();
          points.handler().prepare_for_serialization();
          dynamic_cast<const parallel::distributed::Triangulation<dim> &>(
            grid.triangulation())
            .save(grid_file(partial));
        }
      if (root)
        {
          state.write(partial + "/state.txt");
          // The swap: the old checkpoint stays whole until the new one is.
          std::error_code error;
          fs::remove_all(old, error);
          if (fs::exists(directory))
            fs::rename(directory, old);
          fs::rename(partial, directory);
          fs::remove_all(old, error);
        }
      MPI_Barrier(comm);
    }


    std::string
    locate(const std::string &directory)
    {
      namespace fs = std::filesystem;
      for (const auto &candidate : {directory, directory + ".old"})
        if (fs::exists(candidate + "/state.txt"))
          return candidate;
      throw InputError("--restart",
                       directory,
                       "holds no complete checkpoint (no state.txt there or "
                       "in '" +
                         directory + ".old')");
    }


    template void
    save<1>(const std::string &,
            BackgroundGrid<1> &,
            MaterialPoints<1> &,
            const RunState &,
            MPI_Comm);
    template void
    save<2>(const std::string &,
            BackgroundGrid<2> &,
            MaterialPoints<2> &,
            const RunState &,
            MPI_Comm);
    template void
    save<3>(const std::string &,
            BackgroundGrid<3> &,
            MaterialPoints<3> &,
            const RunState &,
            MPI_Comm);
  } // namespace Checkpoint
} // namespace mpm
