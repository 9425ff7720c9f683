// dealii-mpm: run a Material Point Method scene described in a .prm file.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/parameters.h>
#include <mpm/simulation.h>
#include <mpm/stages/staged_run.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace
{
  using namespace dealii;

  const char *usage =
    "Usage: dealii-mpm [options] scene.prm\n"
    "  -s \"Section/Name=value\"  override one parameter (repeatable), e.g.\n"
    "                           -s \"Grid/cells=64\" -s \"Bodies/Body "
    "0/density=2000\"\n"
    "  --restart DIR             continue the run from the checkpoint in DIR\n"
    "                           (see 'Checkpoint'); the scene's output\n"
    "                           directory must hold the run's output\n"
    "  --print-parameters        print every parameter with its default,\n"
    "                           allowed values and documentation\n"
    "  --help                    this text\n";


  struct CommandLine
  {
    std::string                                      scene;
    std::string                                      restart;
    std::vector<std::pair<std::string, std::string>> overrides;
    bool                                             help             = false;
    bool                                             print_parameters = false;
  };


  CommandLine
  parse_command_line(const int argc, char **argv)
  {
    CommandLine c;
    for (int i = 1; i < argc; ++i)
      {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h")
          c.help = true;
        else if (a == "--print-parameters")
          c.print_parameters = true;
        else if (a == "--restart")
          {
            if (i + 1 == argc)
              throw std::runtime_error("option --restart needs a checkpoint "
                                       "directory");
            c.restart = argv[++i];
          }
        else if (a == "-s")
          {
            if (i + 1 == argc)
              throw std::runtime_error(
                "option -s needs \"Section/Name=value\"");
            const std::string o  = argv[++i];
            const auto        eq = o.find('=');
            if (eq == std::string::npos || o.find('/') == std::string::npos)
              throw std::runtime_error(
                "option -s '" + o +
                "' is not of the form \"Section/Name=value\"");
            c.overrides.emplace_back(Utilities::trim(o.substr(0, eq)),
                                     Utilities::trim(o.substr(eq + 1)));
          }
        else if (!a.empty() && a[0] == '-')
          throw std::runtime_error("unknown option '" + a + "'\n" + usage);
        else if (c.scene.empty())
          c.scene = a;
        else
          throw std::runtime_error("more than one scene file given ('" +
                                   c.scene + "', '" + a + "')");
      }
    return c;
  }


  /**
   * A mesh file named relative to the scene is found next to it, wherever
   * the program is started from: the scene and its meshes travel together.
   */
  void
  resolve_mesh_files(ParameterHandler  &prm,
                     const unsigned int n_bodies,
                     const std::string &scene)
  {
    const auto directory = std::filesystem::path(scene).parent_path();
    prm.enter_subsection("Bodies");
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        prm.enter_subsection("Body " + std::to_string(b));
        const std::filesystem::path file = prm.get("mesh file");
        if (!file.empty() && file.is_relative())
          prm.set("mesh file", (directory / file).lexically_normal().string());
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  /**
   * What ParameterHandler accepts silently but a scene must not do: be a
   * directory or empty, set one parameter twice or open one section twice
   * (the later value wins unseen), or declare more bodies or rigid walls
   * than it describes (a default one would be added). Checked on the text
   * of the file; the -s overrides count as written.
   */
  class SceneText
  {
  public:
    SceneText(const std::string &scene, const CommandLine &c)
    {
      std::vector<std::string> stack;
      if (!read(scene, stack, 0))
        throw mpm::InputError("scene file '" + scene +
                              "' is empty: nothing to simulate");
      for (const auto &[path, value] : c.overrides)
        sections.emplace(path.substr(0, path.rfind('/')), "option -s");
    }

    /// Is section @p path ("Bodies/Body 1") written?
    bool
    has_section(const std::string &path) const
    {
      return sections.count(path) > 0;
    }

    /// The written parameters ("Simulation/end time") and where.
    const std::map<std::string, std::string> &
    written_entries() const
    {
      return entries;
    }

    /// The written sections whose path starts with @p prefix.
    std::vector<std::string>
    sections_starting_with(const std::string &prefix) const
    {
      std::vector<std::string> found;
      for (const auto &[path, line] : sections)
        if (path.rfind(prefix, 0) == 0)
          found.push_back(path);
      return found;
    }

  private:
    /// Note the sections and parameters of @p file, opened in the sections
    /// of @p stack; follows 'include' as deal.II does (the file named
    /// relative to the directory the program runs in). Was anything
    /// written?
    bool
    read(const std::string        &file,
         std::vector<std::string> &stack,
         const unsigned int        depth)
    {
      namespace fs = std::filesystem;
      if (!fs::exists(file))
        throw mpm::InputError("scene file '" + file + "' does not exist" +
                              (depth > 0 ? " (an 'include' names it; it is "
                                           "read relative to the directory "
                                           "the program runs in)"
                                         : ""));
      if (fs::is_directory(file))
        throw mpm::InputError("scene '" + file +
                              "' is a directory, not a scene file");
      if (depth > 16)
        throw mpm::InputError("scene file '" + file +
                              "' is included more than 16 deep: does it "
                              "include itself?");
      std::ifstream in(file);
      std::string   line, logical;
      unsigned int  number = 0, first_of_logical = 0;
      bool          anything = false;
      while (std::getline(in, line))
        {
          ++number;
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (logical.empty())
            first_of_logical = number;
          // deal.II joins a line ending in a backslash with the next.
          if (!line.empty() && line.back() == '\\')
            {
              logical += line.substr(0, line.size() - 1) + " ";
              continue;
            }
          line = Utilities::trim(logical + line);
          logical.clear();
          if (line.empty())
            continue;
          anything = true;
          const auto where =
            "line " + std::to_string(first_of_logical) + " of " + file;
          if (line.rfind("subsection ", 0) == 0)
            {
              stack.push_back(Utilities::trim(line.substr(11)));
              note(sections, path(stack, ""), where, "section");
            }
          else if (line == "end")
            {
              if (!stack.empty())
                stack.pop_back();
            }
          else if (line.rfind("set ", 0) == 0)
            note(entries,
                 path(stack,
                      Utilities::trim(line.substr(4, line.find('=') - 4))),
                 where,
                 "parameter");
          else if (line.rfind("include ", 0) == 0 ||
                   line.rfind("INCLUDE ", 0) == 0)
            read(Utilities::trim(line.substr(8)), stack, depth + 1);
        }
      return anything;
    }

    static std::string
    path(const std::vector<std::string> &stack, const std::string &name)
    {
      std::string p;
      for (const auto &s : stack)
        p += (p.empty() ? "" : "/") + s;
      return name.empty() ? p : p + "/" + name;
    }

    static void
    note(std::map<std::string, std::string> &seen,
         const std::string                  &path,
         const std::string                  &where,
         const std::string                  &kind)
    {
      const auto [first, fresh] = seen.emplace(path, where);
      if (!fresh)
        throw mpm::InputError(kind + " '" + path + "' is written twice (" +
                              first->second + " and " + where +
                              (kind == "parameter"
                                 ? "): the second would silently win"
                                 : "): their entries would silently merge") +
                              "; write it once");
    }

    std::map<std::string, std::string> sections, entries;
  };


  /// Every one of the @p n numbered sections '@p parent/@p kind N' the
  /// count @p count_path declares must be written, and no other (deal.II
  /// would reject it naming only a line).
  void
  check_numbered_sections(const SceneText   &text,
                          const std::string &parent,
                          const std::string &kind,
                          const unsigned int n,
                          const std::string &count_path)
  {
    for (unsigned int i = 0; i < n; ++i)
      if (!text.has_section(parent + "/" + kind + " " + std::to_string(i)))
        throw mpm::InputError(count_path,
                              std::to_string(n),
                              "but the scene has no section '" + parent + "/" +
                                kind + " " + std::to_string(i) +
                                "': describe each of them");
    const std::string prefix = parent + "/" + kind + " ";
    for (const auto &section : text.sections_starting_with(prefix))
      {
        const std::string number =
          section.substr(prefix.size(),
                         section.find('/', prefix.size()) - prefix.size());
        const bool counted =
          !number.empty() &&
          number.find_first_not_of("0123456789") == std::string::npos &&
          std::stoul(number) < n;
        if (!counted)
          throw mpm::InputError(count_path,
                                std::to_string(n),
                                "but the scene has a section '" + prefix +
                                  number +
                                  "': raise the count or remove "
                                  "the section");
      }
  }


  /**
   * A parameter the scene writes (in the file or with -s) that the program
   * does not declare is an input error naming it and the closest declared
   * ones, before deal.II would reject it with its own words (which name a
   * line, or 'not yet declared', but not what was meant).
   */
  void
  check_parameter_names(const ParameterHandler &prm,
                        const SceneText        &text,
                        const CommandLine      &c)
  {
    const auto declared = mpm::Parse::entries(prm);
    auto       check = [&](const std::string &path, const std::string &where) {
      if (declared.count(path) > 0)
        return;
      throw mpm::InputError(
        "parameter '" + path + "' (" + where + ") is not declared" +
        mpm::Parse::did_you_mean(path, declared) +
        " ('dealii-mpm --print-parameters' lists them all)");
    };
    for (const auto &[path, where] : text.written_entries())
      check(path, where);
    for (const auto &[path, value] : c.overrides)
      check(path, "option -s");
  }


  /**
   * Read the scene in two passes: the first learns the number of bodies
   * and of rigid walls (and tolerates everything it does not know yet), the
   * second declares that many and reads strictly.
   */
  void
  read_scene(ParameterHandler &prm, const CommandLine &c)
  {
    const SceneText text(c.scene, c);
    unsigned int    n_bodies = 1, n_walls = 0, n_stages = 0;
    {
      ParameterHandler first;
      mpm::declare_scene_parameters(first, 1);
      first.parse_input(c.scene, "", true);
      const std::map<std::string, unsigned int *> counts = {
        {"Bodies/number of bodies", &n_bodies},
        {"Boundary conditions/number of rigid walls", &n_walls},
        {"Stages/number of stages", &n_stages}};
      for (const auto &[path, value] : c.overrides)
        if (counts.count(path) > 0)
          mpm::Parse::set_entry(first, path, value);
      for (const auto &[path, count] : counts)
        {
          const auto slash = path.find('/');
          first.enter_subsection(path.substr(0, slash));
          *count = first.get_integer(path.substr(slash + 1));
          first.leave_subsection();
        }
    }
    check_numbered_sections(
      text, "Bodies", "Body", n_bodies, "Bodies/number of bodies");
    check_numbered_sections(text,
                            "Boundary conditions",
                            "Rigid wall",
                            n_walls,
                            "Boundary conditions/number of rigid walls");
    check_numbered_sections(
      text, "Stages", "Stage", n_stages, "Stages/number of stages");
    mpm::declare_scene_parameters(prm, n_bodies, n_walls, n_stages);
    check_parameter_names(prm, text, c);
    prm.parse_input(c.scene);
    for (const auto &[path, value] : c.overrides)
      mpm::Parse::set_entry(prm, path, value);
    resolve_mesh_files(prm, n_bodies, c.scene);
  }
} // namespace


int
main(int argc, char **argv)
{
  // Open MPI's shared-memory file pointer (component 'sharedfp sm', used
  // by the MPI-IO writes of the .vtu files) keeps a named semaphore per
  // file name in /dev/shm. A run killed while writing leaves it locked,
  // and every later run writing a file of that name on this machine hangs
  // (seen: a kill of particles_00141.0.vtu stopped a later, unrelated run
  // there). The file-lock component's locks end with the process. A
  // setting of the user's own is kept.
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root  = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  auto       error = [root](const std::string &kind, const std::string &what) {
    if (root)
      std::cerr << "dealii-mpm: " << kind << ": " << what << std::endl;
  };
  try
    {
      const CommandLine c = parse_command_line(argc, argv);
      if (c.help)
        {
          if (root)
            std::cout << usage;
          return 0;
        }
      ParameterHandler prm;
      if (c.print_parameters)
        {
          mpm::declare_scene_parameters(prm, 1);
          if (root)
            prm.print_parameters(std::cout, ParameterHandler::PRM);
          return 0;
        }
      if (c.scene.empty())
        throw std::runtime_error(std::string("no scene file given\n") + usage);
      read_scene(prm, c);
      const auto read_again = [&c](ParameterHandler &p) { read_scene(p, c); };
      prm.enter_subsection("Simulation");
      const int dim = prm.get_integer("dimension");
      prm.leave_subsection();
      switch (dim)
        {
          case 1:
            mpm::run_scene<1>(prm, MPI_COMM_WORLD, c.restart, read_again);
            break;
          case 2:
            mpm::run_scene<2>(prm, MPI_COMM_WORLD, c.restart, read_again);
            break;
          default:
            mpm::run_scene<3>(prm, MPI_COMM_WORLD, c.restart, read_again);
        }
    }
  catch (const mpm::InputError &e)
    {
      error("input error", e.what());
      return 1;
    }
  catch (const mpm::RunError &e)
    {
      error("run stopped", e.what());
      return 2;
    }
  catch (const ExceptionBase &e)
    {
      error("input error", mpm::Parse::one_line(e));
      return 1;
    }
  catch (const std::exception &e)
    {
      error("error", e.what());
      return 1;
    }
  return 0;
}
