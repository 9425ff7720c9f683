#include <deal.II/base/conditional_ostream.h>

#include <mpm/checkpoint.h>
#include <mpm/parameters.h>
#include <mpm/simulation.h>
#include <mpm/stages/staged_run.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>

namespace mpm
{
  namespace
  {
    /// Run one Simulation. It (and its TimerOutput, which communicates in
    /// its destructor) is destroyed normally before a failure is passed
    /// on.
    template <int dim>
    RunEnding
    run_one(ParameterHandler    &prm,
            MPI_Comm             comm,
            const std::string   &restart,
            const StagePosition &stage)
    {
      std::exception_ptr failure;
      RunEnding          ending;
      {
        Simulation<dim> simulation(prm, comm, restart, stage);
        try
          {
            ending = simulation.run();
          }
        catch (...)
          {
            failure = std::current_exception();
          }
      }
      if (failure)
        std::rethrow_exception(failure);
      return ending;
    }


    /// The stage a checkpoint was written in (0 for a run without stages).
    unsigned int
    stage_of_checkpoint(const std::string &restart)
    {
      const RunState state =
        RunState::read(Checkpoint::locate(restart) + "/state.txt");
      return state.values.count("stage") > 0
               ? static_cast<unsigned int>(state.get("stage"))
               : 0;
    }


    std::string
    exact(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(17) << x;
      return s.str();
    }


    /**
     * Divide the strength of every frictional body in @p prm by @p factor:
     * c / F and tan(phi) / F (Griffiths and Lane 1999), the dilation angle
     * as phi so that it stays below it, and the residual values of
     * softening alike ('peak' follows the reduced peak). Only the section
     * of the material a body uses. Returns the paths changed.
     */
    std::vector<std::string>
    reduce_strength(ParameterHandler &prm, const double factor)
    {
      static const std::regex strength(
        "(Bodies/Body [0-9]+)/([^/]+)/(residual )?"
        "(cohesion|friction angle|dilation angle)");
      const auto               entries = Parse::entries(prm);
      std::vector<std::string> changed;
      for (const auto &[path, value] : entries)
        {
          std::smatch m;
          if (!std::regex_match(path, m, strength) || value == "peak" ||
              entries.at(m[1].str() + "/material") != m[2].str())
            continue;
          const double v = Parse::number(value);
          const double reduced =
            m[4] == "cohesion"
              ? v / factor
              : std::atan(std::tan(v * M_PI / 180) / factor) * 180 / M_PI;
          Parse::set_entry(prm, path, exact(reduced));
          changed.push_back(path);
        }
      return changed;
    }


    /**
     * A trial's output directory: statistics.csv of the run so far (the
     * trial continues it) and links to its frames, so that the trial's
     * particles.pvd shows the whole history.
     */
    void
    prepare_trial_directory(const std::string &run_directory,
                            const std::string &trial_directory,
                            MPI_Comm           comm)
    {
      namespace fs = std::filesystem;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          fs::create_directories(trial_directory);
          fs::copy_file(run_directory + "/statistics.csv",
                        trial_directory + "/statistics.csv",
                        fs::copy_options::overwrite_existing);
          for (const auto &entry : fs::directory_iterator(run_directory))
            {
              const std::string name = entry.path().filename().string();
              const fs::path    link = fs::path(trial_directory) / name;
              if (entry.is_regular_file() &&
                  (name.rfind("particles_", 0) == 0 ||
                   name.rfind("grid_", 0) == 0) &&
                  !fs::exists(fs::symlink_status(link)))
                fs::create_symlink(fs::path("../..") / name, link);
            }
        }
      MPI_Barrier(comm);
    }


    /// One trial of the strength reduction.
    struct Trial
    {
      double      factor         = 1;
      bool        holds          = false;
      double      end_time       = 0;
      double      out_of_balance = 0;
      std::string diagnosis;
    };


