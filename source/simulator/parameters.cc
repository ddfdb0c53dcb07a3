/**
 * @file
 * The scene file: declaration, two-pass parsing and checks.
 *
 * A scene names its bodies, boundary conditions, contact pairs and probes in
 * lists at the top level; each name then has its own subsection ("Body
 * rod_a", ...). The lists are read first (unknown entries skipped), then the
 * whole file is parsed strictly against the full declaration, so a
 * misspelled entry is an error, not a silently ignored line.
 */
#include <anvil/mesh/mesh_file.h>
#include <anvil/rebar/reinforcement.h>
#include <anvil/deck/deck.h>
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/input_error.h>
#include <anvil/utilities/plugins.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <set>

namespace anvil
{
  namespace
  {
    std::vector<std::string> names(const std::string &list)
    {
      return dealii::Utilities::split_string_list(list, ',');
    }

    std::string join(const std::vector<std::string> &list)
    {
      std::string result;
      for (const auto &s : list)
        result += (result.empty() ? "" : ", ") + s;
      return result;
    }

    void declare_lists(dealii::ParameterHandler &prm)
    {
      using namespace dealii;
      prm.declare_entry("Additional shared libraries",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Plugins to load before the scene is read: shared libraries "
                        "(relative to the folder of the scene file that names them) whose plugins register "
                        "themselves like Anvil's own (doc/extending.md).");
      prm.declare_entry("Bodies",
                        "body",
                        Patterns::List(Patterns::Anything()),
                        "Names of the scene's bodies; each has a subsection "
                        "'Body NAME'.");
      prm.declare_entry("Boundary conditions",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Names of kinematic boundary conditions; each has a "
                        "subsection 'Boundary condition NAME'.");
      prm.declare_entry("Contact pairs",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Names of contact pairs; each has a subsection "
                        "'Contact pair NAME'. No contact search runs "
                        "without pairs.");
      prm.declare_entry("Probes",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Names of probe points; each has a subsection "
                        "'Probe NAME' and writes probe_NAME.csv.");
      prm.declare_entry("Rebars",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Names of reinforcement layouts; each has a subsection "
                        "'Rebar NAME' and writes rebar_NAME.csv.");
      prm.declare_entry("Stages",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Names of the stages that follow the scene's own run, in "
                        "order, each on the state the one before left; each has a "
                        "subsection 'Stage NAME' and writes its results to "
                        "OUTPUT DIRECTORY/NAME/NAME-OF-STAGE/ (doc/user_guide.md, "
                        "\"Stages\").");
    }

    // @sect3{Include files}
    //
    // deal.II opens an 'include' relative to the working directory; a scene
    // that includes another in its own folder (the variants in prm/) must
    // run from anywhere. So the scene is expanded here: each 'include FILE'
    // is resolved relative to the file that names it, a file that includes
    // itself (directly or through others) is an input error, and the origin
    // of every expanded line is kept for the messages.
    struct ExpandedScene
    {
      std::string                                text;
      std::vector<std::pair<std::string, int>>  origin;
    };

    /**
     * A file an included scene names ('File name', 'Additional shared
     * libraries') is where that scene says, relative to its own folder,
     * wherever the scene that includes it lies: a relative path in such a
     * line of an included file becomes that folder's path. (The top file's
     * are relative to its folder already.)
     */
    std::string anchor_file_names(const std::string &line, const std::filesystem::path &folder)
    {
      const auto first = line.find_first_not_of(" \t");
      const auto eq    = line.find('=');
      if (first == std::string::npos || line.compare(first, 4, "set ") != 0 || eq == std::string::npos)
        return line;
      const std::string entry = dealii::Utilities::trim(line.substr(first + 4, eq - first - 4));
      if (entry != "File name" && entry != "Additional shared libraries")
        return line;
      std::string value   = line.substr(eq + 1);
      std::string comment;
      if (const auto hash = value.find('#'); hash != std::string::npos)
        {
          comment = value.substr(hash);
          value.erase(hash);
        }
      std::string anchored;
      for (const std::string &item : dealii::Utilities::split_string_list(value, ','))
        {
          const std::string name = dealii::Utilities::trim(item);
          if (name.empty())
            continue;
          const std::filesystem::path path(name);
          anchored += (anchored.empty() ? "" : ", ") +
                      (path.is_relative() ? std::filesystem::absolute(folder / path).lexically_normal().string() : name);
        }
      return line.substr(0, eq + 1) + " " + anchored + (comment.empty() ? "" : " " + comment);
    }


    void expand(const std::filesystem::path &file,
                std::vector<std::string>    &stack,
                ExpandedScene               &scene)
    {
      const std::string key = std::filesystem::weakly_canonical(file).string();
      if (std::find(stack.begin(), stack.end(), key) != stack.end())
        throw InputError(file.string() + ": includes itself (through " +
                         std::to_string(stack.size()) + " file(s)); an include must not form a cycle");
      if (stack.size() > 32)
        throw InputError(file.string() + ": includes nested more than 32 deep");
      std::ifstream in(file);
      if (!in)
        throw InputError(file.string() + ": the file cannot be opened");
      stack.push_back(key);
      std::string line;
      int         number = 0;
      while (std::getline(in, line))
        {
          ++number;
          const auto first = line.find_first_not_of(" \t");
          if (first != std::string::npos &&
              (line.compare(first, 8, "include ") == 0 || line.compare(first, 8, "INCLUDE ") == 0))
            {
              std::string name = line.substr(first + 8);
              name.erase(0, name.find_first_not_of(" \t"));
              const auto hash = name.find('#');
              if (hash != std::string::npos)
                name.erase(hash);
              name.erase(name.find_last_not_of(" \t\r") + 1);
              std::filesystem::path target(name);
              if (target.is_relative())
                target = file.parent_path() / target;
              if (!std::filesystem::exists(target))
                throw InputError(file.string() + ": line " + std::to_string(number) + ": include file '" +
                                 name.substr(0, 200) + "' does not exist (relative to " +
                                 (file.parent_path().empty() ? std::string(".") :
                                                               file.parent_path().string()) +
                                 ")");
              expand(target, stack, scene);
              continue;
            }
          if (stack.size() > 1)
            line = anchor_file_names(line, file.parent_path());
          scene.text += line;
          scene.text += '\n';
          scene.origin.emplace_back(file.string(), number);
        }
      stack.pop_back();
    }

