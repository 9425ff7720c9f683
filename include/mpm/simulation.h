#ifndef mpm_simulation_h
#define mpm_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/background_grid.h>
#include <mpm/bodies/extents.h>
#include <mpm/energy_guard.h>
#include <mpm/material_points.h>
#include <mpm/output.h>
#include <mpm/stages/stage_parameters.h>
#include <mpm/time_integrator.h>
#include <mpm/verification.h>

namespace mpm
{
  using namespace dealii;

  /**
   * Declare every parameter of a scene with @p n_bodies bodies,
   * @p n_walls rigid walls and @p n_stages stages. The
   * declarations do not depend on the dimension: vectors are lists that
   * are checked against it when they are parsed.
   */
  void
  declare_scene_parameters(ParameterHandler  &prm,
                           const unsigned int n_bodies,
                           const unsigned int n_walls  = 0,
                           const unsigned int n_stages = 0);


  /// How Simulation::run() ended.
  struct RunEnding
  {
    /// At the end of its stage, not at the end time (nor in equilibrium
    /// if the stage stopped without it and may continue).
    bool stage_ended = false;
    /// The stage reached equilibrium.
    bool equilibrium = false;
    /// The checkpoint the next stage starts from (none after the last).
    std::string checkpoint;
    /// The time it ended and the out-of-balance force over the weight
    /// then (0 without a stage that ends at equilibrium).
    double time           = 0;
    double out_of_balance = 0;
  };


  /// Wires the components of the design together and runs the scene.
  template <int dim>
  class Simulation
  {
  public:
    /// @p restart: a checkpoint directory to continue from (empty: start);
    /// @p stage: where the run stands among the scene's stages (none by
    /// default).
    Simulation(ParameterHandler    &prm,
               MPI_Comm             comm,
               const std::string   &restart = "",
               const StagePosition &stage   = {});

    /// Set up the scene (or take it back from a checkpoint) and run it
    /// to its end time, or to the end of its stage.
    RunEnding
    run();

    /// The point fields this scene needs (its materials' included).
    FieldRequests
    point_fields() const;

  private:
    /// The grid, partitioned by the points each cell will hold, and the
    /// bodies' points (or the checkpoint's partition and points).
    void
    set_up_grid_and_points(const RunState    *resume,
                           const std::string &checkpoint);
    /// The boundary conditions, contact, the integrator, the verification
    /// and the energy guard (their state from @p resume if given), and the
    /// list of force reporters.
    void
    set_up_integrator(const RunState *resume);
    /// The statistics columns of the scene and the output.
    void
    set_up_output(const RunState *resume);
    /// Step to the end time, with output, checkpoints and progress.
    RunEnding
    run_time_loop(const Timer &wall);
    /// The stage's clock and equilibrium count: from @p resume if the run
    /// continues within its stage, else started now (and the displacements
    /// reset if the stage asks).
    void
    begin_stage(const RunState *resume);
    /// After a step: has the stage reached its end (duration or
    /// equilibrium)? Measures the out-of-balance force (collective).
    bool
    stage_is_over();
    /// Has the stage reached its end (as last measured)?
    bool
    stage_reached_end() const;
    /// The stage ended: the checkpoint the next stage starts from, or the
    /// diagnosis of an equilibrium not reached.
    RunEnding
    end_stage();
    /// The simulated time the run steps to: the end time, or the end of
    /// the stage if sooner.
    double
    run_end_time() const;
    /// Write a checkpoint of the run as it stands into @p directory.
    void
    save_checkpoint(const std::string &directory);
    /// Refuse a checkpoint written by another scene (grid or point fields).
    [[noreturn]] void
    throw_scene_differs(const RunState &resume) const;
    void
    print_scene_summary() const;
    void
    write_output(const double wall_seconds);
    /// Do the points carry APIC's affine velocity field (some stage's
    /// transfer keeps it)? The energy residual then counts its energy.
    bool
    has_affine_field() const
    {
      return points->layout().affine_velocity != FieldLayout::absent;
    }
    /// Stop the run if a value for statistics.csv is not finite.
    void
    stop_if_not_finite(const Statistics<dim>     &s,
                       const std::vector<double> &extra) const;
    /// Refuse a run of more than 1e9 steps, or of more than 1e5 frames
    /// at an interval below its time step.
    void
    refuse_endless_run() const;
    /// A restart continues the checkpoint's physics: refuse a scene that
    /// differs in anything but the end time, output and checkpoint
    /// settings, an end time already passed, and output fields whose point
    /// data the checkpoint lacks.
    void
    check_restart(const RunState &resume, const std::string &checkpoint) const;
    /// After an output: write a checkpoint if one is due.
    void
    checkpoint_if_due(const double wall_seconds);
    void
    print_progress(const double wall_seconds) const;
    /// "scheme USL, basis linear, transfer ..." for the start-up summary.
    std::string
    scheme_description() const;
    void
    warn_of_volumetric_locking() const;
    /// Frictional bodies with FLIP's PIC share (see there).
    void
    warn_of_pic_viscosity() const;
    void
    warn_of_apic_at_rough_faces() const;
    /// Round bodies on a flat wider than mu R (see there).
    void
    warn_of_rolling_resistance() const;
    void
    print_performance(const double wall_seconds,
                      const double step_seconds) const;
    /// Work of the busiest rank over the mean, less 1 (collective).
    double
    imbalance() const;
    /// Repartition the grid if imbalance() exceeds the scene's limit.
    void
    balance_load();
    /// Peak resident memory so far, summed over the ranks (collective).
    /// With @p private_only, less each rank's library pages at the start:
    /// the memory the run itself holds, an upper bound (library pages only
    /// grow as more code runs).
    double
    peak_memory_bytes(const bool private_only = false) const;

