/**
 * @file
 * momentum.csv: the linear momentum of each body and of the scene at time n
 * (a conservation check: constant without supports and gravity).
 */
#include <anvil/boundary_conditions/constraints.h>
#include <anvil/postprocess/interface.h>
#include <anvil/mesh/body.h>
#include <anvil/simulator/force_contributor.h>
#include <anvil/simulator/records.h>

#include <deal.II/base/mpi.h>

#include <iomanip>

namespace anvil::Postprocess
{
  class Momentum : public Interface
  {
  public:
    using Interface::Interface;

    // sum m v over the owned dofs at time n, v^{n+1/2} - dt/2 a^n (a held
    // dof's prescribed velocity: its reaction is part of a^n); the
    // families add what they move themselves (a rigid body's M V, the
    // bars' own nodes).
    void execute(const double t, const double dt) override
    {
      const auto       &bodies    = get_bodies();
      const auto       &rigid_dof = get_rigid_dof();
      const auto       &dof_body = get_dof_body(), &dof_component = get_dof_component();
      const VectorType &v = get_velocity(), &f = get_force(), &m = get_mass();
      std::vector<double> momentum(3 * bodies.size(), 0.);
      for (unsigned int i = 0; i < v.locally_owned_size(); ++i)
        if (rigid_dof.empty() || !rigid_dof[i])
          momentum[3 * dof_body[i] + dof_component[i]] +=
            is_held(i) ? m.local_element(i) * velocity_at_n(i, dt) :
                         m.local_element(i) * v.local_element(i) - 0.5 * dt * (f.local_element(i) + get_constraints().damping_force(i));
      dealii::Utilities::MPI::sum(momentum, get_mpi_communicator(), momentum);
      for (const auto *family : get_families())
        family->add_momentum(dt, momentum);
      if (!is_root())
        return;
      if (!file.is_open())
        {
          record_output("momentum.csv");
          file.open(get_output_directory() + "/momentum.csv");
          file << "time";
          for (const auto &b : bodies)
            file << ',' << b.name << "_px," << b.name << "_py," << b.name << "_pz";
          file << ",px,py,pz\n";
        }
      file << std::setprecision(15) << t;
      double total[3] = {0, 0, 0};
      for (unsigned int k = 0; k < momentum.size(); ++k)
        {
          file << ',' << momentum[k];
          total[k % 3] += momentum[k];
        }
      file << ',' << total[0] << ',' << total[1] << ',' << total[2] << '\n';
    }

    std::vector<HistoryFile *> history_files() override
    {
      return {&file};
    }

  private:
    HistoryFile file;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Momentum, "momentum", "momentum.csv: linear momentum per body and in total.")
} // namespace anvil::Postprocess
