/**
 * @file
 * bodies.csv at the end of a run: per body, elements, eroded elements, peak
 * effective plastic strain (of the intact and of all elements), current
 * bounding box, dissipated energy and reference volume.
 */
#include <anvil/postprocess/interface.h>
#include <anvil/mesh/body.h>
#include <anvil/element/element_group.h>
#include <anvil/simulator/records.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <fstream>
#include <iomanip>

namespace anvil::Postprocess
{
  using namespace dealii;

  class Bodies : public Interface
  {
  public:
    using Interface::Interface;

    void end_of_run(double) override
    {
      const auto        &bodies           = get_bodies();
      const auto        &element_groups   = get_element_groups();
      const auto        &group_body       = get_group_body();
      const auto        &dof_body         = get_dof_body();
      const auto        &dof_component    = get_dof_component();
      const VectorType  &position         = get_position();
      const MPI_Comm     mpi_communicator = get_mpi_communicator();
      const std::string &output_directory = get_output_directory();
      const unsigned int  nb = bodies.size();
      std::vector<double> count(3 * nb, 0.), peak(2 * nb, 0.), lo(3 * nb, 1e300), hi(3 * nb, -1e300);
      std::vector<double> dissipated(nb, 0.), volume(nb, 0.);
      for (unsigned int g = 0; g < element_groups.size(); ++g)
        {
          const auto        &group = element_groups[g];
          const unsigned int b     = group_body[g];
          const auto  names = group.get_material().history_names();
          const auto  it    = std::find(names.begin(), names.end(), "effective_plastic_strain");
          const int   id    = group.get_material().dissipation_index();
          for (unsigned int e = 0; e < group.n_elements(); ++e)
            if (group.element_is_owned(e))
              {
                const bool eroded = group.element_is_eroded(e);
                if (id >= 0)
                  for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
                    dissipated[b] += group.history_variable(e, q, id) *
                                     group.element_reference_volume(e) /
                                     group.n_quadrature_points();
                count[3 * b] += 1;
                count[3 * b + 1] += eroded;
                volume[b] += group.element_reference_volume(e);
                if (it == names.end())
                  continue;
                double eps_p = 0;
                for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
                  eps_p += group.history_variable(e, q, it - names.begin()) /
                           group.n_quadrature_points();
                if (!eroded)
                  peak[2 * b] = std::max(peak[2 * b], eps_p);
                peak[2 * b + 1] = std::max(peak[2 * b + 1], eps_p);
              }
        }
      for (unsigned int i = 0; i < position.locally_owned_size(); ++i)
        {
          const unsigned int b = dof_body[i], d = dof_component[i];
          lo[3 * b + d]        = std::min(lo[3 * b + d], position.local_element(i));
          hi[3 * b + d]        = std::max(hi[3 * b + d], position.local_element(i));
        }
      Utilities::MPI::sum(count, mpi_communicator, count);
      Utilities::MPI::sum(dissipated, mpi_communicator, dissipated);
      Utilities::MPI::sum(volume, mpi_communicator, volume);
      Utilities::MPI::max(peak, mpi_communicator, peak);
      Utilities::MPI::min(lo, mpi_communicator, lo);
      Utilities::MPI::max(hi, mpi_communicator, hi);
      if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
        return;
      record_output("bodies.csv");
      std::ofstream out(output_directory + "/bodies.csv");
      out << "body,elements,eroded,peak_effective_plastic_strain_intact,"
             "peak_effective_plastic_strain,xmin,ymin,zmin,xmax,ymax,zmax,"
             "dissipated_energy,reference_volume\n"
          << std::setprecision(12);
      for (unsigned int b = 0; b < nb; ++b)
        out << bodies[b].name << ',' << count[3 * b] << ',' << count[3 * b + 1] << ','
            << peak[2 * b] << ',' << peak[2 * b + 1] << ',' << lo[3 * b] << ',' << lo[3 * b + 1]
            << ',' << lo[3 * b + 2] << ',' << hi[3 * b] << ',' << hi[3 * b + 1] << ','
            << hi[3 * b + 2] << ',' << dissipated[b] << ',' << volume[b] << '\n';
    }
  };

  ANVIL_REGISTER_POSTPROCESSOR(Bodies, "bodies", "bodies.csv: a line per body at the end of a run.")
} // namespace anvil::Postprocess