    /**
     * Every number written in a 'set' line must be a normal double: strtod
     * reports a value beyond the largest double (1e309) or below the
     * smallest normal one (1e-308, a subnormal) as a range error, and
     * deal.II would only find it later, when an entry is read, with a
     * message that names neither file nor line. Throws an InputError
     * naming the line, the entry and the number.
     */
    void check_number_ranges(const ExpandedScene &scene, const std::string &file)
    {
      std::istringstream in(scene.text);
      std::string        line;
      for (unsigned int n = 0; std::getline(in, line); ++n)
        {
          const auto first = line.find_first_not_of(" \t");
          if (first == std::string::npos || line.compare(first, 4, "set ") != 0)
            continue;
          const auto eq = line.find('=', first);
          if (eq == std::string::npos)
            continue;
          const std::string entry = line.substr(first + 4, eq - first - 4);
          const char       *c     = line.c_str() + eq + 1;
          while (*c != '\0' && *c != '#')
            {
              // A number starts with a digit, or a point before a digit,
              // not preceded by a letter or digit (names like 'b2').
              const bool starts = (std::isdigit(*c) || (*c == '.' && std::isdigit(c[1]))) &&
                                  (c == line.c_str() + eq + 1 ||
                                   !(std::isalnum(c[-1]) || c[-1] == '_' || c[-1] == '.'));
              if (!starts)
                {
                  ++c;
                  continue;
                }
              char *end = nullptr;
              errno     = 0;
              const double value = std::strtod(c, &end);
              if (errno == ERANGE && (value != 0. || end - c > 1))
                {
                  const auto &[origin_file, origin_line] =
                    scene.origin[std::min<std::size_t>(n, scene.origin.size() - 1)];
                  std::string number(c, std::min<std::ptrdiff_t>(end - c, 40));
                  std::string name = entry.substr(0, entry.find_last_not_of(" \t") + 1);
                  throw InputError(file + ": line " + std::to_string(origin_line) + " of " + origin_file +
                                   ": entry '" + name.substr(0, 80) + "': the number " + number +
                                   (std::abs(value) > 1. ? " is larger than the largest double (1.8e308)" :
                                                           " is below the smallest normal double (2.2e-308); write 0 "
                                                           "or a number of sensible size"));
                }
              c = end;
            }
        }
    }

    // deal.II's messages name 'Line <N> of file <F>' of the expanded text:
    // name the real file and line instead.
    std::string locate(std::string msg, const ExpandedScene &scene, const std::string &file)
    {
      const std::string tag = "Line <";
      const auto        at  = msg.find(tag);
      if (at == std::string::npos)
        return msg;
      const auto close = msg.find('>', at);
      const auto of    = msg.find("of file <", close);
      if (close == std::string::npos || of == std::string::npos)
        return msg;
      // Some of deal.II's messages close the file name with '>', some
      // ("no such subsection") do not.
      auto end = of + 9 + file.size() - 1;
      if (msg.compare(of + 9, file.size(), file) != 0)
        end = msg.find('>', of + 9);
      else if (end + 1 < msg.size() && msg[end + 1] == '>')
        ++end;
      if (end == std::string::npos)
        return msg;
      const int n = std::atoi(msg.substr(at + tag.size(), close - at - tag.size()).c_str());
      if (n < 1 || n > int(scene.origin.size()))
        return msg;
      const auto &[origin_file, line] = scene.origin[n - 1];
      return msg.substr(0, at) + "line " + std::to_string(line) + " of " + origin_file + msg.substr(end + 1);
    }
  } // namespace


