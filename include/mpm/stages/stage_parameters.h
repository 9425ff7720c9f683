#ifndef mpm_stages_stage_parameters_h
#define mpm_stages_stage_parameters_h

// The stages of a scene ('Stages/Stage N'): a run in phases, each with its
// own end (a time, or equilibrium) and changes to the scene's parameters,
// as a finite-element slope code runs gravity loading, then the failure.
#include <deal.II/base/parameter_handler.h>

#include <mpm/field_layout.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /// How a stage ends (besides 'Simulation/end time', which ends the run).
  enum class StageEnd
  {
    time,       ///< after its duration
    equilibrium ///< once in equilibrium (or after its duration)
  };

  /// One stage: when it ends and what it changes.
  struct StageParameters
  {
    /// 'Stages/number of stages' and @p n_stages sections 'Stage N'.
    static void
    declare_parameters(ParameterHandler &prm, const unsigned int n_stages);

    /// Stage @p k; @p declared: every entry of the scene by its path (the
    /// changes name them).
    void
    parse_parameters(ParameterHandler                         &prm,
                     const unsigned int                        k,
                     const std::map<std::string, std::string> &declared);

    /// "Stages/Stage k", for messages.
    std::string path;
    StageEnd    end;
    /// The longest the stage runs, in simulated time.
    double duration;
    /// Equilibrium: the out-of-balance force summed over the grid's nodes,
    /// over the bodies' weight, below this for 'balanced steps' steps in a
    /// row.
    double tolerance;
    /// Equilibrium not reached within the duration: stop the run with a
    /// diagnosis (or go on to the next stage).
    bool stop_if_not_reached;
    /// At the stage's start, the points' current positions become their
    /// initial positions (the displacement output starts from zero).
    bool reset_displacements;
    /// "path = value" pairs applied to the scene when the stage starts, on
    /// top of the previous stages' changes.
    std::vector<std::pair<std::string, std::string>> changes;
    /// The stage searches the factor of safety: trials from the previous
    /// stage's end with the strength divided by a factor, bisected
    /// between 1 and 'largest factor' to a bracket of 'factor tolerance'.
    bool   strength_reduction;
    double largest_factor;
    double factor_tolerance;
  };

  /// Consecutive steps below the tolerance that make equilibrium: one step
  /// can pass through a balance while the body still moves (a vibration
  /// crosses its rest position at its fastest).
  constexpr unsigned int balanced_steps = 10;

  /// The scene's stages; empty if it has none ('Stages/number of stages' =
  /// 0: the run is one phase, as without stages).
  std::vector<StageParameters>
  parse_stages(ParameterHandler &prm);

  /// Apply stage @p stage's changes to @p prm.
  void
  apply_changes(ParameterHandler &prm, const StageParameters &stage);

  /// Where a run stands among the scene's stages (Simulation).
  struct StagePosition
  {
    /// The scene's stages, or null without.
    const std::vector<StageParameters> *stages = nullptr;
    unsigned int                        index  = 0;
    /// The run starts the stage from the previous one's end (not a restart
    /// within it).
    bool entering = false;
    /// Entries the run changes besides the stage's own changes (a trial of
    /// the strength reduction: the reduced strengths).
    std::vector<std::string> other_changes = {};
    /// The point fields of every stage's scene together (run_scene): the
    /// points keep one layout through the stages, e.g. the opening of a
    /// soil that softens to no cohesion only in a later stage.
    FieldRequests fields_of_all_stages = {};

    bool
    staged() const
    {
      return stages != nullptr && !stages->empty();
    }
    const StageParameters &
    current() const
    {
      return (*stages)[index];
    }
    bool
    is_last() const
    {
      return index + 1 == stages->size();
    }
    /// Does any stage end at equilibrium (the statistics then have the
    /// out-of-balance column, in every stage alike)?
    bool
    any_equilibrium() const;
  };
} // namespace mpm

#endif
