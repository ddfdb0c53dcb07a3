/**
 * @file
 * centre_of_mass.csv: the mass and the centre of mass of the deformable
 * bodies at every history row, or of those 'Postprocess/centre of mass/
 * Bodies' names: a postprocessor plugin with a parameter
 * (doc/extending.md, "A postprocessor as a plugin").
 *
 * Without supports, gravity or rigid bodies the nodal forces of the
 * elements and of the contact pairs sum to zero, so the central-difference
 * update keeps sum m v^{n+1/2} constant and the centre of mass moves on a
 * straight line at constant speed, whatever the step sizes: a conservation
 * law to round-off that tests/verification/postprocessor_plugin.py checks.
 */
#include <anvil/mesh/body.h>
#include <anvil/postprocess/interface.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <iomanip>

namespace anvil::Postprocess
{
  class CentreOfMass : public Interface
  {
  public:
    using Interface::Interface;

    // Its own entries, declared in the scene's 'Postprocess/centre of
    // mass' subsection (the registration below names this function).
    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Bodies", "", dealii::Patterns::Anything(),
                        "The deformable bodies whose centre of mass is written, comma-separated "
                        "(empty: all of them).");
    }

    // ... and read once the scene is parsed, in the same subsection. A
    // name that is no body of the scene is bad input: one line, naming the
    // entry.
    void parse_parameters(dealii::ParameterHandler &prm) override
    {
      const auto &bodies = get_bodies();
      const auto  names  = dealii::Utilities::split_string_list(prm.get("Bodies"));
      selected.assign(bodies.size(), names.empty() ? 1 : 0);
      for (const auto &name : names)
        {
          const auto it = std::find_if(bodies.begin(), bodies.end(),
                                       [&](const Body &b) { return b.name == name; });
          if (it == bodies.end())
            throw InputError("entry 'Postprocess/centre of mass/Bodies': '" + name +
                             "' is not a body of the scene");
          selected[it - bodies.begin()] = 1;
        }
    }

    // Called at every history row on every process, with the positions
    // x^n. Each process sums over the dofs it owns (the lumped mass m_i of
    // dof i, its component c_i): M = sum over x-dofs of m_i and
    // M x_c = sum m_i x_i per component; one reduction adds the processes'
    // sums, rank 0 writes the row.
    void execute(const double t, double) override
    {
      const VectorType &x         = get_position();
      const VectorType &m         = get_mass();
      const auto       &component = get_dof_component();
      const auto       &rigid     = get_rigid_dof();
      const auto       &body      = get_dof_body();
      std::vector<double> sums(4, 0.);
      for (unsigned int i = 0; i < x.locally_owned_size(); ++i)
        if ((rigid.empty() || !rigid[i]) && selected[body[i]])
          {
            if (component[i] == 0)
              sums[0] += m.local_element(i);
            sums[1 + component[i]] += m.local_element(i) * x.local_element(i);
          }
      dealii::Utilities::MPI::sum(sums, get_mpi_communicator(), sums);
      if (!is_root())
        return;
      // The file is noted as this run's before it is opened (a later run
      // in the same directory removes exactly the files a run wrote), and a
      // HistoryFile keeps rows whole, flushes them with the others and
      // lets a checkpoint record its length.
      if (!file.is_open())
        {
          record_output("centre_of_mass.csv");
          file.open(get_output_directory() + "/centre_of_mass.csv");
          file << "time,mass,x,y,z\n";
        }
      file << std::setprecision(15) << t << ',' << sums[0] << ',' << sums[1] / sums[0] << ','
           << sums[2] / sums[0] << ',' << sums[3] / sums[0] << '\n';
    }

    std::vector<HistoryFile *> history_files() override
    {
      return {&file};
    }

  private:
    HistoryFile                file;
    std::vector<unsigned char> selected;
  };

  ANVIL_REGISTER_POSTPROCESSOR_WITH_PARAMETERS(CentreOfMass, "centre of mass",
                                               "centre_of_mass.csv: mass and centre of mass of the "
                                               "deformable bodies, or of those 'Bodies' names (a "
                                               "plugin: doc/extending.md).")
} // namespace anvil::Postprocess