  void Simulator::declare_parameters(dealii::ParameterHandler       &prm,
                                     const std::vector<std::string> &body_names,
                                     const std::vector<std::string> &bc_names,
                                     const std::vector<std::string> &pair_names,
                                     const std::vector<std::string> &probe_names,
                                     const std::vector<std::string> &rebar_names,
                                     const std::vector<std::string> &stage_names)
  {
    using namespace dealii;
    declare_lists(prm);
    prm.enter_subsection("Simulation");
    {
      prm.declare_entry("Name",
                        "",
                        Patterns::Anything(),
                        "Scene name; results go to OUTPUT DIRECTORY/NAME. "
                        "Empty: the parameter file's name without .prm.");
      prm.declare_entry("Output directory",
                        "output",
                        Patterns::Anything(),
                        "Directory under which the scene's result directory "
                        "is made, relative to the working directory.");
      prm.declare_entry("Overwrite existing output",
                        "false",
                        Patterns::Bool(),
                        "If false, a run stops before it starts when its "
                        "result directory already holds results.");
      prm.declare_entry("End time",
                        "1",
                        Patterns::Double(0.),
                        "Simulated time. Units: s.");
      prm.declare_entry("Time step safety factor",
                        "0.9",
                        Patterns::Double(0.),
                        "Factor on the stable time step min_e L_e / c_e. "
                        "0.9: smaller factors changed no measured quantity of "
                        "the accuracy study by more than 0.2 % and cost 1.3 "
                        "(0.7) and 1.8 (0.5) times the steps; above 1 the "
                        "step is unstable (doc/accuracy.md). Units: none.");
      prm.declare_entry("Maximum time step",
                        "0",
                        Patterns::Anything(),
                        "Upper bound of the time step, a function of the time t "
                        "(a constant such as 1e-7, or an expression such as "
                        "'if(t < 0.01, 1e-7, 1e-6)'; LS-DYNA's LCTM curve); where "
                        "it is 0 or negative the stable step alone sets the step. "
                        "Units: s.");
      prm.declare_entry("End kinetic energy fraction",
                        "0",
                        Patterns::Double(0., 1.),
                        "End the run before 'End time' once no contact pair "
                        "carries force and the kinetic energy of the deformable "
                        "bodies has stayed below this fraction of the initial "
                        "energy for 'End quiet time' (an impact that is over); "
                        "0: off. Units: none.");
      prm.declare_entry("End quiet time",
                        "0.01",
                        Patterns::Double(0.),
                        "How long the end criterion must hold. Units: s.");
      prm.declare_entry("End kinetic to internal ratio",
                        "0",
                        Patterns::Double(0., 1.),
                        "End the run before 'End time' once no contact pair "
                        "carries force and the kinetic energy of the deformable "
                        "bodies has stayed below this fraction of the internal "
                        "energy for 'End quiet time' (a member that has settled); "
                        "0: off. With 'End kinetic energy fraction' too, both "
                        "must hold. Units: none.");
      prm.declare_entry("End contact pairs",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "The contact pairs that must carry no force for the end "
                        "criteria above (names from 'Contact pairs'); empty: every "
                        "pair. A scene whose bodies stay in contact (a member on a "
                        "support modelled by contact) names the impact's pair "
                        "alone.");
      prm.declare_entry("Summary probe",
                        "",
                        Patterns::Anything(),
                        "The probe whose peak and residual displacement are "
                        "summary.csv's peak_displacement_m and "
                        "residual_displacement_m, the figures studies plot (a name "
                        "from 'Probes'); empty: the first probe. Every probe's "
                        "figures are in summary.csv by name as well.");
      prm.declare_entry("Summary contact pair",
                        "",
                        Patterns::Anything(),
                        "The contact pair whose peak force and contact duration are "
                        "summary.csv's peak_contact_force_N and contact_duration_s "
                        "(a name from 'Contact pairs'); empty: the first pair.");
      prm.declare_entry("Duration",
                        "0",
                        Patterns::Double(0.),
                        "If positive, the run ends this long after its start: a "
                        "stage's after the state it starts from (its 'End time' "
                        "is then not used); 0: the run ends at 'End time'. "
                        "Units: s.");
      prm.declare_entry("Mass damping",
                        "0",
                        Patterns::Double(0.),
                        "Mass-proportional damping alpha of the deformable bodies' "
                        "nodes, the force -alpha m v (ABAQUS's alpha_R, LS-DYNA's "
                        "*DAMPING_GLOBAL), for a stage that lets a member settle; "
                        "its work is the energy column 'damping'. A mode of "
                        "angular frequency omega gets the damping ratio alpha / "
                        "(2 omega). 0: none. Units: 1/s.");
      prm.declare_entry("Inactive bodies",
                        "",
                        Patterns::List(Patterns::Anything()),
                        "Rigid bodies taken out of the analysis (a stage that "
                        "removes the hammer): they stop where they are, their "
                        "contact pairs are skipped, and their kinetic energy (and "
                        "their springs' energy) becomes the energy column "
                        "'removed'.");
      prm.declare_entry("Maximum number of steps",
                        "100000000",
                        Patterns::Integer(1),
                        "The run stops with an error after this many steps. "
                        "Units: none.");
      prm.declare_entry("Output interval",
                        "0",
                        Patterns::Double(0.),
                        "Time between VTU field outputs; 0 writes only the "
                        "first and last state. Units: s.");
      prm.declare_entry("History interval",
                        "0",
                        Patterns::Double(0.),
                        "Time between rows of the CSV histories; 0 writes "
                        "every step. Units: s.");
      prm.declare_entry("Gravity",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Gravitational acceleration, applied to every "
                        "deformable body as the body force rho g; its work "
                        "is part of external_work. Units: m/s^2.");
      prm.declare_entry("Energy balance tolerance",
                        "0.05",
                        Patterns::Double(0.),
                        "The run stops when the total energy has grown by "
                        "more than this fraction of the largest E_kin, E_int, E_0 or |W_ext| so far "
                        "beyond the external work. Units: none.");
      prm.declare_entry("Minimum time step ratio",
                        "1e-4",
                        Patterns::Double(0., 1.),
                        "The run stops with an error when the stable time step "
                        "falls below this fraction of the first step's (a collapsing "
                        "element; LS-DYNA's DTMIN); 0: never. Units: none.");
      prm.declare_entry("Checkpoint interval",
                        "0",
                        Patterns::Double(0.),
                        "Simulated time between checkpoints (OUTPUT/NAME/checkpoint/: "
                        "everything 'anvil --resume SCENE.prm' needs to continue the run "
                        "bitwise, on any number of processes); 0: none. SIGTERM and "
                        "SIGINT always write one and stop the run. Units: s.");
      prm.declare_entry("Checkpoint wall interval",
                        "0",
                        Patterns::Double(0.),
                        "Wall-clock time between checkpoints; 0: none. Units: s.");
      prm.declare_entry("Checkpoint at end",
                        "false",
                        Patterns::Bool(),
                        "Write a checkpoint when the run ends, for a next stage "
                        "('anvil --resume-from DIR NEXT.prm').");
      prm.declare_entry("Capacity support",
                        "",
                        Patterns::Anything(),
                        "A boundary condition whose largest reaction summary.csv "
                        "reports as axial_capacity_N (an axial push to failure); "
                        "empty: none.");
      prm.declare_entry("End capacity drop",
                        "0",
                        Patterns::Double(0., 1.),
                        "End the run before 'End time' once the reaction of the "
                        "'Capacity support' has stayed below its peak less this "
                        "fraction for 'End quiet time' (a push to failure that is "
                        "past its capacity; 0.5: below half the peak), checked at "
                        "the history rows; 0: off. Units: none.");
      prm.declare_entry("Intact axial capacity",
                        "0",
                        Patterns::Double(0.),
                        "The undamaged member's capacity: summary.csv adds "
                        "damage_index = 1 - axial_capacity_N / this (Shi, Hao and Li "
                        "2008); 0: none. Units: N.");
      // The test suite runs hundreds of scenes: it makes 'false' the
      // default through the environment (a scene's own 'set Plots' wins).
      const char *plots_default = std::getenv("ANVIL_DEFAULT_PLOTS");
      prm.declare_entry("Partitioner",
                        "metis per kind",
                        Patterns::Selection("hierarchical|metis|zoltan|metis per kind"),
                        "How the elements are cut into one piece per process, "
                        "each weighed by its measured cost (a fully integrated "
                        "element 15 one-point ones, a rigid body's 0.1): "
                        "'metis per kind' (the default) partitions the graph of "
                        "the cells' faces with METIS, each kind of element "
                        "(one-point, fully integrated) balanced by itself "
                        "(METIS's multi-constraint partition), so that every "
                        "process holds its share of a 'Full integration region' "
                        "and of the change of its work during the run (cracking "
                        "under an impactor); 'hierarchical' cuts deal.II's "
                        "hierarchical order of the cells' vertex connectivity "
                        "(neighbours together, groups of groups) into pieces of "
                        "equal weight; 'metis' and 'zoltan' partition the face "
                        "graph by the weights alone with METIS or Trilinos' "
                        "Zoltan (through deal.II). The "
                        "results do not depend on it, bit for bit; the ghost "
                        "layer and the balance do (summary.csv: ghost_elements, "
                        "ghost_dofs; doc/performance.md). Units: none.");
      prm.declare_entry("Rebalance interval",
                        "0",
                        Patterns::Double(0.),
                        "Simulated time between checks of the balance of the "
                        "processes' element work (several processes only): where the "
                        "slowest process spent more than 'Rebalance threshold' times "
                        "the mean in the element loop since the last check, the "
                        "elements are partitioned anew, each weighed by the time its "
                        "kind took per element on its process (cracking concrete, a "
                        "process sharing its core), and the run goes on from a "
                        "checkpoint on the new partition, bit for bit the same "
                        "trajectory; 0: never (the partition of the start, by element "
                        "kind). Units: s.");
      prm.declare_entry("Adapt interval",
                        "0",
                        Patterns::Double(0.),
                        "Simulated time between refinements and coarsenings of the "
                        "bodies with a 'Refinement region' during the run: an element "
                        "is halved (to the region's 'Levels') where its body's criteria "
                        "hold in the current state (the box, by reference centroid; "
                        "within 'Distance' of the 'Near body''s current box, by current "
                        "centroid; its 'Indicator' above the threshold), and eight "
                        "children are joined again where they hold for none of them. "
                        "The state moves onto the new elements and nodes (the energy "
                        "this changes: energy.csv, 'adaptation'; doc/adaptivity.md) and "
                        "the run goes on from a checkpoint of the new mesh; 0: the mesh "
                        "of the start throughout. Units: s.");
      prm.declare_entry("Rebalance threshold",
                        "1.1",
                        Patterns::Double(1.),
                        "The imbalance (the slowest process's element time over the "
                        "mean) above which a check of 'Rebalance interval' partitions "
                        "anew. Units: none.");
      prm.declare_entry("Rebalance when it pays",
                        "true",
                        Patterns::Bool(),
                        "Partition anew only where, beside the threshold, the time the "
                        "slowest process lost to the imbalance since the last check "
                        "(its element time over the mean) exceeds what a new partition "
                        "costs (the run's own start: setup, checkpoint, first forces, "
                        "measured); false: at every check past the threshold.");
      prm.declare_entry("Output compression",
                        "zlib",
                        Patterns::Selection("zlib|none"),
                        "How the VTU pieces of the fields store their arrays: "
                        "'zlib' compresses them in blocks of 32 KiB at zlib's "
                        "fastest level (VTK's vtkZLibDataCompressor, which "
                        "ParaView reads as it is; the run's last lines give "
                        "the ratio); 'none' "
                        "writes them as they are (base64). Units: none.");
      prm.declare_entry("Plots",
                        plots_default && std::string(plots_default) == "false" ? "false" :
                                                                                 "true",
                        Patterns::Bool(),
                        "At the end of the run, write PNG plots beside the CSV "
                        "histories (energies, probes, contact forces, support "
                        "reactions, rigid bodies; a plot per file, with units) "
                        "with Python's matplotlib (Debian: python3-matplotlib); "
                        "without it the run says the plots were skipped. The "
                        "environment variable ANVIL_DEFAULT_PLOTS=false makes "
                        "false the default (the test suite does).");
      prm.declare_entry("Print wall times",
                        "true",
                        Patterns::Bool(),
                        "Print the TimerOutput summary and the estimated "
                        "time left (off for comparable screen output).");
      prm.declare_entry("Progress interval",
                        "5",
                        Patterns::Double(0.),
                        "Wall time between progress lines (step, time, step "
                        "size, energies, balance, time left from the rate "
                        "since the start) and updates of the file 'status' in "
                        "the output directory. 0, or 'Print wall times = "
                        "false': every 10 % of the end time instead, so that "
                        "screen output compares between runs. Units: s.");
    }
    prm.leave_subsection();

    prm.enter_subsection("Postprocess");
    Postprocess::declare_parameters(prm);
    prm.leave_subsection();

    for (const auto &b : body_names)
      {
        prm.enter_subsection("Body " + b);
        Body::declare_parameters(prm);
        prm.leave_subsection();
      }
    for (const auto &b : bc_names)
      {
        prm.enter_subsection("Boundary condition " + b);
        BoundaryCondition::declare_parameters(prm);
        prm.leave_subsection();
      }
    for (const auto &p : pair_names)
      {
        prm.enter_subsection("Contact pair " + p);
        Contact::declare_parameters(prm);
        prm.leave_subsection();
      }
    for (const auto &r : rebar_names)
      {
        prm.enter_subsection("Rebar " + r);
        Rebar::Layout::declare_parameters(prm);
        prm.leave_subsection();
      }
    for (const auto &p : probe_names)
      {
        prm.enter_subsection("Probe " + p);
        prm.declare_entry("Point",
                          "0, 0, 0",
                          Patterns::List(Patterns::Double(), 3, 3),
                          "Reference position; the probe follows the "
                          "nearest node of 'Body'. Units: m.");
        prm.declare_entry("Body", "", Patterns::Anything(),
                          "Body whose node is probed (required when bodies "
                          "touch).");
        prm.declare_entry("Node set", "", Patterns::Anything(),
                          "A node set of one node in the mesh file of 'Body' "
                          "(ABAQUS *Nset, 'INSTANCE.SET'); its node replaces "
                          "'Point'.");
        prm.declare_entry("Average",
                          "node",
                          Patterns::Selection("node|section"),
                          "'node': the motion of the probed node. 'section': "
                          "the motion of the centre of mass of the body's "
                          "cross-section through that node, normal to 'Section "
                          "normal' (the lumped-mass weighted mean over the "
                          "section's nodes; ABAQUS: a reference node with a "
                          "distributing coupling to the section): a member's "
                          "deflection, which a node of crushed or spalled cover "
                          "does not follow. The stress is the probed node's "
                          "element's either way. Units: none.");
        prm.declare_entry("Section normal",
                          "z",
                          Patterns::Selection("x|y|z"),
                          "The axis normal to the section of 'Average = "
                          "section' (a member's axis). Units: none.");
        prm.leave_subsection();
      }
    for (const auto &s : stage_names)
      {
        prm.enter_subsection("Stage " + s);
        prm.declare_entry("Changes",
                          "",
                          Patterns::Anything(),
                          "The entries this stage changes, 'PATH=VALUE' separated "
                          "by ';' (as 'anvil --set' takes them, for example "
                          "'Simulation/Inactive bodies=hammer; Simulation/Mass "
                          "damping=2000'); they hold for this stage and the ones "
                          "after it. A stage keeps the scene's bodies, mesh, bars, "
                          "contact pairs and constrained nodes; it may change "
                          "boundary-condition types and velocities, the end, the "
                          "end criteria, damping, inactive bodies and outputs.");
        prm.leave_subsection();
      }
  }


