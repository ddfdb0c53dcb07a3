/**
 * @file
 * probe_NAME.csv per probe: displacement and velocity of the probed node (or
 * of the centre of mass of its section, 'Average = section') at time n and
 * the Cauchy stress of the node's element; the first probe's
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
    // (SimulatorAccess::velocity_at_n). A section probe's nodes come the
    // same way, each in its slot of the section's order, so that the mean
    // is summed in one order on any number of processes.
    void execute(const double t, const double dt) override
    {
      const auto          &probes = get_probes();
      const VectorType    &x = get_position(), &X = get_reference_position(), &v = get_velocity();
      constexpr unsigned   n_values = 12;
      std::size_t          n_all    = n_values * probes.size();
      for (const auto &p : probes)
        n_all += 6 * p.section_mass.size();
      std::vector<double> values(n_all, 0.);
      auto motion = [&](const unsigned long x_dof, double *u_v) {
        for (unsigned int d = 0; d < 3; ++d)
          {
            const auto g = x_dof + d;
            u_v[d]       = x(g) - X(g);
            u_v[3 + d]   = velocity_at_n(v.get_partitioner()->global_to_local(g), dt);
          }
      };
      std::size_t section_start = n_values * probes.size();
      for (unsigned int p = 0; p < probes.size(); ++p)
        {
          if (x.locally_owned_elements().is_element(probes[p].x_dof))
            {
              motion(probes[p].x_dof, &values[n_values * p]);
              if (probes[p].group >= 0)
                get_element_groups()[probes[p].group].cauchy_stress(probes[p].element, x.begin(),
                                                                    &values[n_values * p + 6]);
            }
          for (const auto &[slot, x_dof] : probes[p].owned_section_dofs)
            motion(x_dof, &values[section_start + 6 * slot]);
          section_start += 6 * probes[p].section_mass.size();
        }
      if (!probes.empty())
        dealii::Utilities::MPI::sum(values, get_mpi_communicator(), values);
      // The centre of mass of each section, in place of its node's motion.
      section_start = n_values * probes.size();
      for (unsigned int p = 0; p < probes.size(); ++p)
        if (!probes[p].section_mass.empty())
          {
            const auto &m = probes[p].section_mass;
            double      mean[6] = {}, total = 0;
            for (unsigned int i = 0; i < m.size(); ++i, section_start += 6)
              {
                total += m[i];
                for (unsigned int k = 0; k < 6; ++k)
                  mean[k] += m[i] * values[section_start + k];
              }
            for (unsigned int k = 0; k < 6; ++k)
              values[n_values * p + k] = mean[k] / total;
          }
      values.resize(n_values * probes.size());
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
