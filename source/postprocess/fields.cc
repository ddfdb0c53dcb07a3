/**
 * @file
 * The fields: one VTU piece per process and a PVTU record per frame
 * (displacement, velocity, node and element ids, stresses, Green-Lagrange
 * strains, von Mises stress, energy densities, the materials' history
 * variables, erosion, rank), and solution.pvd, the time series, rewritten
 * (atomically) with each frame. Output is not on the hot path: strains come
 * from FEValues at the cell centre (the tutorial path), stresses from the
 * element groups.
 */
#include <anvil/postprocess/interface.h>
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/vtu_file.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace anvil::Postprocess
{
  using namespace dealii;

  class Fields : public Interface
  {
  public:
    using Interface::Interface;

    /** Frames before the summaries at the end of a run. */
    int order() const override
    {
      return 10;
    }

    void write_frame(const double t, const std::string &basename, const unsigned int output_count) override
    {
      const auto        &triangulation    = get_triangulation();
      const auto        &dof_handler      = get_dof_handler();
      const auto        &element_groups   = get_element_groups();
      const VectorType  &position         = get_position();
      const VectorType  &reference_position = get_reference_position();
      const VectorType  &velocity         = get_velocity();
      const MPI_Comm     mpi_communicator = get_mpi_communicator();
      const std::string &output_directory = get_output_directory();
      VectorType         displacement(position);
      displacement -= reference_position;
      displacement.update_ghost_values();

      const unsigned int    n_cells = triangulation.n_active_cells();
      std::vector<Vector<float>> stress(6, Vector<float>(n_cells));
      std::vector<Vector<float>> strain(6, Vector<float>(n_cells));
      Vector<float> von_mises(n_cells), hourglass_density(n_cells), internal_density(n_cells);
      Vector<float> body_id(n_cells), rank(n_cells);
      const float   my_rank = Utilities::MPI::this_mpi_process(mpi_communicator);

      // Scalar history variables of the materials (effective plastic strain,
      // ...), averaged over each element's points; and the erosion flag.
      std::map<std::string, Vector<float>> history_fields;
      for (const auto &group : element_groups)
        for (const auto &name : group.get_material().history_names())
          if (!name.empty() && name.rfind("back_stress", 0) != 0)
            history_fields.emplace(name, Vector<float>(n_cells));
      Vector<float> eroded(n_cells);

      const double *x = position.begin();
      for (const auto &group : element_groups)
        {
        const auto names = group.get_material().history_names();
        for (unsigned int e = 0; e < group.n_elements(); ++e)
          if (group.element_is_owned(e))
          {
            for (unsigned int k = 0; k < names.size(); ++k)
              if (history_fields.count(names[k]))
                {
                  double mean = 0;
                  for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
                    mean += group.history_output(e, q, k) /
                            group.n_quadrature_points();
                  history_fields[names[k]][group.element_cell_index(e)] = mean;
                }
            eroded[group.element_cell_index(e)] = group.element_is_eroded(e);
            const unsigned int c = group.element_cell_index(e);
            double             s[6];
            group.cauchy_stress(e, x, s);
            for (unsigned int k = 0; k < 6; ++k)
              stress[k][c] = s[k];
            const double p = (s[0] + s[1] + s[2]) / 3.;
            von_mises[c]   = std::sqrt(1.5 * ((s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) +
                                            (s[2] - p) * (s[2] - p) +
                                            2. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
            const double V0      = group.element_reference_volume(e);
            hourglass_density[c] = group.element_hourglass_energy(e) / V0;
            internal_density[c]  = group.element_internal_energy(e) / V0;
          }
        }

      const QMidpoint<3>                 centre;
      FEValues<3>                        fe_values(get_fe(), centre, update_gradients);
      std::vector<Tensor<2, 3>>          grad(1);
      const FEValuesExtractors::Vector   u(0);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const unsigned int c = cell->active_cell_index();
            fe_values.reinit(cell);
            fe_values[u].get_function_gradients(displacement, grad);
            const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad[0];
            const Tensor<2, 3> E = 0.5 * (transpose(F) * F - unit_symmetric_tensor<3>());
            const unsigned int ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
            for (unsigned int k = 0; k < 6; ++k)
              strain[k][c] = E[ij[k][0]][ij[k][1]];
            body_id[c] = cell->material_id();
            rank[c]    = my_rank;
          }

      // One connected piece per process: the points of its cells (shared
      // by the cells around them), node ids from the scene's coarse vertices
      // and element ids from its coarse cells, the same on any number of
      // processes.
      Vtu::Piece                 piece;
      std::vector<std::int64_t>  point_of(triangulation.n_vertices(), -1);
      std::vector<double>        node_id, u_values, v_values, element_id;
      std::vector<unsigned int>  cells;
      static constexpr unsigned int vtk_order[8] = {0, 1, 3, 2, 4, 5, 7, 6};
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cells.push_back(cell->active_cell_index());
            element_id.push_back(cell->id().get_coarse_cell_id());
            for (const unsigned int v : vtk_order)
              {
                const unsigned int vertex = cell->vertex_index(v);
                if (point_of[vertex] < 0)
                  {
                    point_of[vertex] = node_id.size();
                    node_id.push_back(vertex);
                    for (unsigned int d = 0; d < 3; ++d)
                      {
                        piece.points.push_back(cell->vertex(v)[d]);
                        const auto dof = cell->vertex_dof_index(v, d);
                        u_values.push_back(displacement(dof));
                        v_values.push_back(velocity(dof));
                      }
                  }
                piece.hexahedra.push_back(point_of[vertex]);
              }
          }
      using Type = Vtu::Array::Type;
      piece.point_data.push_back({"displacement", 3, Type::float64, u_values});
      piece.point_data.push_back({"velocity", 3, Type::float64, v_values});
      piece.point_data.push_back({"node_id", 1, Type::int64, node_id});
      piece.cell_data.push_back({"element_id", 1, Type::int64, element_id});
      auto add = [&](const std::string &name, const Vector<float> &field, const Type type) {
        std::vector<double> values(cells.size());
        for (unsigned int i = 0; i < cells.size(); ++i)
          values[i] = field[cells[i]];
        piece.cell_data.push_back({name, 1, type, values});
      };
      add("body", body_id, Type::int64);
      const char *names[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
      for (unsigned int k = 0; k < 6; ++k)
        {
          add(std::string("stress_") + names[k], stress[k], Type::float32);
          add(std::string("strain_") + names[k], strain[k], Type::float32);
        }
      add("von_mises", von_mises, Type::float32);
      add("internal_energy_density", internal_density, Type::float32);
      add("hourglass_energy_density", hourglass_density, Type::float32);
      for (const auto &[name, field] : history_fields)
        add(name, field, Type::float32);
      if (n_eroded_elements() > 0 || std::any_of(element_groups.begin(), element_groups.end(), [](const auto &g) {
            return g.get_material().erodes();
          }))
        add("eroded", eroded, Type::float32);
      add("mpi_rank", rank, Type::int64);

      // Each process its piece, rank 0 the record naming them.
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
      const std::string  frame =
        basename == "solution" ? basename + "_" + Utilities::int_to_string(output_count, 4) : basename;
      record_output(frame + ".pvtu");
      std::vector<std::string> files;
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          files.push_back(frame + "." + std::to_string(r) + ".vtu");
          record_output(files.back());
        }
      std::string failure;
      try
        {
          write_atomically(output_directory + "/" +
                             files[Utilities::MPI::this_mpi_process(mpi_communicator)],
                           [&](std::ostream &out) { Vtu::write_vtu(out, piece, t, output_count); });
        }
      catch (const OutputError &e)
        {
          failure = e.what();
        }
      if (Utilities::MPI::max(failure.empty() ? 0 : 1, mpi_communicator) != 0)
        throw OutputError(failure.empty() ? "a VTU piece could not be written on another process" :
                                            failure);
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        write_atomically(output_directory + "/" + frame + ".pvtu", Vtu::pvtu_text(piece, files));
      if (basename == "solution")
        {
          pvd_records.emplace_back(t, frame + ".pvtu");
          write_frame_index();
        }
    }

    void start_stage() override
    {
      pvd_records.clear();
    }

    void serialize(StateArchive &ar) override
    {
      ar &pvd_records;
    }

  private:
    /** solution.pvd: the frames so far (time, PVTU file). */
    void write_frame_index()
    {
      if (!is_root())
        return;
      record_output("solution.pvd");
      write_atomically(get_output_directory() + "/solution.pvd", Vtu::pvd_text(pvd_records));
    }

    std::vector<std::pair<double, std::string>> pvd_records;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Fields, "fields", "the VTU frames of the fields and solution.pvd.")
} // namespace anvil::Postprocess