  void Simulator::print_parameters(std::ostream &out)
  {
    dealii::ParameterHandler prm;
    declare_parameters(prm, {"body"}, {"support"}, {"pair"}, {"probe"}, {"bars"}, {"stage"});
    prm.print_parameters(out,
                         dealii::ParameterHandler::OutputStyle::PRM |
                           dealii::ParameterHandler::OutputStyle::KeepDeclarationOrder);
  }


  // @sect3{Overrides}
  //
  // 'anvil SCENE.prm --set "Body hammer/Rigid body/Mass=220"' (and every run
  // of a study) changes entries without editing the scene: each override
  // becomes the lines 'subsection ...', 'set ENTRY = VALUE', 'end' after the
  // scene's own text, where deal.II's later 'set' wins. Its entry is checked
  // like the scene's, so a misspelled path is an input error naming it.
  std::vector<std::pair<std::string, std::string>>
  Simulator::split_overrides(const std::vector<std::string> &overrides)
  {
    std::vector<std::pair<std::string, std::string>> result;
    for (const auto &o : overrides)
      {
        const auto equal = o.find('=');
        if (equal == std::string::npos || equal == 0)
          throw InputError("--set '" + o.substr(0, 100) +
                           "': expected SUBSECTION/.../ENTRY=VALUE, for example "
                           "'Body hammer/Rigid body/Mass=220'");
        std::string path = o.substr(0, equal), value = o.substr(equal + 1);
        for (auto *s : {&path, &value})
          {
            s->erase(0, s->find_first_not_of(" \t"));
            s->erase(s->find_last_not_of(" \t") + 1);
          }
        if (path.empty() || path.back() == '/' || path.front() == '/' ||
            path.find("//") != std::string::npos)
          throw InputError("--set '" + o.substr(0, 100) + "': the entry path '" + path +
                           "' has an empty subsection or entry name");
        result.emplace_back(path, value);
      }
    return result;
  }


