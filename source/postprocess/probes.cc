/**
 * @file
 * probe_NAME.csv per probe: displacement and velocity of the probed node at
 * time n and the Cauchy stress of its element; the first probe's
 * displacement feeds summary.csv and the end criterion.
 */
#include <anvil/postprocess/interface.h>
#include <anvil/element/element_group.h>
#include <anvil/simulator/records.h>

#include <deal.II/base/mpi.h>

#include <iomanip>

namespace anvil::Postprocess
{
  class Probes : public Interface
  {
  public:
    using Interface::Interface;

    // The values come from the process that owns the probed node (the
    // others add zeros); velocities at n are v^{n+1/2} - dt/2 a^n
    // (SimulatorAccess::velocity_at_n).
    void execute(const double t, const double dt) override
    {
      const auto          &probes = get_probes();
      const VectorType    &x = get_position(), &X = get_reference_position(), &v = get_velocity();
      constexpr unsigned   n_values = 12;
      std::vector<double>  values(n_values * probes.size(), 0.);
      for (unsigned int p = 0; p < probes.size(); ++p)
        if (x.locally_owned_elements().is_element(probes[p].x_dof))
          {
            for (unsigned int d = 0; d < 3; ++d)
              {
                const auto g                 = probes[p].x_dof + d;
                values[n_values * p + d]     = x(g) - X(g);
                values[n_values * p + 3 + d] = velocity_at_n(v.get_partitioner()->global_to_local(g), dt);
              }
            if (probes[p].group >= 0)
              get_element_groups()[probes[p].group].cauchy_stress(probes[p].element, x.begin(),
                                                                  &values[n_values * p + 6]);
          }
      if (!probes.empty())
        dealii::Utilities::MPI::sum(values, get_mpi_communicator(), values);
      if (!is_root())
        return;
      record_probe_summary(values);
      if (files.empty())
        for (const auto &p : probes)
          {
            record_output("probe_" + p.name + ".csv");
            files.emplace_back(get_output_directory() + "/probe_" + p.name + ".csv");
            files.back() << "time,ux,uy,uz,vx,vy,vz,stress_xx,stress_yy,stress_zz,stress_xy,stress_yz,stress_xz\n";
          }
      for (unsigned int p = 0; p < probes.size(); ++p)
        {
          files[p] << std::setprecision(12) << t;
          for (unsigned int k = 0; k < n_values; ++k)
            files[p] << ',' << values[n_values * p + k];
          files[p] << '\n';
        }
    }
  };

  ANVIL_REGISTER_POSTPROCESSOR(Probes, "probes",
                               "probe_NAME.csv: displacement, velocity and element stress at each 'Probe NAME'.")
} // namespace anvil::Postprocess