    /**
     * The strength reduction stage @p k: trials from @p from (the end of
     * stage k - 1) with the strength divided by F, bisected between 1 (the
     * stage before is in equilibrium) and the largest factor; the factor of
     * safety is the middle of the last bracket. A trial that stops (a
     * failing slope leaving the grid) fails, with its diagnosis listed.
     */
    template <int dim>
    void
    search_factor_of_safety(
      const std::function<void(ParameterHandler &)> &read_scene,
      const std::vector<StageParameters>            &stages,
      const unsigned int                             k,
      const std::string                             &from,
      const FieldRequests                           &fields,
      MPI_Comm                                       comm)
    {
      ConditionalOStream     pcout(std::cout,
                               Utilities::MPI::this_mpi_process(comm) == 0);
      const StageParameters &s = stages[k];
      std::string            run_directory;
      std::vector<Trial>     trials;
      const auto             holds = [&](const double factor) {
        ParameterHandler prm;
        read_scene(prm);
        for (unsigned int j = 0; j <= k; ++j)
          apply_changes(prm, stages[j]);
        StagePosition position{&stages, k, true, reduce_strength(prm, factor)};
        position.fields_of_all_stages = fields;
        prm.enter_subsection("Output");
        run_directory = prm.get("directory");
        prm.leave_subsection();
        const std::string directory =
          run_directory + "/strength_reduction/F_" + exact(factor);
        Parse::set_entry(prm, "Output/directory", directory);
        Parse::set_entry(prm, "Checkpoint/interval", "0");
        Parse::set_entry(prm, "Checkpoint/wall interval", "0");
        prepare_trial_directory(run_directory, directory, comm);
        Trial trial;
        trial.factor = factor;
        try
          {
            const RunEnding ending = run_one<dim>(prm, comm, from, position);
            trial.holds            = ending.equilibrium;
            trial.end_time       = ending.time;
            trial.out_of_balance = ending.out_of_balance;
          }
        catch (const RunError &e)
          {
            trial.diagnosis = e.what();
          }
        pcout << "  strength reduction: F = " << factor
              << (trial.holds ? " holds" : " fails")
              << (trial.diagnosis.empty() ? "" : " (" + trial.diagnosis + ")")
              << std::endl;
        trials.push_back(trial);
        return trial.holds;
      };
      double lower = 1, upper = s.largest_factor;
      if (holds(upper))
        lower = upper;
      else
        while (upper - lower > s.factor_tolerance)
          {
            const double middle             = 0.5 * (lower + upper);
            (holds(middle) ? lower : upper) = middle;
          }
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::ofstream out(run_directory + "/factor_of_safety.csv");
          out << "factor,holds,end_time,out_of_balance,diagnosis\n";
          for (const auto &t : trials)
            {
              std::string diagnosis = t.diagnosis;
              for (char &c : diagnosis)
                if (c == ',' || c == '\n')
                  c = ';';
              out << exact(t.factor) << ',' << t.holds << ','
                  << exact(t.end_time) << ',' << t.out_of_balance << ','
                  << diagnosis << '\n';
            }
        }
      if (lower == upper)
        pcout << "factor of safety: above " << upper
              << " (the largest factor tried holds; raise '" << s.path
              << "/largest factor')" << std::endl;
      else
        pcout << "factor of safety: " << 0.5 * (lower + upper) << " (holds at "
              << lower << ", fails at " << upper << ", " << trials.size()
              << " trials)" << std::endl;
    }
  } // namespace


  template <int dim>
  void
  run_scene(ParameterHandler                              &prm,
            MPI_Comm                                       comm,
            const std::string                             &restart,
            const std::function<void(ParameterHandler &)> &read_scene)
  {
    const std::vector<StageParameters> stages = parse_stages(prm);
    if (stages.empty())
      {
        run_one<dim>(prm, comm, restart, {});
        return;
      }
    // Every stage's scene, read (and its values checked) now, and the
    // point fields they need together.
    FieldRequests fields;
    {
      ParameterHandler scratch;
      read_scene(scratch);
      for (unsigned int k = 0; k < stages.size(); ++k)
        {
          apply_changes(scratch, stages[k]);
          try
            {
              const Simulation<dim> check(scratch,
                                          comm,
                                          "",
                                          {&stages, k, false});
              fields |= check.point_fields();
            }
          catch (const InputError &e)
            {
              throw InputError(std::string(e.what()) + " (in the scene of '" +
                               stages[k].path +
                               "', with its changes and those before)");
            }
        }
    }
    const unsigned int first =
      restart.empty() ? 0 : stage_of_checkpoint(restart);
    if (first >= stages.size())
      throw InputError("--restart",
                       restart,
                       "was written in stage " + std::to_string(first) +
                         ", but the scene has " +
                         std::to_string(stages.size()) + " stages");
    for (unsigned int k = 0; k <= first; ++k)
      apply_changes(prm, stages[k]);
    std::string from           = restart;
    bool        in_equilibrium = false;
    for (unsigned int k = first; k < stages.size(); ++k)
      {
        if (k > first)
          apply_changes(prm, stages[k]);
        if (stages[k].strength_reduction)
          {
            if (!in_equilibrium)
              throw RunError(stages[k].path +
                             " searches the factor of safety from the end "
                             "of the stage before, which did not reach "
                             "equilibrium: the strength of the scene itself "
                             "(F = 1) does not hold");
            search_factor_of_safety<dim>(
              read_scene, stages, k, from, fields, comm);
            return;
          }
        StagePosition position{&stages, k, k > first};
        position.fields_of_all_stages = fields;
        const RunEnding ending        = run_one<dim>(prm, comm, from, position);
        if (!ending.stage_ended)
          return; // at the end time, within the stage
        from           = ending.checkpoint;
        in_equilibrium = ending.equilibrium;
      }
  }


  template void
  run_scene<1>(ParameterHandler &,
               MPI_Comm,
               const std::string &,
               const std::function<void(ParameterHandler &)> &);
  template void
  run_scene<2>(ParameterHandler &,
               MPI_Comm,
               const std::string &,
               const std::function<void(ParameterHandler &)> &);
  template void
  run_scene<3>(ParameterHandler &,
               MPI_Comm,
               const std::string &,
               const std::function<void(ParameterHandler &)> &);
} // namespace mpm