  namespace
  {
    void append_overrides(const std::vector<std::pair<std::string, std::string>> &overrides,
                          ExpandedScene                                          &scene)
    {
      for (const auto &[path, value] : overrides)
        {
          const auto   parts = dealii::Utilities::split_string_list(path, '/');
          const std::string origin = "the override '" + path + "=" + value.substr(0, 60) + "'";
          auto add = [&](const std::string &line) {
            scene.text += line + '\n';
            scene.origin.emplace_back(origin, 1);
          };
          for (unsigned int i = 0; i + 1 < parts.size(); ++i)
            add("subsection " + parts[i]);
          add("set " + parts.back() + " = " + value);
          for (unsigned int i = 0; i + 1 < parts.size(); ++i)
            add("end");
        }
    }
  } // namespace


  void Simulator::validate_scene(const std::string              &parameter_file,
                                 const std::vector<std::string> &overrides)
  {
    dealii::ParameterHandler prm;
    read_scene(parameter_file, overrides, prm);
  }


  std::vector<std::vector<std::string>>
  Simulator::read_scene(const std::string              &parameter_file,
                        const std::vector<std::string> &overrides,
                        dealii::ParameterHandler       &prm,
                        std::vector<std::string>       *deck_notes)
  {
    if (!std::filesystem::exists(parameter_file))
      throw InputError(parameter_file + ": the scene file does not exist");

    ExpandedScene expanded;
    if (Deck::is_deck(parameter_file))
      {
        // A deck of another code: the scene it translates to, its mesh
        // read from the deck itself (beside which the scene 'lies').
        const auto t = Deck::translate(parameter_file,
                                       std::filesystem::path(parameter_file).filename().string());
        expanded.text   = t.text;
        expanded.origin = t.origin;
        if (deck_notes && !t.ignored.empty())
          deck_notes->push_back("the deck's " + t.ignored + ": output or settings Anvil answers its own way");
        if (deck_notes && !t.differs.empty())
          deck_notes->push_back("where Anvil's model differs from the deck's code: " + t.differs);
      }
    else
      {
        std::vector<std::string> stack;
        expand(parameter_file, stack, expanded);
      }
    append_overrides(split_overrides(overrides), expanded);
    check_number_ranges(expanded, parameter_file);
    auto parse = [&](dealii::ParameterHandler &prm, const bool skip) {
      try
        {
          std::istringstream in(expanded.text);
          prm.parse_input(in, parameter_file, "", skip);
        }
      catch (const dealii::ExceptionBase &e)
        {
          std::string msg = locate(one_line_message(e), expanded, parameter_file);
          if (msg.find("No entry with name") != std::string::npos ||
              msg.find("no subsection") != std::string::npos)
            msg += " ('anvil --print-parameters' lists every entry)";
          throw InputError(parameter_file + ": " + msg);
        }
    };

    // Pass 1: the lists of names.
    dealii::ParameterHandler lists;
    declare_lists(lists);
    parse(lists, true);
    {
      const std::string dir = std::filesystem::path(parameter_file).parent_path().string();
      load_shared_libraries(lists.get("Additional shared libraries"), dir.empty() ? "." : dir, parameter_file);
    }
    const auto body_names  = names(lists.get("Bodies"));
    const auto bc_names    = names(lists.get("Boundary conditions"));
    const auto pair_names  = names(lists.get("Contact pairs"));
    const auto probe_names = names(lists.get("Probes"));
    const auto rebar_names = names(lists.get("Rebars"));
    const auto stage_names = names(lists.get("Stages"));
    // Every name becomes a subsection of some fifty entries: a list of
    // hundreds of thousands would take minutes and gigabytes to declare.
    constexpr std::size_t max_names = 1000;
    for (const auto &[entry, list] : {std::pair{"Bodies", &body_names},
                                      std::pair{"Boundary conditions", &bc_names},
                                      std::pair{"Contact pairs", &pair_names},
                                      std::pair{"Probes", &probe_names},
                                      std::pair{"Rebars", &rebar_names},
                                      std::pair{"Stages", &stage_names}})
      {
        if (list->size() > max_names)
          throw InputError(parameter_file + ": entry '" + entry + "' names " + std::to_string(list->size()) +
                           " items; at most " + std::to_string(max_names) + " are allowed");
        if (std::set<std::string>(list->begin(), list->end()).size() != list->size())
          throw InputError(parameter_file + ": a name appears twice in entry '" + entry + "'");
      }
    if (body_names.empty())
      throw InputError(parameter_file + ": entry 'Bodies' names no body");

    // Pass 2: everything, strictly.
    declare_parameters(prm, body_names, bc_names, pair_names, probe_names, rebar_names, stage_names);
    parse(prm, false);
    return {body_names, bc_names, pair_names, probe_names, rebar_names, stage_names};
  }


