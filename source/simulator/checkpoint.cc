/**
 * @file
 * Checkpoint and restart. The mesh and every constant of the scene are
 * rebuilt from the scene file as in the first run, on any number of
 * processes; the checkpoint holds what the steps changed, each process's
 * share by scene-wide keys (StateArchive::keyed()): nodal
 * state, element stresses and histories, hourglass state, contact history
 * and search trees, rigid bodies, bars, energies, the loop's schedule and
 * the lengths of the history files, which a resumed run cuts back to and
 * appends to. The resumed run's histories and fields equal an uninterrupted
 * run's bitwise (tests/verification/restart.py).
 */
#include <anvil/simulator/simulator.h>
#include <anvil/utilities/input_error.h>

#include <deal.II/base/mpi.h>

#include <boost/crc.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace anvil
{
  using namespace dealii;
  namespace fs = std::filesystem;

  namespace
  {
    // Every state file ends with a trailer: a tag, the length of the state
    // before it and the state's CRC-32, so that a file cut short, grown or
    // with a flipped byte is refused before a byte of it is read as state
    // (a damaged length field would otherwise allocate at random).
    constexpr char          trailer_tag[8] = {'A', 'N', 'V', 'I', 'L', 'C', 'K', '1'};
    constexpr std::size_t   trailer_size   = sizeof(trailer_tag) + sizeof(std::uint64_t) + sizeof(std::uint32_t);

    std::uint32_t crc32(const std::string &data, const std::size_t n)
    {
      boost::crc_32_type crc;
      crc.process_bytes(data.data(), n);
      return crc.checksum();
    }

    std::string with_trailer(const std::string &state)
    {
      std::string         out = state;
      const std::uint64_t n   = state.size();
      const std::uint32_t c   = crc32(state, state.size());
      out.append(trailer_tag, sizeof(trailer_tag));
      out.append(reinterpret_cast<const char *>(&n), sizeof(n));
      out.append(reinterpret_cast<const char *>(&c), sizeof(c));
      return out;
    }

    /** The state of a file read whole, or an empty string and @p failure
        saying what is wrong with it. */
    std::string without_trailer(std::string data, std::string &failure)
    {
      if (data.size() < trailer_size ||
          data.compare(data.size() - trailer_size, sizeof(trailer_tag), trailer_tag, sizeof(trailer_tag)) != 0)
        {
          failure = "it is cut short or is no checkpoint of this Anvil (no checksum at its end)";
          return {};
        }
      std::uint64_t n;
      std::uint32_t c;
      std::memcpy(&n, data.data() + data.size() - trailer_size + sizeof(trailer_tag), sizeof(n));
      std::memcpy(&c, data.data() + data.size() - sizeof(c), sizeof(c));
      if (n != data.size() - trailer_size)
        {
          failure = "its length does not match the length it records (" + std::to_string(data.size() - trailer_size) +
                    " bytes of state, " + std::to_string(n) + " recorded)";
          return {};
        }
      if (crc32(data, n) != c)
        {
          failure = "its checksum does not match: the file is damaged";
          return {};
        }
      data.resize(n);
      return data;
    }
  } // namespace



  namespace
  {
    /** A family's or a postprocessor's state in a checkpoint, under its
        name and the version of its record. */
    struct Record
    {
      std::string  key;
      unsigned int version = 0;
      std::string  state;

      void serialize(StateArchive &ar)
      {
        ar &key &version &state;
      }
    };
  } // namespace


  namespace
  {
    /** A checkpoint's info: the number of processes that wrote it (its
        files state.0.bin, ...; -1: no checkpoint) and its state layout
        (1 where unstated). */
    std::pair<int, int> read_info(const std::string &dir)
    {
      int n = -1, layout = 1;
      if (std::ifstream info(dir + "/info"); info)
        {
          std::string word;
          info >> word >> n;
          for (std::string key, value; info >> key >> value;)
            if (key == "layout")
              layout = std::atoi(value.c_str());
        }
      return {n, layout};
    }
  } // namespace


  RecordMismatch::RecordMismatch(const std::string &what)
    : std::runtime_error(what)
  {}


  // The driver's own state, then one record per family and postprocessor,
  // keyed by name with its version: a record that changes (a field added)
  // raises its own version, and a checkpoint holding the old one is refused
  // by name (RecordMismatch) while the other records stay readable.
  void Simulator::serialize(StateArchive &ar)
  {
    // The nodal state by dof key (the owned dofs of any partition).
    {
      VectorType *const nodal[] = {&position, &velocity, &force, &mass, &balance.good_position,
                                   &balance.good_velocity};
      if (ar.is_loading() && ar.element_transfer() != nullptr)
        load_transferred_nodes(ar);
      else
        ar.keyed_items("nodes", dof_key, std::size(nodal), [&](const std::size_t i, RecordCursor &io) {
          for (auto *v : nodal)
            io(v->local_element(i));
        });
    }
    ar &balance.good_time;
    ar &energies &balance.initial_energy &balance.balance_error &balance.energy_scale &critical_dt &balance.pending_step_change
      &balance.step_change_steps &current_dt &step_number &time &balance.growth_steps &balance.negative_steps &balance.first_dt &output.output_count
          &summary &loop;

    struct Part
    {
      std::string                              key;
      unsigned int                             version;
      std::function<void(StateArchive &)> io;
    };
    std::vector<Part> parts;
    for (auto *family : contributors())
      parts.push_back({"family '" + family->name() + "'", family->state_version(),
                       [family](StateArchive &a) { family->serialize(a); }});
    for (auto &postprocessor : postprocessors)
      parts.push_back({"postprocessor '" + postprocessor->plugin_name + "'", postprocessor->state_version(),
                       [p = postprocessor.get()](StateArchive &a) { p->serialize(a); }});
    std::vector<Record> records;
    if (!ar.is_loading())
      {
        for (const auto &part : parts)
          {
            StateArchive sub = ar.nested(part.key);
            part.io(sub);
            records.push_back({part.key, part.version, sub.data()});
          }
        ar &records;
        return;
      }
    ar &records;
    for (const auto &part : parts)
      {
        const auto record =
          std::find_if(records.begin(), records.end(), [&](const Record &r) { return r.key == part.key; });
        if (record == records.end())
          throw RecordMismatch("it holds no record of the " + part.key);
        if (record->version != part.version)
          throw RecordMismatch("its record of the " + part.key + " is version " + std::to_string(record->version) +
                               ", this build reads version " + std::to_string(part.version));
        StateArchive sub = ar.nested(part.key, record->state);
        part.io(sub);
        if (!sub.exhausted())
          throw RecordMismatch("its record of the " + part.key + " is longer than version " +
                               std::to_string(part.version) + " of it");
      }
  }


  // A stage that takes bodies out (the hammer once the impact is over):
  // what they held leaves the balance as 'removed' energy, booked once, at
  // the start of the stage (@p book_energy; not for a run that starts
  // without them).
  void Simulator::remove_inactive_bodies(const bool book_energy)
  {
    const double kinetic = rigid_bodies->remove_inactive(book_energy);
    if (book_energy)
      {
        energies.removed += kinetic;
        energies.kinetic -= kinetic;
      }
    const double springs = contact->remove_inactive();
    if (book_energy)
      energies.removed += springs;
    velocity.update_ghost_values();
  }


  void Simulator::write_checkpoint()
  {
    TimerOutput::Scope t(*timer, "checkpoint");
    const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    const std::string  dir  = parameters.output_directory + "/checkpoint";
    // The histories first: the checkpoint records how long they are.
    flush_histories();
    if (Utilities::MPI::max(output.failure.empty() ? 0 : 1, mpi_communicator) != 0)
      throw OutputError(output.failure.empty() ? "a history file could not be written (see rank 0)" :
                                                 output.failure);
    StateArchive ar;
    serialize(ar);
    // The open histories (rank 0's): file name and length; -1: not open.
    std::vector<long>        lengths;
    std::vector<std::string> names;
    std::vector<unsigned int> counts;
    for (auto &postprocessor : postprocessors)
      counts.push_back(postprocessor->history_files().size());
    for (auto *family : contributors())
      counts.push_back(family->history_files().size());
    for (auto *f : history_files())
      {
        lengths.push_back(f->is_open() ? f->bytes_written() : -1);
        names.push_back(f->is_open() ? fs::path(f->file()).filename().string() : "");
      }
    ar &counts &lengths &names;

    if (rank == 0)
      {
        record_output("checkpoint");
        std::error_code ec;
        fs::remove_all(dir + ".new", ec);
        fs::create_directories(dir + ".new", ec);
      }
    MPI_Barrier(mpi_communicator);
    std::string failure;
    try
      {
        write_atomically(dir + ".new/state." + std::to_string(rank) + ".bin", with_trailer(ar.file_data()));
      }
    catch (const OutputError &e)
      {
        failure = e.what();
      }
    if (Utilities::MPI::max(failure.empty() ? 0 : 1, mpi_communicator) != 0)
      throw OutputError(failure.empty() ? "a checkpoint file could not be written (see the other ranks)" :
                                          failure);
    if (rank == 0)
      {
        std::ostringstream info;
        info << "processes " << Utilities::MPI::n_mpi_processes(mpi_communicator) << "\ntime "
             << std::setprecision(17) << time << "\nstep " << step_number << "\nlayout "
             << checkpoint_layout << "\n";
        if (!adapt_rounds.empty())
          write_adaptation(dir + ".new", mesh_rounds);
        write_atomically(dir + ".new/info", info.str());
        // The previous checkpoint goes only once the new one is complete.
        std::error_code ec;
        fs::remove_all(dir + ".old", ec);
        if (fs::exists(dir))
          fs::rename(dir, dir + ".old", ec);
        fs::rename(dir + ".new", dir, ec);
        if (ec)
          failure = "cannot rename " + dir + ".new to " + dir + ": " + ec.message();
        fs::remove_all(dir + ".old", ec);
      }
    if (Utilities::MPI::max(failure.empty() ? 0 : 1, mpi_communicator) != 0)
      throw OutputError(failure.empty() ? "the checkpoint could not be completed (see rank 0)" : failure);
    output.last_checkpoint_wall = std::chrono::steady_clock::now();
    pcout << "  checkpoint at t = " << time << " s, step " << step_number << std::endl;
  }


  void Simulator::resume_output_directory()
  {
    check_checkpoint(parameters.output_directory + "/checkpoint");
    // The files this run's first part wrote stay on the list.
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ifstream list(parameters.output_directory + "/anvil_files.txt");
        std::string   name;
        while (std::getline(list, name))
          if (!name.empty())
            output.recorded_outputs.insert(name);
      }
  }


  // 'layout' names how the state is laid out (1, unstated: per process,
  // element ids in p4est's tree order; 2: the scene's cell order, the fully
  // distributed mesh; 3: the run summary with every probe's figures; 6:
  // the penalty pairs' approach; 7: Johnson-Cook's thermal factor; 8: the
  // families and postprocessors in records keyed by name, each with its
  // own version; 11: each process's share in keyed tables, so that any
  // number of processes resumes it). A checkpoint of another layout would
  // load its state wrongly.
  void Simulator::check_checkpoint(const std::string &dir) const
  {
    const auto [n, layout] = read_info(dir);
    if (n < 0)
      throw InputError(parameters.scene_file + ": --resume: no checkpoint in '" + dir +
                       "' (set 'Checkpoint interval' or stop a run with SIGTERM to write one)");
    if (layout != checkpoint_layout)
      throw InputError(parameters.scene_file + ": --resume: the checkpoint in '" + dir + "' has state layout " +
                       std::to_string(layout) + " (written by an earlier Anvil, whose state was laid " +
                       "out otherwise); this build reads layout " + std::to_string(checkpoint_layout) +
                       ": run the scene again from its start");
  }



  // Every process reads every file of the checkpoint: the stream of the
  // writers' first process (what all processes hold alike) and the keyed
  // tables of all of them, merged, in which it finds the items of its own
  // share, whatever the number of processes that wrote them.
  void Simulator::load_checkpoint(const std::string &directory, const bool new_stage)
  {
    const unsigned int        rank    = Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int        writers = std::max(read_info(directory).first, 0);
    std::string               stream, refused, damage;
    std::vector<KeyedTables>  parts;
    for (unsigned int w = 0; w < writers && refused.empty(); ++w)
      {
        const std::string  file = directory + "/state." + std::to_string(w) + ".bin";
        std::ifstream      in(file, std::ios::binary);
        std::ostringstream data;
        data << in.rdbuf();
        if (!in)
          {
            refused = file;
            damage  = "it cannot be read";
            break;
          }
        const std::string state = without_trailer(data.str(), damage);
        if (!damage.empty())
          {
            refused = file;
            break;
          }
        try
          {
            auto [own_stream, tables] = StateArchive::split_file_data(state);
            if (w == 0)
              stream = std::move(own_stream);
            parts.push_back(std::move(tables));
          }
        catch (const std::exception &e)
          {
            refused = file;
            damage  = e.what();
          }
      }
    std::shared_ptr<const KeyedTables> merged;
    if (refused.empty())
      try
        {
          merged = StateArchive::merge(parts);
        }
      catch (const std::exception &e)
        {
          refused = directory;
          damage  = e.what();
        }
    parts.clear();
    if (Utilities::MPI::max(refused.empty() ? 0 : 1, mpi_communicator) != 0)
      throw InputError(parameters.scene_file + ": --resume: the checkpoint file " +
                       (refused.empty() ? std::string("of another rank") : refused) + " is refused: " +
                       (refused.empty() ? std::string("it is damaged") : damage) +
                       " (run the scene again from its start, or from an intact checkpoint)");

    StateArchive              ar(stream, merged);
    if (transferring)
      ar.set_transfer(element_sources);
    std::vector<unsigned int> counts;
    std::vector<long>         lengths;
    std::vector<std::string>  names;
    std::string               failure;
    int                       mismatch = 0;
    try
      {
        serialize(ar);
        ar &counts &lengths &names;
        if (!ar.exhausted())
          failure = "longer than the state of this scene";
      }
    catch (const RecordMismatch &e)
      {
        failure  = e.what();
        mismatch = 1;
      }
    catch (const std::exception &e)
      {
        failure = e.what();
      }
    if (Utilities::MPI::max(mismatch, mpi_communicator) != 0)
      throw InputError(parameters.scene_file + ": --resume: the checkpoint in '" + directory +
                       "' was written by another version of Anvil (" +
                       (failure.empty() ? std::string("on another rank") : failure) +
                       "): run the scene again from its start");
    if (Utilities::MPI::max(failure.empty() ? 0 : 1, mpi_communicator) != 0)
      throw InputError(parameters.scene_file + ": --resume: the checkpoint does not fit this scene (" +
                       (failure.empty() ? std::string("on another rank") : failure) +
                       "); was the scene changed since it was written?");
    position.update_ghost_values();
    velocity.update_ghost_values();
    mass.update_ghost_values();
    if (transferring)
      {
        const KeyedTable *old_nodes = ar.table("nodes");
        finish_transfer(old_nodes != nullptr ? *old_nodes : KeyedTable());
      }
    if (new_stage)
      loop.stage_start = time;
    if (parameters.duration > 0)
      parameters.end_time = loop.stage_start + parameters.duration;
    if (new_stage)
      {
        // A stage of its own: its histories, frames and figures start
        // here; the energies (and the balance) continue.
        remove_inactive_bodies(true);
        summary = RunSummary();
        for (auto *family : contributors())
          family->start_stage();
        for (auto &postprocessor : postprocessors)
          postprocessor->start_stage();
        output.output_count       = 0;
        loop.next_output   = time + parameters.output_interval;
        loop.next_history  = time;
        loop.next_progress = time;
        loop.quiet_end     = false;
        output.last_flush         = std::chrono::steady_clock::now();
        pcout << "  a new stage from the checkpoint in " << directory << " at t = " << time << " s, step "
              << step_number << "; it ends at t = " << parameters.end_time << " s" << std::endl;
        output_results(time, "solution");
        return;
      }

    // The histories: cut back to their length at the checkpoint, then
    // appended to (rank 0).
    if (rank == 0)
      {
        unsigned int c = 0;
        for (auto &postprocessor : postprocessors)
          if (c < counts.size())
            postprocessor->resize_history_files(counts[c++]);
        for (auto *family : contributors())
          if (c < counts.size())
            family->resize_history_files(counts[c++]);
        const auto files = history_files();
        for (unsigned int k = 0; k < files.size() && k < lengths.size(); ++k)
          if (lengths[k] >= 0)
            files[k]->resume(parameters.output_directory + "/" + names[k], lengths[k]);
      }
    output.last_flush = std::chrono::steady_clock::now();
    if (run_wall_start)
      {
        const auto counts = Utilities::MPI::gather(mpi_communicator, triangulation.n_locally_owned_active_cells());
        pcout << "  the run goes on from t = " << time << " s on the new partition (elements per process:";
        for (const auto n : counts)
          pcout << ' ' << n;
        pcout << ")" << std::endl;
      }
    else
      pcout << "  resumed from the checkpoint at t = " << time << " s, step " << step_number << std::endl;
  }
} // namespace anvil
