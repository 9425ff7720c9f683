#include <deal.II/base/utilities.h>

#include <mpm/parameters.h>
#include <mpm/stages/stage_parameters.h>

#include <regex>

namespace mpm
{
  namespace
  {
    const char *changes_help =
      "Changes to the scene when the stage starts, on top of the previous "
      "stages' changes: 'path = value' pairs separated by ';', the path as "
      "in -s (e.g. 'Simulation/local damping = 0; Bodies/Body 0/"
      "Mohr-Coulomb/softening = linear'). A value may hold ';' itself (an "
      "expression per component): a piece starts a new pair only if it "
      "begins with a declared parameter's path. What a stage may not "
      "change: the dimension, the grid's box and cells, the bodies and "
      "their points (only their material's parameters), the numbers of "
      "bodies and walls, the end time, the output's directory, fields and "
      "format, and the stages.";


    /**
     * What the points, the grid or the stages are made of: fixed for the
     * whole run. A body's entries outside its material's section place its
     * points (geometry, density, initial state) and act once, at the
     * start; so does the choice of material, whose point data the
     * checkpoint between the stages holds.
     */
    bool
    fixed_for_the_run(const std::string &path)
    {
      static const std::regex fixed(
        "Simulation/(dimension|end time)|Grid/(lower corner|upper corner|"
        "cells|cells per tile)|Bodies/(number of bodies|may overlap)|"
        "Bodies/Body [0-9]+/[^/]*|Boundary conditions/number of rigid walls|"
        "Output/(directory|fields|particle format)|Stages/.*");
      return std::regex_match(path, fixed);
    }


    /// The pairs of @p text (see changes_help).
    std::vector<std::pair<std::string, std::string>>
    split_changes(const std::string                        &text,
                  const std::string                        &parameter,
                  const std::map<std::string, std::string> &declared)
    {
      std::vector<std::pair<std::string, std::string>> changes;
      if (Utilities::trim(text).empty())
        return changes;
      for (const auto &piece : Utilities::split_string_list(text, ';'))
        {
          const auto        equals = piece.find('=');
          const std::string path   = Utilities::trim(piece.substr(0, equals));
          if (equals != std::string::npos && declared.count(path) > 0)
            {
              changes.emplace_back(path,
                                   Utilities::trim(piece.substr(equals + 1)));
              continue;
            }
          // A component of the previous value, or a misspelt path.
          if (!changes.empty() && (equals == std::string::npos ||
                                   path.find('/') == std::string::npos))
            {
              changes.back().second += "; " + piece;
              continue;
            }
          throw InputError(parameter,
                           text,
                           "'" + path + "' is not a declared parameter" +
                             Parse::did_you_mean(path, declared) +
                             " (write 'path = value' pairs separated by ';')");
        }
      for (const auto &[path, value] : changes)
        if (fixed_for_the_run(path))
          throw InputError(parameter,
                           text,
                           "a stage cannot change '" + path +
                             "', which is fixed for the whole run (a stage "
                             "may change damping, the materials' parameters, "
                             "faces, walls, loads and the output interval)");
      return changes;
    }
  } // namespace