  std::vector<Stage> Simulator::read_stages(const std::string              &parameter_file,
                                            const std::vector<std::string> &overrides)
  {
    dealii::ParameterHandler prm;
    const auto               lists = read_scene(parameter_file, overrides, prm);
    std::vector<Stage>       stages;
    for (const auto &name : lists[5])
      {
        Stage stage;
        stage.name = name;
        prm.enter_subsection("Stage " + name);
        const std::string changes = prm.get("Changes");
        prm.leave_subsection();
        for (const auto &c : dealii::Utilities::split_string_list(changes, ';'))
          if (!c.empty())
            stage.changes.push_back(c);
        // A stage keeps the scene's lists; its changes are otherwise
        // checked as overrides when the stage's scene is read
        // (run_scene_with_stages, before anything runs).
        for (const auto &c : stage.changes)
          {
            const auto path = c.substr(0, c.find('='));
            if (path.rfind("Stage", 0) == 0 || path == "Stages" || path == "Bodies" ||
                path == "Contact pairs" || path == "Rebars" || path == "Boundary conditions" ||
                path == "Probes")
              throw InputError(parameter_file + ": subsection 'Stage " + name + "', entry 'Changes': '" +
                               c.substr(0, 80) +
                               "' changes the scene's lists; a stage keeps the scene's bodies, "
                               "boundary conditions, contact pairs, probes, bars and stages");
          }
        stages.push_back(stage);
      }
    return stages;
  }


