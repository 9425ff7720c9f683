#include <deal.II/base/timer.h>

#include <deal.II/base/utilities.h>
#include <optional>

#include <mpm/parameters.h>
#include <mpm/simulation.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

namespace mpm
{
  namespace
  {
    /// This process's resident file-backed pages in bytes (Linux: RssFile
    /// of /proc/self/status; 0 where it is not known).
    double
    resident_file_bytes()
    {
      std::ifstream status("/proc/self/status");
      std::string   key;
      while (status >> key)
        if (key == "RssFile:")
          {
            double kilobytes = 0;
            status >> kilobytes;
            return kilobytes * 1024.;
          }
      return 0;
    }
  } // namespace


  void
  declare_scene_parameters(ParameterHandler  &prm,
                           const unsigned int n_bodies,
                           const unsigned int n_walls,
                           const unsigned int n_stages)
  {
    prm.enter_subsection("Simulation");
    prm.declare_entry("dimension",
                      "2",
                      Patterns::Integer(1, 3),
                      "Space dimension: 1 (serial only), 2 or 3.");
    prm.leave_subsection();
    IntegratorParameters<2>::declare_parameters(prm);
    GridParameters<2>::declare_parameters(prm);
    prm.enter_subsection("Bodies");
    prm.declare_entry("number of bodies",
                      "1",
                      Patterns::Integer(1, 1000),
                      "Number of bodies; body N is described in subsection "
                      "'Body N', N = 0, 1, ...");
    prm.declare_entry("may overlap",
                      "false",
                      Patterns::Bool(),
                      "true or false: may two bodies fill the same space? "
                      "Usually a mistake in the scene (the overlap holds "
                      "twice the mass), so it is an error unless true.");
    prm.leave_subsection();
    for (unsigned int b = 0; b < n_bodies; ++b)
      BodyParameters<2>::declare_parameters(prm, b);
    VelocityRegionParameters<2>::declare_parameters(prm);
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("number of rigid walls",
                      "0",
                      Patterns::Integer(0, 100),
                      "Number of rigid walls; wall N is described in "
                      "subsection 'Rigid wall N', N = 0, 1, ...: a plane at "
                      "any angle to the grid acting on the material points "
                      "by a penalty with Coulomb friction, its mean force "
                      "from the material in statistics.csv (wall<N>_force_x, "
                      "...).");
    prm.leave_subsection();
    for (unsigned int w = 0; w < n_walls; ++w)
      RigidWallParameters<2>::declare_parameters(prm, w);
    VirtualFluidParameters<2>::declare_parameters(prm);
    ContactParameters<2>::declare_parameters(prm);
    OutputParameters::declare_parameters(prm);
    CheckpointParameters::declare_parameters(prm);
    VerificationParameters::declare_parameters(prm);
    StageParameters::declare_parameters(prm, n_stages);
  }