  void
  StageParameters::declare_parameters(ParameterHandler  &prm,
                                      const unsigned int n_stages)
  {
    prm.enter_subsection("Stages");
    prm.declare_entry(
      "number of stages",
      "0",
      Patterns::Integer(0, 100),
      "0: the scene runs as one phase to 'Simulation/end time'. N > 0: it "
      "runs stages 'Stage 0' to 'Stage N-1' in turn, each to its end (its "
      "duration, or equilibrium) with its changes to the scene, e.g. "
      "gravity loading under damping, then the failure with softening. "
      "The clock, the output and statistics.csv run on through the stages; "
      "a checkpoint is written at the end of each stage but the last "
      "('<output directory>/stage_N'), and a restart continues within or "
      "across stages. 'Simulation/end time' still ends the run.");
    for (unsigned int k = 0; k < n_stages; ++k)
      {
        prm.enter_subsection("Stage " + std::to_string(k));
        prm.declare_entry("end",
                          "time",
                          Patterns::Selection("time|equilibrium"),
                          "time: the stage ends after its duration. "
                          "equilibrium: it ends once the out-of-balance "
                          "force (summed over the grid's nodes, without the "
                          "damping and the supports' reactions) is below "
                          "'equilibrium tolerance' times the bodies' weight "
                          "for 10 steps in a row, or after its duration.");
        prm.declare_entry("duration",
                          "1",
                          Patterns::Anything(),
                          "The longest the stage runs, in simulated "
                          "seconds, > 0.");
        prm.declare_entry("equilibrium tolerance",
                          "1e-3",
                          Patterns::Anything(),
                          "Out-of-balance force over the weight that counts "
                          "as equilibrium, in (0, 1).");
        prm.declare_entry("if not in equilibrium",
                          "stop",
                          Patterns::Selection("stop|continue"),
                          "A stage that ends at equilibrium but has not "
                          "reached it within its duration: stop the run "
                          "with a diagnosis, or continue with the next "
                          "stage.");
        prm.declare_entry("reset displacements",
                          "false",
                          Patterns::Bool(),
                          "true: the displacement output counts from the "
                          "positions at the stage's start.");
        prm.declare_entry("changes", "", Patterns::Anything(), changes_help);
        prm.declare_entry(
          "strength reduction",
          "false",
          Patterns::Bool(),
          "true: the stage finds the factor of safety F (Griffiths and Lane "
          "1999). It runs from the end of the stage before (which must end "
          "in equilibrium) again and again, each time with the cohesion "
          "and tan(friction angle) of every frictional body divided by a "
          "factor (the dilation angle and the residual values alike), to "
          "equilibrium (the factor holds) or to its duration (the slope "
          "fails), and bisects between 1 and 'largest factor' until the "
          "bracket is narrower than 'factor tolerance'. Each trial writes "
          "to '<output directory>/strength_reduction/F_<factor>', and "
          "factor_of_safety.csv lists them. Only the last stage, with end = "
          "equilibrium; a restart runs the search again.");
        prm.declare_entry("largest factor",
                          "4",
                          Patterns::Anything(),
                          "Strength reduction: the largest factor tried, > 1.");
        prm.declare_entry("factor tolerance",
                          "0.01",
                          Patterns::Anything(),
                          "Strength reduction: the width of the final "
                          "bracket, in (0, 1).");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  void
  StageParameters::parse_parameters(
    ParameterHandler                         &prm,
    const unsigned int                        k,
    const std::map<std::string, std::string> &declared)
  {
    path = "Stages/Stage " + std::to_string(k);
    prm.enter_subsection("Stages");
    prm.enter_subsection("Stage " + std::to_string(k));
    end =
      prm.get("end") == "equilibrium" ? StageEnd::equilibrium : StageEnd::time;
    duration  = Parse::bounded_double(prm, path, "duration", 0, 1e300, true);
    tolerance = Parse::bounded_double(
      prm, path, "equilibrium tolerance", 0, 1, true, true);
    stop_if_not_reached = prm.get("if not in equilibrium") == "stop";
    reset_displacements = prm.get_bool("reset displacements");
    changes = split_changes(prm.get("changes"), path + "/changes", declared);
    strength_reduction = prm.get_bool("strength reduction");
    largest_factor =
      Parse::bounded_double(prm, path, "largest factor", 1, 100, true);
    factor_tolerance =
      Parse::bounded_double(prm, path, "factor tolerance", 0, 1, true, true);
    prm.leave_subsection();
    prm.leave_subsection();
  }


  std::vector<StageParameters>
  parse_stages(ParameterHandler &prm)
  {
    prm.enter_subsection("Stages");
    const unsigned int n = prm.get_integer("number of stages");
    prm.leave_subsection();
    std::vector<StageParameters> stages(n);
    if (n == 0)
      return stages;
    const auto declared = Parse::entries(prm);
    for (unsigned int k = 0; k < n; ++k)
      {
        stages[k].parse_parameters(prm, k, declared);
        if (!stages[k].strength_reduction)
          continue;
        const std::string name = stages[k].path + "/strength reduction";
        if (k == 0 || k + 1 < n)
          throw InputError(name,
                           "true",
                           "only the last stage, after one that brings the "
                           "bodies to equilibrium, can search the factor of "
                           "safety");
        if (stages[k].end != StageEnd::equilibrium)
          throw InputError(name,
                           "true",
                           "needs '" + stages[k].path +
                             "/end' = equilibrium: a factor holds if its "
                             "trial reaches equilibrium");
      }
    return stages;
  }


  void
  apply_changes(ParameterHandler &prm, const StageParameters &stage)
  {
    for (const auto &[path, value] : stage.changes)
      try
        {
          Parse::set_entry(prm, path, value);
        }
      catch (const InputError &e)
        {
          throw InputError(std::string(e.what()) + " (in '" + stage.path +
                           "/changes')");
        }
  }


  bool
  StagePosition::any_equilibrium() const
  {
    if (!staged())
      return false;
    for (const auto &s : *stages)
      if (s.end == StageEnd::equilibrium)
        return true;
    return false;
  }
} // namespace mpm