  void Simulator::parse_parameters(const std::string              &parameter_file,
                                   const std::vector<std::string> &overrides)
  {
    parameters.scene_file = parameter_file;
    dealii::ParameterHandler prm;
    parameters.deck_notes.clear();
    const auto               lists       = read_scene(parameter_file, overrides, prm, &parameters.deck_notes);
    const auto              &body_names  = lists[0];
    const auto              &bc_names    = lists[1];
    const auto              &pair_names  = lists[2];
    const auto              &probe_names = lists[3];
    const auto              &rebar_names = lists[4];

    const std::string dir =
      std::filesystem::path(parameter_file).parent_path().string();
    try
      {
        prm.enter_subsection("Simulation");
        parameters.scene_name = prm.get("Name");
        if (parameters.scene_name.empty())
          parameters.scene_name = std::filesystem::path(parameter_file).stem().string();
        parameters.output_directory = prm.get("Output directory") + "/" + parameters.scene_name;
        parameters.overwrite_output = prm.get_bool("Overwrite existing output");
        parameters.end_time         = prm.get_double("End time");
        parameters.time_step_factor = prm.get_double("Time step safety factor");
        parameters.max_steps        = prm.get_integer("Maximum number of steps");
        parameters.end_criterion.kinetic_fraction       = prm.get_double("End kinetic energy fraction");
        parameters.end_criterion.quiet_time             = prm.get_double("End quiet time");
        parameters.end_criterion.kinetic_internal_ratio = prm.get_double("End kinetic to internal ratio");
        parameters.end_criterion.capacity_drop          = prm.get_double("End capacity drop");
        if (parameters.end_criterion.capacity_drop > 0 && prm.get("Capacity support").empty())
          throw InputError("entry 'Simulation/End capacity drop': needs a 'Capacity support' (the boundary "
                           "condition whose reaction it follows); 0 switches it off");
        // The pairs and the probe these entries name, by index.
        const auto index_of = [](const std::string &entry, const std::string &name,
                                 const std::vector<std::string> &names, const std::string &list) {
          const auto it = std::find(names.begin(), names.end(), name);
          if (it == names.end())
            throw InputError("entry 'Simulation/" + entry + "': '" + name + "' is not in '" + list + "' (" +
                             (names.empty() ? std::string("none") : join(names)) + ")");
          return static_cast<unsigned int>(it - names.begin());
        };
        parameters.end_criterion.pairs.clear();
        for (const auto &name : names(prm.get("End contact pairs")))
          parameters.end_criterion.pairs.push_back(index_of("End contact pairs", name, pair_names, "Contact pairs"));
        if (parameters.end_criterion.pairs.empty())
          for (unsigned int p = 0; p < pair_names.size(); ++p)
            parameters.end_criterion.pairs.push_back(p);
        const std::string summary_probe = prm.get("Summary probe"), summary_pair = prm.get("Summary contact pair");
        parameters.summary_subjects.probe = summary_probe.empty() ? 0 : index_of("Summary probe", summary_probe, probe_names, "Probes");
        parameters.summary_subjects.pair =
          summary_pair.empty() ? 0 : index_of("Summary contact pair", summary_pair, pair_names, "Contact pairs");
        parameters.duration                   = prm.get_double("Duration");
        const auto inactive_names  = names(prm.get("Inactive bodies"));
        {
          const std::string expression = prm.get("Maximum time step");
          parameters.max_dt_function = std::make_unique<dealii::FunctionParser<1>>(1);
          // muparser reads 'a, b' as a list of two results: a comma outside
          // parentheses is a typing slip ('1,2' for 1.2), not an expression.
          int depth = 0;
          for (const char ch : expression)
            {
              depth += (ch == '(') - (ch == ')');
              if (ch == ',' && depth == 0)
                throw InputError("entry 'Simulation/Maximum time step': '" + expression.substr(0, 60) +
                                 "' has a comma outside parentheses; give one number or one expression "
                                 "in t (for example 1.2e-7 or if(t < 0.01, 1e-7, 1e-6))");
            }
          // deal.II's parser writes muparser's diagnosis to std::cerr before
          // it throws: keep it off the screen (the error is one line).
          std::ostringstream quiet;
          auto *const        cerr_buffer = std::cerr.rdbuf(quiet.rdbuf());
          try
            {
              parameters.max_dt_function->initialize("t", expression, {});
              const double probe = parameters.max_dt_function->value(dealii::Point<1>(0.));
              if (!std::isfinite(probe))
                throw std::runtime_error("not finite at t = 0");
              std::cerr.rdbuf(cerr_buffer);
              // A constant (the default 0 among them) needs no parser in the
              // explicit step.
              if (expression.find('t') == std::string::npos)
                {
                  parameters.max_dt_constant = probe;
                  parameters.max_dt_function.reset();
                }
            }
          catch (...)
            {
              std::cerr.rdbuf(cerr_buffer);
              throw InputError("entry 'Simulation/Maximum time step': '" +
                               expression.substr(0, 60) +
                               "' is not a number or an expression in t (muparser syntax, "
                               "for example 1e-7 or if(t < 0.01, 1e-7, 1e-6))");
            }
        }
        parameters.output_interval  = prm.get_double("Output interval");
        parameters.history_interval = prm.get_double("History interval");
        parameters.energy_tolerance = prm.get_double("Energy balance tolerance");
        parameters.min_dt_ratio     = prm.get_double("Minimum time step ratio");
        parameters.print_wall_times = prm.get_bool("Print wall times");
        parameters.progress_interval = prm.get_double("Progress interval");
        parameters.make_plots       = prm.get_bool("Plots");
        parameters.compress_output  = prm.get("Output compression") == "zlib";
        parameters.partitioner      = prm.get("Partitioner");
        parameters.checkpoint_interval      = prm.get_double("Checkpoint interval");
        parameters.rebalance_interval       = prm.get_double("Rebalance interval");
        parameters.rebalance_threshold      = prm.get_double("Rebalance threshold");
        parameters.adapt_interval           = prm.get_double("Adapt interval");
        parameters.rebalance_when_it_pays   = prm.get_bool("Rebalance when it pays");
        parameters.checkpoint_wall_interval = prm.get_double("Checkpoint wall interval");
        parameters.checkpoint_at_end        = prm.get_bool("Checkpoint at end");
        prm.leave_subsection();
        if (parameters.time_step_factor <= 0)
          throw InputError("entry 'Simulation/Time step safety factor' must "
                           "be positive");

        bodies.resize(body_names.size());
        for (unsigned int b = 0; b < body_names.size(); ++b)
          {
            prm.enter_subsection("Body " + body_names[b]);
            bodies[b].parse_parameters(prm, body_names[b], dir.empty() ? "." : dir);
            prm.leave_subsection();
          }
        parameters.inactive_bodies.assign(bodies.size(), 0);
        for (const auto &name : inactive_names)
          {
            const auto it = std::find(body_names.begin(), body_names.end(), name);
            if (it == body_names.end())
              throw InputError("entry 'Simulation/Inactive bodies': '" + name + "' is not in 'Bodies' (" +
                               join(body_names) + ")");
            if (!bodies[it - body_names.begin()].is_rigid())
              throw InputError("entry 'Simulation/Inactive bodies': body '" + name +
                               "' is deformable; only rigid bodies (impactors) can be taken out of "
                               "the analysis");
            parameters.inactive_bodies[it - body_names.begin()] = 1;
          }
        auto check_body = [&](const std::string &name, const std::string &where) {
          if (std::find(body_names.begin(), body_names.end(), name) ==
              body_names.end())
            throw InputError("subsection '" + where + "': body '" + name +
                             "' is not in 'Bodies' (" + join(body_names) +
                             ")");
        };
        for (const auto &body : bodies)
          {
            if (!body.refinement_near_body().empty())
              check_body(body.refinement_near_body(), "Body " + body.name + "/Refinement region");
            if (!body.second_near_body().empty())
              check_body(body.second_near_body(), "Body " + body.name + "/Refinement region 2");
          }
        auto constraints_and_loads = std::make_unique<ConstraintsAndLoads>(*this, velocity);
        constraints_and_loads->parse_parameters(prm, bc_names, bodies);
        std::vector<std::unique_ptr<Contact::Algorithm>> pairs;
        std::vector<unsigned char>                        pair_inactive;
        for (unsigned int i = 0; i < pair_names.size(); ++i)
          {
            prm.enter_subsection("Contact pair " + pair_names[i]);
            pairs.push_back(Contact::create(prm, pair_names[i]));
            prm.leave_subsection();
            check_body(pairs.back()->first_body, "Contact pair " + pair_names[i]);
            check_body(pairs.back()->second_body, "Contact pair " + pair_names[i]);
            pair_inactive.push_back(0);
            for (unsigned int b = 0; b < bodies.size(); ++b)
              if (parameters.inactive_bodies[b] && (body_names[b] == pairs.back()->first_body ||
                                       body_names[b] == pairs.back()->second_body))
                pair_inactive.back() = 1;
            const std::string note = pairs.back()->parse_note();
            if (!note.empty())
              pcout << note << std::endl;
          }
        std::vector<Rebar::Layout> rebar_layouts(rebar_names.size());
        for (unsigned int i = 0; i < rebar_names.size(); ++i)
          {
            prm.enter_subsection("Rebar " + rebar_names[i]);
            rebar_layouts[i].parse_parameters(prm, rebar_names[i], dir.empty() ? "." : dir);
            prm.leave_subsection();
            check_body(rebar_layouts[i].host, "Rebar " + rebar_names[i]);
          }
        solids = std::make_unique<Element::SolidBodies>(*this);
        families.clear();
        families.push_back(
          std::make_unique<RigidBody::RigidBodies>(*this, fe, velocity, rigid_dof, parameters.inactive_bodies));
        rigid_bodies = static_cast<RigidBody::RigidBodies *>(families.back().get());
        families.push_back(std::make_unique<Rebar::Reinforcement>(*this, std::move(rebar_layouts)));
        constraints = constraints_and_loads.get();
        families.push_back(std::move(constraints_and_loads));
        contact = std::make_unique<Contact::ContactPairs>(*this, std::move(pairs), std::move(pair_inactive),
                                                          *rigid_bodies);
        for (const auto &body : bodies)
          if (body.refinement_indicator() == Body::contact_pressure_indicator && !contact->names_body(body.name))
            throw InputError("subsection 'Body " + body.name + "/Refinement region': 'Indicator = "
                             "contact_pressure' refines where the body's contact pairs press it, and no "
                             "pair in 'Contact pairs' names '" + body.name + "'");
        all_families = {solids.get()};
        for (const auto &family : families)
          all_families.push_back(family.get());
        all_families.push_back(contact.get());
        probes.resize(probe_names.size());
        for (unsigned int i = 0; i < probe_names.size(); ++i)
          {
            prm.enter_subsection("Probe " + probe_names[i]);
            probes[i].name = probe_names[i];
            const auto p   = dealii::Utilities::split_string_list(prm.get("Point"));
            for (unsigned int d = 0; d < 3; ++d)
              probes[i].point[d] = dealii::Utilities::string_to_double(p[d]);
            probes[i].body     = prm.get("Body");
            probes[i].node_set = MeshFile::key(prm.get("Node set"));
            if (prm.get("Average") == "section")
              probes[i].section_normal = prm.get("Section normal")[0] - 'x';
            prm.leave_subsection();
            if (!probes[i].node_set.empty() && probes[i].body.empty())
              throw InputError("subsection 'Probe " + probe_names[i] +
                               "': 'Node set' needs 'Body' (whose mesh file holds the set)");
            if (!probes[i].body.empty())
              check_body(probes[i].body, "Probe " + probe_names[i]);
          }
        prm.enter_subsection("Postprocess");
        postprocessors = Postprocess::create_all(*this, prm);
        prm.leave_subsection();
      }
    catch (const InputError &e)
      {
        throw InputError(parameter_file + ": " + e.what());
      }
  }
} // namespace anvil