  template <int dim>
  Simulation<dim>::Simulation(ParameterHandler    &prm,
                              MPI_Comm             comm,
                              const std::string   &restart,
                              const StagePosition &stage)
    : comm(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , restart(restart)
    , scene_entries(Parse::entries(prm))
    , stage(stage)
  {
    grid_parameters.parse_parameters(prm);
    integrator_parameters.parse_parameters(prm);
    prm.enter_subsection("Bodies");
    const unsigned int n_bodies = prm.get_integer("number of bodies");
    bodies_may_overlap          = prm.get_bool("may overlap");
    prm.leave_subsection();
    body_parameters.resize(n_bodies);
    for (unsigned int b = 0; b < n_bodies; ++b)
      body_parameters[b].parse_parameters(prm, b, grid_parameters);
    velocity_region_parameters.parse_parameters(prm);
    prm.enter_subsection("Boundary conditions");
    const unsigned int n_walls = prm.get_integer("number of rigid walls");
    prm.leave_subsection();
    rigid_wall_parameters.resize(n_walls);
    for (unsigned int w = 0; w < n_walls; ++w)
      rigid_wall_parameters[w].parse_parameters(prm, w);
    virtual_fluid_parameters.parse_parameters(prm, n_bodies);
    contact_parameters.parse_parameters(prm, n_bodies);
    output_parameters.parse_parameters(prm);
    checkpoint_parameters.parse_parameters(prm, output_parameters.directory);
    verification_parameters.parse_parameters(prm);
    if (dim == 1 && output_parameters.hdf5)
      throw InputError("Output/particle format",
                       "HDF5",
                       "needs dimension 2 or 3 (deal.II writes HDF5 for 2D and "
                       "3D data only); use VTU");
    if (stage.staged() && stage.stages->size() > 1 && dim == 1)
      throw InputError("Stages/number of stages",
                       std::to_string(stage.stages->size()),
                       "needs dimension 2 or 3 (a stage starts from the "
                       "checkpoint of the one before, and deal.II saves "
                       "distributed triangulations only)");
    if (stage.staged() && stage.current().end == StageEnd::equilibrium &&
        integrator_parameters.gravity.norm() == 0)
      throw InputError(stage.current().path + "/end",
                       "equilibrium",
                       "needs gravity: the out-of-balance force is measured "
                       "against the bodies' weight");
    if (dim == 1 && (checkpoint_parameters.enabled() || !restart.empty()))
      throw InputError("Checkpoint/interval",
                       "(or --restart)",
                       "checkpoints need dimension 2 or 3 (deal.II saves "
                       "distributed triangulations only, and 1D is serial)");
  }


  template <int dim>
  RunEnding
  Simulation<dim>::run()
  {
    Timer wall;
    // Made here rather than in the constructor: a TimerOutput that is
    // destroyed while an input error unwinds the stack prints a warning.
    timer = std::make_unique<TimerOutput>(comm,
                                          pcout,
                                          TimerOutput::never,
                                          TimerOutput::wall_times);
    // A restart: the checkpoint (the one '--restart' names, or what an
    // interrupted swap left) and its state.
    const std::string checkpoint =
      restart.empty() ? "" : Checkpoint::locate(restart);
    const std::unique_ptr<RunState> resume =
      checkpoint.empty()
        ? nullptr
        : std::make_unique<RunState>(RunState::read(checkpoint + "/state.txt"));
    if (resume != nullptr)
      check_restart(*resume, checkpoint);
    // The memory of the program itself (its libraries, MPI), before the
    // scene's data: a constant per rank, which timing.csv lists apart.
    {
      Utilities::System::MemoryStats memory;
      Utilities::System::get_memory_stats(memory);
      baseline_bytes = Utilities::MPI::sum(double(memory.VmRSS) * 1024., comm);
      library_bytes  = resident_file_bytes();
    }
    set_up_grid_and_points(resume.get(), checkpoint);
    set_up_integrator(resume.get());
    set_up_output(resume.get());
    setup_peak_bytes = peak_memory_bytes();
    print_scene_summary();
    refuse_endless_run();
    if (resume == nullptr)
      write_output(wall.wall_time());
    else
      {
        // The checkpoint was taken right after an output: the force meters
        // were reset there.
        last_output_time     = resume->get("last_output_time");
        next_checkpoint_time = resume->get("checkpoint_next_time");
        const double t       = integrator->time();
        for (auto *reporter : force_reporters)
          reporter->mean_force_since_last_call(t, comm);
        pcout << "  restarted from '" << checkpoint << "' at t = " << t
              << ", step " << integrator->step_number() << std::endl;
      }
    begin_stage(resume.get());
    first_step           = integrator->step_number();
    last_checkpoint_wall = wall.wall_time();
    return run_time_loop(wall);
  }


  /**
   * A checkpoint is only read by the scene that wrote it (checked before
   * deal.II loads a grid that does not match, which it cannot report).
   * With the physics the same (check_restart), only the output fields
   * change what the points store.
   */
  template <int dim>
  void
  Simulation<dim>::throw_scene_differs(const RunState &resume) const
  {
    const auto fields = resume.scene.find("Output/fields");
    if (fields != resume.scene.end() &&
        fields->second != scene_entries.at("Output/fields"))
      throw InputError("Output/fields",
                       scene_entries.at("Output/fields"),
                       "needs other point data than the checkpoint "
                       "stores; restart with its 'Output/fields' = '" +
                         fields->second +
                         "' (the other output settings may change)");
    throw InputError("--restart",
                     restart,
                     "was written by a scene with another grid or other "
                     "point fields; restart with the scene that wrote it "
                     "(end time, output and checkpoint settings may "
                     "change)");
  }


  template <int dim>
  FieldRequests
  Simulation<dim>::point_fields() const
  {
    FieldRequests fields =
      point_fields_needed(integrator_parameters,
                          body_parameters,
                          rigid_wall_parameters,
                          output_parameters.writes("displacement") ||
                            Verification<dim>::needs_initial_position(
                              verification_parameters),
                          output_parameters.writes("strain") ||
                            output_parameters.writes("deviatoric strain"));
    if (stage.staged())
      for (const auto &s : *stage.stages)
        fields.displacement_origin |= s.reset_displacements;
    for (const auto &body : body_parameters)
      body.material->request_fields(fields);
    return fields;
  }


  template <int dim>
  void
  Simulation<dim>::set_up_grid_and_points(const RunState    *resume,
                                          const std::string &checkpoint)
  {
    if (resume != nullptr)
      {
        double n_cells = 1;
        for (const auto n : grid_parameters.n_cells)
          n_cells *= n;
        if (resume->get("grid_cells") != n_cells)
          throw_scene_differs(*resume);
      }
    // Balance the ranks by the material points each cell will hold (or
    // take the checkpoint's partition and points).
    std::optional<TimerOutput::Scope> setup_scope;
    setup_scope.emplace(*timer, "setup: grid");
    grid = std::make_unique<BackgroundGrid<dim>>(
      grid_parameters,
      comm,
      [&](const Point<dim> &cell_origin) {
        unsigned int n = 0;
        for (const auto &body : body_parameters)
          n += body.count_seeds(cell_origin);
        return n;
      },
      resume == nullptr ? "" : Checkpoint::grid_file(checkpoint));
    FieldRequests fields = point_fields();
    if (stage.staged())
      fields |= stage.fields_of_all_stages;
    setup_scope.reset();
    setup_scope.emplace(*timer, "setup: points");
    points = std::make_unique<MaterialPoints<dim>>(*grid,
                                                   body_parameters,
                                                   fields,
                                                   comm);
    if (resume == nullptr)
      {
        points->generate(bodies_may_overlap,
                         {{integrator_parameters.J_min,
                           integrator_parameters.J_max}});
        return;
      }
    // The scene must store the same fields (deal.II would read the
    // points' data misaligned, or fail).
    if (resume->get("point_properties") != points->layout().n_properties)
      throw_scene_differs(*resume);
    points->restore(resume->get("minimum_point_mass"));
    // A run that never rebalanced had the partition of the initial
    // work estimate, which comes back bit for bit; after rebalancing,
    // the partition of the points as they are is the nearest (the
    // history then agrees to round-off).
    n_rebalances =
      resume->values.count("rebalances") > 0 ? resume->get("rebalances") : 0;
    if (n_rebalances > 0)
      grid->repartition(points->handler());
    else
      grid->restore_partition(points->handler());
  }


  template <int dim>
  void
  Simulation<dim>::set_up_integrator(const RunState *resume)
  {
    velocity_region =
      std::make_unique<VelocityRegion<dim>>(velocity_region_parameters, *grid);
    const std::vector<unsigned int> slip_slot =
      wall_slip_slots(rigid_wall_parameters);
    for (unsigned int w = 0; w < rigid_wall_parameters.size(); ++w)
      rigid_walls.push_back(std::make_unique<RigidWall<dim>>(
        rigid_wall_parameters[w], grid->min_cell_size(), slip_slot[w]));
    std::vector<RigidWall<dim> *> walls;
    for (const auto &wall : rigid_walls)
      walls.push_back(wall.get());
    virtual_fluid =
      std::make_unique<VirtualFluid<dim>>(virtual_fluid_parameters,
                                          integrator_parameters.gravity.norm(),
                                          grid->min_cell_size());
    contact      = std::make_unique<MultiFieldContact<dim>>(contact_parameters,
                                                       body_parameters);
    integrator   = std::make_unique<TimeIntegrator<dim>>(integrator_parameters,
                                                       *grid,
                                                       *points,
                                                       *velocity_region,
                                                       *timer,
                                                       comm,
                                                       walls,
                                                       virtual_fluid.get(),
                                                       contact.get());
    verification = std::make_unique<Verification<dim>>(
      verification_parameters, *points, integrator_parameters.gravity, comm);
    energy_guard = std::make_unique<EnergyGuard<dim>>(
      integrator_parameters.energy_growth_bound,
      integrator_parameters.energy_residual,
      *points,
      comm);
    if (resume != nullptr)
      {
        integrator->restore_state(*resume);
        verification->restore_state(*resume);
        energy_guard->restore_state(*resume);
      }
    else
      next_checkpoint_time = checkpoint_parameters.interval;
    if (stage.any_equilibrium())
      integrator->measure_out_of_balance();
    force_reporters = {velocity_region.get()};
    for (const auto &wall : rigid_walls)
      force_reporters.push_back(wall.get());
    force_reporters.push_back(virtual_fluid.get());
    force_reporters.push_back(contact.get());
  }


  template <int dim>
  void
  Simulation<dim>::set_up_output(const RunState *resume)
  {
    std::vector<std::string> columns = verification->columns();
    for (const auto *reporter : force_reporters)
      for (const auto &c : reporter->columns())
        columns.push_back(c);
    if (integrator_parameters.macro_time_step > 0)
      for (const std::string c : {"macro_steps", "macro_mismatch"})
        columns.push_back(c);
    if (integrator_parameters.energy_residual)
      for (const std::string c : {"external_work",
                                  "dissipation",
                                  "face_friction_work",
                                  "face_work",
                                  "damping_work",
                                  "energy_residual"})
        columns.push_back(c);
    if (integrator_parameters.energy_residual && contact->n_fields() > 1)
      columns.push_back("contact_work");
    if (integrator_parameters.energy_residual && has_affine_field())
      columns.push_back("affine_kinetic_energy");
    if (stage.staged())
      columns.push_back("stage");
    if (stage.any_equilibrium())
      columns.push_back("out_of_balance");
    if (output_parameters.body_extents)
      {
        extents =
          std::make_unique<BodyExtents<dim>>(*grid,
                                             integrator_parameters.gravity,
                                             output_parameters.front_percentile,
                                             output_parameters.front_thickness,
                                             body_parameters.size(),
                                             comm);
        for (const auto &c : extents->columns())
          columns.push_back(c);
      }
    statistics_columns = columns;
    output             = std::make_unique<Output<dim>>(output_parameters,
                                           *grid,
                                           *points,
                                           *integrator,
                                           integrator_parameters.gravity,
                                           columns,
                                           comm,
                                           resume);
  }


  /**
   * The time loop: steps of at most the time to the next output or the
   * end, each after balancing the ranks, an output (and a checkpoint if
   * due) at each output time, the progress line. A run that stops names
   * where its last good output is.
   */
  template <int dim>
  RunEnding
  Simulation<dim>::run_time_loop(const Timer &wall)
  {
    const double end_time   = run_end_time();
    double       last_print = 0;
    const double start      = wall.wall_time();
    // Also between the substeps of a macro step, which may take long.
    const auto report_progress = [&]() {
      if (wall.wall_time() - last_print >= output_parameters.progress_interval)
        {
          last_print = wall.wall_time();
          print_progress(last_print - start);
        }
    };
    integrator->after_substep = report_progress;
    Timer stepping; // time in steps only: the cost per particle-step
    stepping.stop();
    // A restart at the end of a stage has no step left in it.
    bool stage_end = stage.staged() && stage_reached_end();
    try
      {
        while (!stage_end && integrator->time() < end_time * (1 - 1e-12))
          {
            double max_dt = end_time - integrator->time();
            if (output_parameters.interval > 0)
              max_dt =
                std::min(max_dt,
                         output->next_output_time() - integrator->time());
            stepping.start();
            balance_load();
            integrator->step(max_dt);
            stepping.stop();
            const double now = integrator->time();
            stage_end        = stage.staged() && stage_is_over();
            if (output_parameters.interval == 0 ||
                now >= output->next_output_time() * (1 - 1e-12) ||
                now >= end_time * (1 - 1e-12) || stage_end)
              {
                write_output(wall.wall_time());
                checkpoint_if_due(wall.wall_time());
              }
            report_progress();
            if (stage_end)
              break;
          }
        if (stage_end)
          {
            print_performance(wall.wall_time() - start, stepping.wall_time());
            return end_stage();
          }
      }
    catch (const RunError &e)
      {
        std::ostringstream message;
        message << e.what() << (std::string(e.what()).back() == '.' ? "" : ".")
                << " Output up to t = " << last_output_time << " is in '"
                << output_parameters.directory << "/'.";
        throw RunError(message.str());
      }
    print_performance(wall.wall_time() - start, stepping.wall_time());
    verification->check(pcout);
    return {};
  }


  template <int dim>
  double
  Simulation<dim>::run_end_time() const
  {
    if (!stage.staged())
      return integrator_parameters.end_time;
    return std::min(integrator_parameters.end_time,
                    stage_start_time + stage.current().duration);
  }


  template <int dim>
  void
  Simulation<dim>::begin_stage(const RunState *resume)
  {
    if (!stage.staged())
      return;
    weight =
      Statistics<dim>::compute(*points, integrator_parameters.gravity, comm)
        .mass *
      integrator_parameters.gravity.norm();
    const StageParameters &s = stage.current();
    if (resume != nullptr && !stage.entering &&
        resume->values.count("stage_start_time") > 0)
      {
        stage_start_time = resume->get("stage_start_time");
        steps_in_balance = resume->get("steps_in_balance");
        out_of_balance   = resume->get("out_of_balance");
      }
    else
      {
        stage_start_time = integrator->time();
        if (stage.entering && s.reset_displacements)
          points->reset_displacement_origin();
      }
    pcout << "  stage " << stage.index << " of " << stage.stages->size()
          << " ('" << s.path << "'): from t = " << stage_start_time
          << ", at most " << s.duration
          << (s.end == StageEnd::equilibrium
                ? " s, or to equilibrium (out-of-balance force below " +
                    std::to_string(s.tolerance) + " of the weight)"
                : " s")
          << ", " << s.changes.size() << " change"
          << (s.changes.size() == 1 ? "" : "s") << std::endl;
  }


  template <int dim>
  bool
  Simulation<dim>::stage_is_over()
  {
    const StageParameters &s = stage.current();
    // Measured in every stage once one ends at equilibrium: the column
    // then shows how far a released slope is from it.
    if (stage.any_equilibrium())
      out_of_balance = integrator->out_of_balance_force() / weight;
    if (s.end == StageEnd::equilibrium)
      steps_in_balance =
        out_of_balance < s.tolerance ? steps_in_balance + 1 : 0;
    return stage_reached_end();
  }


  template <int dim>
  bool
  Simulation<dim>::stage_reached_end() const
  {
    return steps_in_balance >= balanced_steps ||
           integrator->time() >=
             (stage_start_time + stage.current().duration) * (1 - 1e-12);
  }


  template <int dim>
  RunEnding
  Simulation<dim>::end_stage()
  {
    const StageParameters &s = stage.current();
    RunEnding              ending;
    ending.stage_ended    = true;
    ending.equilibrium    = steps_in_balance >= balanced_steps;
    ending.time           = integrator->time();
    ending.out_of_balance = out_of_balance;
    // A trial of the strength reduction that fails is its answer.
    if (s.end == StageEnd::equilibrium && !ending.equilibrium &&
        s.stop_if_not_reached && !s.strength_reduction)
      {
        std::ostringstream message;
        message << "stage " << stage.index << " ('" << s.path
                << "') did not reach equilibrium within its duration of "
                << s.duration << " s: at t = " << integrator->time()
                << " the out-of-balance force is " << out_of_balance
                << " of the weight (tolerance " << s.tolerance
                << "). The bodies may be failing, or still settling: "
                   "lengthen its 'duration', damp the motion ('Simulation/"
                   "local damping'), or set its 'if not in equilibrium = "
                   "continue'";
        throw RunError(message.str());
      }
    pcout << "  stage " << stage.index << " ended at t = " << integrator->time()
          << (s.end != StageEnd::equilibrium ? " (its duration)"
              : ending.equilibrium           ? " in equilibrium"
                                             : " without equilibrium")
          << (s.end == StageEnd::equilibrium
                ? ", out-of-balance force " + std::to_string(out_of_balance) +
                    " of the weight"
                : "")
          << std::endl;
    if (!stage.is_last())
      {
        ending.checkpoint =
          output_parameters.directory + "/stage_" + std::to_string(stage.index);
        save_checkpoint(ending.checkpoint);
      }
    return ending;
  }


  template <int dim>
  void
  Simulation<dim>::refuse_endless_run() const
  {
    constexpr double max_steps = 1e9;
    // An interval shorter than the step is fine for a few frames (the
    // verification problems land steps on output times); beyond this many
    // it is a typo that fills the disk.
    constexpr double max_extra_frames = 1e5;
    const double     remaining =
      integrator_parameters.end_time - integrator->time();
    if (!(remaining > 0))
      return;
    const auto [dt, limit] = integrator->initial_step();
    const double interval  = output_parameters.interval;
    // As a scene would write it (15 digits).
    const auto as_written = [](const double x) {
      char text[32];
      std::snprintf(text, sizeof(text), "%.15g", x);
      return std::string(text);
    };
    if (interval > 0 && interval < dt * (1 - 1e-12) &&
        remaining / interval > max_extra_frames)
      {
        std::ostringstream allowed;
        allowed << "is shorter than the time step, " << dt << " s (set by "
                << limit << "): every step would be cut to it and write a "
                << "frame, " << remaining / interval << " in all (at most "
                << max_extra_frames
                << " are allowed below the step); use at least the time "
                   "step, or 0 for a frame every step";
        throw InputError("Output/interval",
                         as_written(interval),
                         allowed.str());
      }
    const double n_steps = remaining / dt;
    if (!(n_steps <= max_steps))
      {
        std::ostringstream allowed;
        allowed << "would take about " << n_steps << " steps of " << dt
                << " s (set by " << limit << "), more than " << max_steps
                << "; shorten the run or change what sets the step";
        throw InputError("Simulation/end time",
                         as_written(integrator_parameters.end_time),
                         allowed.str());
      }
  }


  template <int dim>
  void
  Simulation<dim>::check_restart(const RunState    &resume,
                                 const std::string &checkpoint) const
  {
    const double t = resume.get("time");
    if (!(integrator_parameters.end_time > t))
      {
        std::ostringstream allowed;
        allowed << "is not after the time of the checkpoint '" << checkpoint
                << "', t = " << t
                << "; a restart continues to a later end time";
        throw InputError("Simulation/end time",
                         scene_entries.at("Simulation/end time"),
                         allowed.str());
      }
    // What a restart may change: when to stop, what to write, where to
    // save (and how unbalanced the ranks may be, as their number may
    // change). Everything else is the physics the checkpoint continues.
    // A stage's start changes what its changes name (and what the stages
    // before it changed, which the checkpoint of the stage before holds
    // already).
    const auto may_change = [this](const std::string &path) {
      for (const std::string prefix : {"Simulation/end time",
                                       "Output/",
                                       "Checkpoint/",
                                       "Grid/load imbalance limit",
                                       "Stages/"})
        if (path.rfind(prefix, 0) == 0)
          return true;
      if (stage.entering)
        {
          for (const auto &change : stage.current().changes)
            if (change.first == path)
              return true;
          for (const auto &other : stage.other_changes)
            if (other == path)
              return true;
        }
      return false;
    };
    // A checkpoint of an older version holds no entries: nothing to
    // compare.
    if (resume.scene.empty())
      return;
    std::vector<std::string> differences;
    const auto value_in = [](const auto &entries, const std::string &path) {
      const auto it = entries.find(path);
      return it == entries.end() ? std::string("(none)")
                                 : "'" + it->second + "'";
    };
    std::set<std::string> paths;
    for (const auto &e : resume.scene)
      paths.insert(e.first);
    for (const auto &e : scene_entries)
      paths.insert(e.first);
    for (const auto &path : paths)
      if (!may_change(path) &&
          value_in(resume.scene, path) != value_in(scene_entries, path))
        differences.push_back("'" + path + "' (" +
                              value_in(resume.scene, path) + " there, " +
                              value_in(scene_entries, path) + " here)");
    if (!differences.empty())
      {
        std::string listed = differences[0];
        for (unsigned int i = 1;
             i < std::min<std::size_t>(differences.size(), 4);
             ++i)
          listed += ", " + differences[i];
        if (differences.size() > 4)
          listed += " and " + std::to_string(differences.size() - 4) + " more";
        throw InputError("--restart",
                         restart,
                         "was written by a scene that differs in " + listed +
                           "; a restart continues the same physics (only "
                           "'Simulation/end time', 'Output/...' and "
                           "'Checkpoint/...' may change)");
      }
  }


  template <int dim>
  void
  Simulation<dim>::checkpoint_if_due(const double wall_seconds)
  {
    const auto  &c   = checkpoint_parameters;
    const double now = integrator->time();
    // The wall clocks of the ranks differ: the root's decides.
    const bool by_wall =
      Utilities::MPI::broadcast(comm,
                                c.wall_interval > 0 &&
                                  wall_seconds - last_checkpoint_wall >=
                                    c.wall_interval,
                                0);
    const bool by_time =
      c.interval > 0 && now >= next_checkpoint_time * (1 - 1e-12);
    if (!by_wall && !by_time)
      return;
    if (c.interval > 0)
      next_checkpoint_time = multiple_after(now, c.interval);
    save_checkpoint(c.directory);
    last_checkpoint_wall = wall_seconds;
  }


  template <int dim>
  void
  Simulation<dim>::save_checkpoint(const std::string &directory)
  {
    TimerOutput::Scope scope(*timer, "checkpoint");
    RunState           state;
    integrator->save_state(state);
    verification->save_state(state);
    energy_guard->save_state(state);
    output->save_state(state);
    state.values["last_output_time"]     = last_output_time;
    state.values["minimum_point_mass"]   = points->min_particle_mass();
    state.values["checkpoint_next_time"] = next_checkpoint_time;
    state.values["point_properties"]     = points->layout().n_properties;
    state.values["grid_cells"]           = grid->n_cells();
    state.values["rebalances"]           = n_rebalances;
    if (stage.staged())
      {
        state.values["stage"]            = stage.index;
        state.values["stage_start_time"] = stage_start_time;
        state.values["steps_in_balance"] = steps_in_balance;
        state.values["out_of_balance"]   = out_of_balance;
      }
    state.scene = scene_entries;
    Checkpoint::save(directory, *grid, *points, state, comm);
  }


  template <int dim>
  void
  Simulation<dim>::write_output(const double wall_seconds)
  {
    TimerOutput::Scope scope(*timer, "output");
    const auto         s =
      Statistics<dim>::compute(*points, integrator_parameters.gravity, comm);
    auto extra = verification->evaluate(s, integrator->time());
    if (integrator->time() == last_output_time)
      return;
    for (auto *reporter : force_reporters)
      for (const double f :
           reporter->mean_force_since_last_call(integrator->time(), comm))
        extra.push_back(f);
    if (integrator_parameters.macro_time_step > 0)
      {
        extra.push_back(integrator->substepping().macro_step_number());
        extra.push_back(integrator->substepping().largest_mismatch());
      }
    // Before anything is written: a run that fails keeps its last good
    // output.
    stop_if_not_finite(s, extra);
    const WorkAccount work = integrator->work_account().totals(comm);
    // Collective: only where the columns have it.
    const double affine =
      integrator_parameters.energy_residual && has_affine_field()
        ? integrator->affine_kinetic_energy()
        : 0.;
    const auto [put_in, residual, dissipation] =
      energy_guard->check(s, work, integrator->time(), affine);
    if (integrator_parameters.energy_residual)
      for (const double value : {work.external,
                                 dissipation,
                                 work.face_friction,
                                 work.face_constraint,
                                 work.damping,
                                 put_in > 0 ? residual / put_in : 0.})
        extra.push_back(value);
    if (integrator_parameters.energy_residual && contact->n_fields() > 1)
      extra.push_back(work.contact);
    if (integrator_parameters.energy_residual && has_affine_field())
      extra.push_back(affine);
    if (stage.staged())
      extra.push_back(stage.index);
    if (stage.any_equilibrium())
      extra.push_back(out_of_balance);
    // A body without points (or without a deposit) has no extents: the
    // writer leaves their fields empty.
    if (extents)
      for (const double x : extents->values(*points))
        extra.push_back(x);
    output->write(s, extra, wall_seconds);
    last_output_time = integrator->time();
  }


  /**
   * statistics.csv holds numbers: a value that is not finite means the
   * run has gone wrong in a way the step's checks on the points did not
   * see (they test velocity, stress and volume; an energy can overflow
   * from a finite state). Stopped collectively, naming the column.
   */
  template <int dim>
  void
  Simulation<dim>::stop_if_not_finite(const Statistics<dim>     &s,
                                      const std::vector<double> &extra) const
  {
    std::vector<std::pair<std::string, double>> values = {
      {"kinetic_energy", s.kinetic_energy},
      {"strain_energy", s.strain_energy},
      {"gravitational_energy", s.gravitational_energy},
      {"mass", s.mass}};
    for (unsigned int d = 0; d < dim; ++d)
      values.emplace_back(std::string("momentum_") + "xyz"[d], s.momentum[d]);
    for (unsigned int d = 0; d < s.angular_momentum.dimension; ++d)
      values.emplace_back("angular_momentum", s.angular_momentum[d]);
    for (unsigned int c = 0; c < extra.size(); ++c)
      values.emplace_back(statistics_columns[c], extra[c]);
    std::string failure;
    for (const auto &[name, value] : values)
      if (!std::isfinite(value))
        {
          std::ostringstream msg;
          msg << "t = " << integrator->time() << ": the statistics column '"
              << name << "' is " << value
              << ": a value overflowed (an input of extreme magnitude, e.g. "
                 "an exact solution for 'Verification', or an unstable run: "
                 "try a smaller CFL number, MUSL, or damping)";
          failure = msg.str();
          break;
        }
    raise_if_any_failed(failure, comm);
  }


  template <int dim>
  void
  Simulation<dim>::print_scene_summary() const
  {
    const auto &l = points->layout();
    pcout << "dealii-mpm: " << dim << "D, " << grid->n_cells() << " cells, "
          << points->handler().n_global_particles() << " material points in "
          << body_parameters.size() << " bod"
          << (body_parameters.size() == 1 ? "y" : "ies") << ", "
          << Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s)\n"
          << "  " << scheme_description() << "\n"
          << "  fields per point (" << l.n_properties << " doubles):";
    for (const auto &[name, n] : l.description)
      pcout << " " << name << "[" << n << "]";
    pcout << std::endl;
    warn_of_volumetric_locking();
    for (const auto &body : body_parameters)
      if (const std::string w = body.sparse_points_warning(); !w.empty())
        pcout << "  warning: " << w << std::endl;
    warn_of_pic_viscosity();
    warn_of_apic_at_rough_faces();
    warn_of_rolling_resistance();
  }


