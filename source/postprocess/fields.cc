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
#include <anvil/element/element_group.h>
#include <anvil/simulator/records.h>
#include <anvil/utilities/vtu_file.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>

namespace anvil::Postprocess
{
  using namespace dealii;

  class Fields : public Interface
  {
  public:
    using Interface::Interface;

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

      // One connected piece per process: the points of its cells (shared
      // by the cells around them), node ids from the scene's vertices
      // and element ids from its coarse cells, the same on any number of
      // processes. Each cell field goes straight into the piece, in the
      // order of the piece's cells (slot), as it is written (float32 as
      // float): a frame holds each value once.
      Vtu::Piece                 piece;
      std::vector<std::int64_t>  point_of(triangulation.n_vertices(), -1);
      std::vector<double>        node_id, u_values, v_values, element_id;
      std::vector<int>           slot(triangulation.n_active_cells(), -1);
      static constexpr unsigned int vtk_order[8] = {0, 1, 3, 2, 4, 5, 7, 6};
      // (The piece's sizes first: arrays grown by push_back would hold up
      // to twice what they need.)
      std::size_t n_points = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : vtk_order)
            if (point_of[cell->vertex_index(v)] < 0)
              point_of[cell->vertex_index(v)] = n_points++;
      std::fill(point_of.begin(), point_of.end(), -1);
      const unsigned int n_owned = triangulation.n_locally_owned_active_cells();
      piece.points.reserve(3 * n_points);
      u_values.reserve(3 * n_points);
      v_values.reserve(3 * n_points);
      node_id.reserve(n_points);
      piece.hexahedra.reserve(8 * n_owned);
      element_id.reserve(n_owned);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            slot[cell->active_cell_index()] = element_id.size();
            element_id.push_back(SimulatorAccess::element_id(cell->active_cell_index()));
            for (const unsigned int v : vtk_order)
              {
                const unsigned int vertex = cell->vertex_index(v);
                if (point_of[vertex] < 0)
                  {
                    point_of[vertex] = node_id.size();
                    node_id.push_back(scene_vertex_index(vertex));
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
      const std::size_t n_cells = element_id.size();
      using Type                = Vtu::Array::Type;
      piece.point_data.push_back({"displacement", 3, Type::float64, std::move(u_values), {}});
      piece.point_data.push_back({"velocity", 3, Type::float64, std::move(v_values), {}});
      piece.point_data.push_back({"node_id", 1, Type::int64, std::move(node_id), {}});
      piece.cell_data.push_back({"element_id", 1, Type::int64, std::move(element_id), {}});
      // A cell field of the piece: float32 in floats, int64 in values.
      const auto field = [&](const std::string &name, const Type type) {
        piece.cell_data.push_back({name, 1, type, {}, {}});
        if (type == Type::float32)
          piece.cell_data.back().floats.assign(n_cells, 0.f);
        else
          piece.cell_data.back().values.assign(n_cells, 0.);
      };
      const char *names[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
      // (Indices into piece.cell_data: a reference would not survive the
      // pushes that follow.)
      const std::size_t body_id = piece.cell_data.size();
      field("body", Type::int64);
      std::size_t stress[6], strain[6];
      for (unsigned int k = 0; k < 6; ++k)
        {
          stress[k] = piece.cell_data.size();
          field(std::string("stress_") + names[k], Type::float32);
          strain[k] = piece.cell_data.size();
          field(std::string("strain_") + names[k], Type::float32);
        }
      const std::size_t von_mises = piece.cell_data.size();
      field("von_mises", Type::float32);
      const std::size_t internal_density = piece.cell_data.size();
      field("internal_energy_density", Type::float32);
      const std::size_t hourglass_density = piece.cell_data.size();
      field("hourglass_energy_density", Type::float32);
      // Scalar history variables of the materials (effective plastic strain,
      // ...), averaged over each element's points, in the order of their
      // names; and the erosion flag.
      std::map<std::string, std::size_t> history_fields;
      for (const auto &group : element_groups)
        for (const auto &name : group.get_material().history_names())
          if (!name.empty() && name.rfind("back_stress", 0) != 0)
            history_fields.emplace(name, 0);
      for (auto &[name, index] : history_fields)
        {
          index = piece.cell_data.size();
          field(name, Type::float32);
        }
      const bool with_eroded =
        n_eroded_elements() > 0 || std::any_of(element_groups.begin(), element_groups.end(),
                                               [](const auto &g) { return g.get_material().erodes(); });
      const std::size_t eroded = piece.cell_data.size();
      if (with_eroded)
        field("eroded", Type::float32);
      const std::size_t rank = piece.cell_data.size();
      field("mpi_rank", Type::int64);
      // The refinement level of each element, where a body is refined.
      const bool        refined = triangulation.n_global_levels() > 1;
      const std::size_t level   = piece.cell_data.size();
      if (refined)
        field("refinement_level", Type::int64);
      const auto cell_value = [&](const std::size_t array, const unsigned int c) -> float & {
        return piece.cell_data[array].floats[slot[c]];
      };

      const double *x = position.begin();
      for (const auto &group : element_groups)
        {
        const auto names = group.get_material().history_names();
        for (unsigned int e = 0; e < group.n_elements(); ++e)
          if (group.element_is_owned(e))
          {
            const unsigned int c = group.element_cell_index(e);
            for (unsigned int k = 0; k < names.size(); ++k)
              if (history_fields.count(names[k]))
                {
                  double mean = 0;
                  for (unsigned int q = 0; q < group.n_quadrature_points(); ++q)
                    mean += group.history_output(e, q, k) /
                            group.n_quadrature_points();
                  cell_value(history_fields[names[k]], c) = mean;
                }
            if (with_eroded)
              cell_value(eroded, c) = group.element_is_eroded(e);
            double             s[6];
            group.cauchy_stress(e, x, s);
            for (unsigned int k = 0; k < 6; ++k)
              cell_value(stress[k], c) = s[k];
            const double p = (s[0] + s[1] + s[2]) / 3.;
            cell_value(von_mises, c) =
              std::sqrt(1.5 * ((s[0] - p) * (s[0] - p) + (s[1] - p) * (s[1] - p) +
                               (s[2] - p) * (s[2] - p) +
                               2. * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])));
            const double V0      = group.element_reference_volume(e);
            cell_value(hourglass_density, c) = group.element_hourglass_energy(e) / V0;
            cell_value(internal_density, c)  = group.element_internal_energy(e) / V0;
          }
        }

      const QMidpoint<3>                 centre;
      FEValues<3>                        fe_values(get_fe(), centre, update_gradients);
      std::vector<Tensor<2, 3>>          grad(1);
      const FEValuesExtractors::Vector   u(0);
      const double                       my_rank = Utilities::MPI::this_mpi_process(mpi_communicator);
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
              cell_value(strain[k], c) = E[ij[k][0]][ij[k][1]];
            piece.cell_data[body_id].values[slot[c]] = cell->material_id();
            piece.cell_data[rank].values[slot[c]]    = my_rank;
            if (refined)
              piece.cell_data[level].values[slot[c]] = cell->level();
          }

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
                           [&](std::ostream &out) {
                             Vtu::write_vtu(out, piece, t, output_count, output_compressed(), &bytes);
                           });
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

    // The frames' bytes over all processes, with the ratio compression
    // gave (a run's own frames: a resumed run counts from its restart).
    void end_of_run(double) override
    {
      const MPI_Comm comm    = get_mpi_communicator();
      const double   raw     = Utilities::MPI::sum(double(bytes.raw), comm);
      const double   written = Utilities::MPI::sum(double(bytes.written), comm);
      if (written > 0)
        get_pcout() << "  fields: " << pvd_records.size() << " frames, arrays " << std::setprecision(3)
                    << raw / 1e6 << " MB, written " << written / 1e6 << " MB"
                    << (output_compressed() ? " (zlib, ratio " : " (uncompressed, ratio ") << raw / written
                    << ")\n";
    }

    void serialize(StateArchive &ar) override
    {
      ar &pvd_records;
    }

  private:
    /** What the VTU arrays held and what was written of them. */
    Vtu::Bytes bytes;

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