    MPI_Comm                              comm;
    ConditionalOStream                    pcout;
    GridParameters<dim>                   grid_parameters;
    IntegratorParameters<dim>             integrator_parameters;
    std::vector<BodyParameters<dim>>      body_parameters;
    VelocityRegionParameters<dim>         velocity_region_parameters;
    std::vector<RigidWallParameters<dim>> rigid_wall_parameters;
    VirtualFluidParameters<dim>           virtual_fluid_parameters;
    ContactParameters<dim>                contact_parameters;
    OutputParameters                      output_parameters;
    CheckpointParameters                  checkpoint_parameters;
    std::string                           restart;
    /// Every entry of the scene by its path, as given (written with each
    /// checkpoint; a restart compares).
    std::map<std::string, std::string> scene_entries;
    bool                               bodies_may_overlap;
    VerificationParameters             verification_parameters;
    /// The stage this run is in (none if the scene has no stages).
    StagePosition stage;
    double        stage_start_time = 0;
    /// Steps in a row with the out-of-balance force below the stage's
    /// tolerance, and the latest ratio of that force to the weight.
    unsigned int steps_in_balance = 0;
    double       out_of_balance   = 0;
    /// The bodies' weight, the scale of the out-of-balance force.
    double weight = 0;

    std::unique_ptr<TimerOutput>         timer; ///< made in run(), see there
    std::unique_ptr<BackgroundGrid<dim>> grid;
    std::unique_ptr<MaterialPoints<dim>> points;
    std::unique_ptr<VelocityRegion<dim>> velocity_region;
    std::vector<std::unique_ptr<RigidWall<dim>>> rigid_walls;
    std::unique_ptr<VirtualFluid<dim>>           virtual_fluid;
    std::unique_ptr<MultiFieldContact<dim>>      contact;
    std::unique_ptr<TimeIntegrator<dim>>         integrator;
    std::unique_ptr<Verification<dim>>           verification;
    std::unique_ptr<EnergyGuard<dim>>            energy_guard;
    std::unique_ptr<BodyExtents<dim>>            extents; ///< if asked for
    std::unique_ptr<Output<dim>>                 output;
    /// The conditions whose mean forces are columns of statistics.csv, in
    /// the order of their columns (region, walls, fluid, contact).
    std::vector<ForceReporter *> force_reporters;
    /// The names of the columns of statistics.csv after the statistics'
    /// own (verification, walls, regions, ..., extents last).
    std::vector<std::string> statistics_columns;
    double                   last_output_time     = -1;
    double                   next_checkpoint_time = 0, last_checkpoint_wall = 0;
    /// The step this run started from (not 0 after a restart): the cost per
    /// particle-step counts this run's steps.
    unsigned int first_step = 0;
    /// Peak resident memory of all ranks once the scene is set up (before
    /// the first output and step), in bytes.
    double setup_peak_bytes = 0;
    /// Resident memory of all ranks before the scene's data (the program's
    /// libraries and MPI), in bytes.
    double baseline_bytes = 0;
    /// Of that, this rank's file-backed pages (the code of the program and
    /// its libraries, which all ranks of a node share in the page cache).
    double library_bytes = 0;
    /// Repartitions during the run, and the largest imbalance any step
    /// ran with (after its repartition, if it had one).
    unsigned int n_rebalances       = 0;
    double       largest_imbalance  = 0;
    double       achieved_imbalance = 0; ///< right after the last one
  };
} // namespace mpm

#endif