  /**
   * A solid with Poisson's ratio near 0.5 locks on every basis once a cell
   * holds more points than its nodes can give independent volume changes:
   * the settling block at nu = 0.499 is 25 times further from the exact
   * stress than at nu = 0.3 (tests/nearly_incompressible_block.prm). The
   * run is not wrong enough to stop, so it is said at the start, with the
   * remedy. Fluids are nearly incompressible by design and are not meant.
   */
  template <int dim>
  void
  Simulation<dim>::warn_of_volumetric_locking() const
  {
    if (integrator_parameters.f_bar)
      return;
    const auto &bodies = points->bodies();
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const auto  &material = *bodies[b].material;
        const double mu       = material.shear_modulus();
        if (bodies[b].rigid_velocity || !(mu > 0))
          continue;
        const double lambda = material.p_wave_modulus() - 2. * mu;
        const double nu     = lambda / (2. * (lambda + mu));
        // The value as the scene gives it (0.4999999 would print as 0.5).
        if (nu > 0.45)
          pcout << "  warning: body " << b << " has Poisson's ratio > 0.45 ("
                << material.stiffness_parameters()
                << "): nearly incompressible bodies lock (too stiff, "
                   "noisy pressure) on every basis; set 'Simulation/F-bar = "
                   "true'"
                << std::endl;
      }
  }


  /**
   * FLIP's PIC share relaxes every point's velocity towards the grid's at
   * the rate (1 - FLIP fraction) / dt. Across a shear band a cell or two
   * wide that is a viscous stress ~ rho c dv (1 - FLIP fraction) / CFL,
   * which does not fall as the grid is refined and grows as the step
   * shrinks, and in a frictional material it is of the order of the band's
   * strength: a granular column (a = 0.5, 32 cells) runs out 0.41 / 0.54 /
   * 0.79 for FLIP fractions 0.95 / 0.99 / 0.999, and the Bui collapse's toe
   * with 0.999 is 0.505 / 0.455 / 0.420 m at CFL 0.5 / 0.25 / 0.125 at
   * h = 5 mm (0.510 / 0.455 / 0.433 at 2.5 mm). A relaxation time makes
   * the share a rate: the toe is then 0.495 m at CFL 0.5 and 0.125
   * (benchmarks/granular/README.md).
   * Not wrong enough to stop, so said at the start, with the remedy.
   */
  template <int dim>
  void
  Simulation<dim>::warn_of_pic_viscosity() const
  {
    const auto &p = integrator_parameters;
    if (!with_transfer(p.transfer, [](auto c) { return c.blends_pic; }) ||
        p.flip_fraction == 1 || p.pic_relaxation_time > 0)
      return;
    for (unsigned int b = 0; b < body_parameters.size(); ++b)
      {
        const std::string &name = body_parameters[b].material_name;
        if (!body_parameters[b].rigid_velocity &&
            (name == "Mohr-Coulomb" || name == "Drucker-Prager"))
          pcout << "  warning: body " << b << " is frictional (" << name
                << ") and the transfer is FLIP with a PIC share of "
                << 1 - p.flip_fraction
                << " per step: it acts on shear bands like a viscosity that "
                   "does not shrink with the grid and grows as the step "
                   "shrinks, and it shortens granular runouts; set "
                   "'Simulation/PIC relaxation time' (a share per second: "
                   "benchmarks/granular/README.md)"
                << std::endl;
      }
  }


  /**
   * A cohesionless point that parts has no stress, and APIC carries its
   * shear as an affine velocity that is already zero at a fixed or
   * friction face's nodes: the face takes no momentum from it, and a sheet
   * of parted points slides along the face undamped. In the Bui et al.
   * collapse at h = 2.5 mm such a sheet ran to the end of the grid on the
   * fixed floor, and on a Coulomb floor the toe ran out 0.566 m; FLIP 0.999
   * gives 0.480-0.484 m at h = 5, 2.5 and 1.25 mm (0.44-0.46 measured;
   * benchmarks/granular/README.md). Said at the start, with the remedy.
   */
  template <int dim>
  void
  Simulation<dim>::warn_of_apic_at_rough_faces() const
  {
    if (!with_transfer(integrator_parameters.transfer,
                       [](auto c) { return c.stores_affine_velocity; }))
      return;
    std::string rough_face;
    for (unsigned int f = 0; f < 2 * dim && rough_face.empty(); ++f)
      if (is_rough(grid_parameters.boundary[f]))
        rough_face =
          face_name(f) + "' = " +
          (grid_parameters.boundary[f] == BoundaryType::fixed ? "fixed"
                                                              : "friction");
    if (rough_face.empty())
      return;
    const auto &bodies = points->bodies();
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (!bodies[b].rigid_velocity && bodies[b].material->can_part())
        {
          pcout << "  warning: body " << b << " is cohesionless ("
                << body_parameters[b].material_name
                << ") and the transfer is APIC with 'Grid/boundary "
                << rough_face
                << ": points that part carry their shear "
                   "as an affine velocity the face does not brake, and slide "
                   "along it undamped on fine grids; 'Simulation/transfer = "
                   "FLIP' with 'FLIP fraction = 0.999' converges "
                   "(benchmarks/granular/README.md)"
                << std::endl;
          return;
        }
  }


  /**
   * Friction turns a round body by its torque mu N R, and a flat under the
   * body of half-width a resists rolling by up to N a: where a > mu R the
   * body slides without turning. At the grid's friction faces and at rigid
   * bodies friction acts on the nodes, and every node the body's stencils
   * reach is held: a flat of sqrt(2 r h R) either side of the lowest point
   * (r the basis' reach in cells). A round disk seeded from a mesh on the
   * friction face: at mu = 0.1 it does not turn at 5-20 cells per radius;
   * at mu = 0.5 it turns at 0 / 63 / 92 % of its rate at 5 / 10 / 20
   * (flat < mu R from 12 on). A rigid wall acts on the points instead, and
   * there the flat is the lattice's: the bottom row of a ball seeded on it
   * is up to sqrt(2 s R) wide (s the points' spacing); a disk at mu = 0.1
   * turns at 11 / 40 / 80 % of its rate with 10 / 20 / 40 points per
   * radius, and seeded from a mesh at 80 / 89 / 93-95 % with 16 / 32 / 64
   * mesh cells across its core, whatever the grid
   * (benchmarks/contact/README.md). Said at the start, with the remedy.
   */
  template <int dim>
  void
  Simulation<dim>::warn_of_rolling_resistance() const
  {
    // The weakest friction that acts at all: a frictionless wall exerts no
    // torque, and the weakest one turns the body least.
    double      mu_at_nodes = 0, mu_at_points = 0;
    std::string at_nodes;
    auto        weakest = [](double &mu, const double candidate) {
      const bool weaker = candidate > 0 && (mu == 0 || candidate < mu);
      if (weaker)
        mu = candidate;
      return weaker;
    };
    for (unsigned int f = 0; f < 2 * dim; ++f)
      if (grid_parameters.boundary[f] == BoundaryType::friction &&
          weakest(mu_at_nodes, grid_parameters.friction_coefficient))
        at_nodes = "'Grid/boundary " + face_name(f) + "' = friction";
    for (const auto &body : body_parameters)
      if (body.rigid_velocity &&
          weakest(mu_at_nodes, contact_parameters.friction_coefficient))
        at_nodes = "contact with a rigid body";
    for (const auto &wall : rigid_wall_parameters)
      weakest(mu_at_points, wall.friction_coefficient);

    const double h = grid->min_cell_size();
    for (unsigned int b = 0; b < body_parameters.size(); ++b)
      {
        const BodyParameters<dim> &body = body_parameters[b];
        const double R = body.shape ? body.shape->rolling_radius() : 0.;
        if (body.rigid_velocity || !(R > 0))
          continue;
        const double spacing    = h / body.particles_per_cell;
        const double reach      = support_reach(integrator_parameters.basis,
                                           0.5 / body.particles_per_cell);
        const double nodes_flat = std::sqrt(2. * reach * h * R);
        const double seed_flat  = std::sqrt(2. * spacing * R);
        if (mu_at_nodes > 0 && nodes_flat > mu_at_nodes * R)
          pcout << "  warning: body " << b << " is round (radius " << R
                << ") and its friction (" << at_nodes
                << ", mu = " << mu_at_nodes
                << ") acts at the grid's nodes: every node its stencils "
                   "reach holds it, a flat of about "
                << nodes_flat
                << " either side of its lowest point, wider than mu R = "
                << mu_at_nodes * R
                << ", and such a flat keeps it from turning (it slides like "
                   "a block); friction turns it only on cells below about "
                   "mu^2 R / (2 r) = "
                << mu_at_nodes * mu_at_nodes * R / (2. * reach)
                << " (r = " << reach
                << ", the basis' reach in cells). A rigid wall ('Boundary "
                   "conditions/Rigid wall') acts "
                   "on the points and turns a body seeded from a mesh "
                   "(benchmarks/contact/README.md)"
                << std::endl;
        else if (mu_at_points > 0 && seed_flat > mu_at_points * R)
          pcout << "  warning: body " << b << " is round (radius " << R
                << ") and seeded on the grid's lattice, whose bottom row is "
                   "a flat of up to "
                << seed_flat
                << " either side of its lowest point, wider than mu R = "
                << mu_at_points * R
                << " of a rigid wall's friction: the flat resists its "
                   "turning (a disk at mu = 0.1 turns at 11 / 40 / 80 % of "
                   "its rate with 10 / 20 / 40 points per radius); 'shape = "
                   "mesh' with 'mesh points = Gauss points' seeds it round "
                   "(benchmarks/contact/README.md)"
                << std::endl;
      }
  }


  template <int dim>
  std::string
  Simulation<dim>::scheme_description() const
  {
    std::ostringstream s;
    const auto        &p = integrator_parameters;
    s << "scheme " << update_scheme_names.name(p.scheme) << ", basis "
      << basis_names.name(p.basis) << ", transfer ";
    if (!with_transfer(p.transfer, [](auto c) { return c.blends_pic; }))
      s << transfer_names.name(p.transfer);
    else if (p.pic_relaxation_time > 0)
      s << "PIC/FLIP with PIC relaxation time " << p.pic_relaxation_time
        << " s";
    else
      s << "PIC/FLIP with FLIP fraction " << p.flip_fraction;
    if (p.f_bar)
      s << ", F-bar";
    if (p.local_damping > 0)
      s << ", local damping " << p.local_damping;
    if (p.mass_scaling > 1)
      s << ", mass scaling " << p.mass_scaling << " (time step x "
        << std::sqrt(p.mass_scaling) << ")";
    if (p.macro_time_step > 0)
      {
        s << ", macro steps of " << p.macro_time_step << " s with ";
        if (p.substeps > 0)
          s << p.substeps << " substeps";
        else
          s << "substeps from the CFL condition";
        if (p.kinetic_damping)
          s << ", kinetic damping";
      }
    return s.str();
  }


  template <int dim>
  void
  Simulation<dim>::print_progress(const double wall_seconds) const
  {
    const double t    = integrator->time();
    const double end  = integrator_parameters.end_time;
    const double done = t / end;
    const double eta  = done > 0 ? wall_seconds * (1 - done) / done : 0;
    pcout << "step " << std::setw(7) << integrator->step_number()
          << "  t = " << std::setprecision(4) << std::setw(10) << t
          << "  dt = " << std::setw(10) << integrator->last_time_step() << "  "
          << std::fixed << std::setprecision(1) << std::setw(5) << 100 * done
          << "%  ETA " << std::setprecision(0) << eta << " s"
          << std::defaultfloat << std::setprecision(6) << std::endl;
  }


  template <int dim>
  double
  Simulation<dim>::imbalance() const
  {
    const auto work =
      Utilities::MPI::min_max_avg(grid->local_work(points->handler()), comm);
    return work.avg > 0 ? work.max / work.avg - 1 : 0;
  }


  /**
   * Dynamic load balancing (as ASPECT and Lethe do with deal.II's
   * particles): when the work of the busiest rank exceeds the mean by
   * more than 'Grid/load imbalance limit', p4est repartitions the tiles
   * weighted by the points they hold, the points travel with their tiles,
   * and everything that holds nodal data is set up again. It runs between
   * steps, where no nodal data carries over.
   */
  template <int dim>
  void
  Simulation<dim>::balance_load()
  {
    const double limit = grid_parameters.imbalance_limit;
    if (Utilities::MPI::n_mpi_processes(comm) == 1 || dim == 1)
      return;
    TimerOutput::Scope scope(*timer, "load balance");
    double             now = imbalance();
    // If the last repartition could not get below the limit (tiles too
    // coarse for the ranks), the next waits until the imbalance has grown
    // by half the limit beyond what that one reached: repartitioning every
    // step would gain nothing.
    const double trigger =
      achieved_imbalance > limit ? achieved_imbalance + 0.5 * limit : limit;
    if (limit > 0 && now > trigger)
      {
        grid->repartition(points->handler());
        integrator->setup_nodal_data();
        velocity_region->find_nodes(*grid);
        ++n_rebalances;
        now                = imbalance();
        achieved_imbalance = now;
      }
    largest_imbalance = std::max(largest_imbalance, now);
  }


  template <int dim>
  double
  Simulation<dim>::peak_memory_bytes(const bool private_only) const
  {
    Utilities::System::MemoryStats memory; // of this rank
    Utilities::System::get_memory_stats(memory);
    return Utilities::MPI::sum(double(memory.VmHWM) * 1024. -
                                 (private_only ? library_bytes : 0.),
                               comm);
  }


  template <int dim>
  void
  Simulation<dim>::print_performance(const double wall_seconds,
                                     const double step_seconds) const
  {
    timer->print_wall_time_statistics(comm);
    const double particle_steps =
      double(points->handler().n_global_particles()) *
      (integrator->step_number() - first_step);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    // Cost per particle-step per rank: rank-seconds / particle-steps.
    auto ns = [&](const double seconds) {
      return 1e9 * seconds * n_ranks / std::max(particle_steps, 1.);
    };
    const double n_points =
      std::max<double>(points->handler().n_global_particles(), 1);
    const double bytes_per_particle = peak_memory_bytes() / n_points;
    const double private_bytes      = peak_memory_bytes(true);
    // The nodes whose values cross rank boundaries (summed over ranks):
    // what the nodal exchanges of a step send, per component.
    const double ghost_nodes =
      Utilities::MPI::sum(double(grid->node_partitioner().n_ghost_indices()),
                          comm);
    pcout << "Finished " << integrator->step_number() - first_step
          << " steps to t = " << integrator->time() << " in " << wall_seconds
          << " s (" << step_seconds << " s in steps): " << ns(step_seconds)
          << " ns per particle-step per rank, peak memory "
          << bytes_per_particle << " bytes per particle (all ranks)\n";

    // The same, per phase, machine-readable (benchmarks/ collect it).
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ofstream f(output_parameters.directory + "/timing.csv");
        f << "phase,seconds,ns_per_particle_step\n";
        for (const auto &[phase, seconds] :
             timer->get_summary_data(TimerOutput::total_wall_time))
          f << phase << "," << seconds << "," << ns(seconds) << "\n";
        f << "steps," << step_seconds << "," << ns(step_seconds) << "\n";
        f << "particles," << points->handler().n_global_particles() << ",\n";
        f << "time steps," << integrator->step_number() << ",\n";
        f << "ranks," << n_ranks << ",\n";
        f << "collective sorts," << points->n_collective_sorts() << ",\n";
        f << "memory re-packs (rank 0)," << points->n_memory_repacks() << ",\n";
        f << "peak bytes per particle," << bytes_per_particle << ",\n";
        f << "rebalances," << n_rebalances << ",\n";
        f << "largest imbalance," << largest_imbalance << ",\n";
        f << "peak bytes per particle after setup,"
          << setup_peak_bytes / n_points << ",\n";
        f << "baseline bytes per particle," << baseline_bytes / n_points
          << ",\n";
        f << "peak private bytes per particle," << private_bytes / n_points
          << ",\n";
        f << "ghost nodes," << ghost_nodes << ",\n";
      }
  }


  template class Simulation<1>;
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace mpm
