/**
 * @file
 * The solid bodies of a scene as one family: one element group per body
 * (and one for its 'Full integration region'), their lumped mass, their
 * internal, hourglass and bulk-viscosity forces and stable step, erosion,
 * and their part of a checkpoint (seed sections 2-3).
 */
#pragma once

#include <anvil/element/element_group.h>
#include <anvil/simulator/force_contributor.h>

#include <array>

namespace anvil::Element
{
  class SolidBodies : public ForceContributor
  {
  public:
    using ForceContributor::ForceContributor;

    std::string name() const override
    {
      return "element forces";
    }
    bool empty() const override
    {
      return element_groups.empty();
    }
    /** The element groups: every process holds its owned cells and one
        layer of ghost cells, in the order of their coarse-cell index. */
    void setup() override;
    /** Row-sum lumping of the consistent mass (seed Eq. (35)), and the
        ratio that lowers the stable step of an element with a light node. */
    void add_mass(VectorType &mass) override;
    /** Every deformable group's forces at time n; this process's smallest
        element step (the Simulator takes the minimum over processes). No
        communication: the energy increments are summed over the processes
        and booked by finish_forces(). */
    double add_forces(double dt) override;
    /** Sum the elements' energy increments over the processes and book
        them; when elements eroded this
        step, gather their ids (returned, sorted, scene-wide: every
        process the same) and erosion.csv's rows (rank 0). */
    std::vector<unsigned long> finish_forces();
    std::string describe() const override;
    void        serialize(StateArchive &ar) override;

    std::vector<ElementGroup> &groups()
    {
      return element_groups;
    }
    const std::vector<ElementGroup> &groups() const
    {
      return element_groups;
    }
    /** The body of each group. */
    const std::vector<unsigned int> &group_body() const
    {
      return body_of_group;
    }
    /** The first element that inverted (its active cell index; -1: none),
        until the health check reports it. */
    long &inverted_cell()
    {
      return first_inverted_cell;
    }
    /** Elements eroded so far (scene-wide), and erosion.csv's rows not yet
        written (rank 0). */
    unsigned long n_eroded() const
    {
      return eroded_so_far;
    }
    std::vector<std::string> &erosion_rows()
    {
      return rows;
    }
    /** Measure what each element costs ('Rebalance interval';
        ElementGroup::time_elements()). */
    void time_elements(const bool on)
    {
      for (auto &g : element_groups)
        g.time_elements(on);
    }
    void reset_timing()
    {
      for (auto &g : element_groups)
        g.reset_timing();
    }

  private:
    /** What erosion.csv tells of each owned element of group @p g eroded
        this step: id, body, centre, effective plastic strain, energy held,
        reference volume (8 numbers each, to @p info). */
    void record_erosion(unsigned int g, const std::vector<unsigned long> &ids, std::vector<double> &info) const;

    std::vector<ElementGroup>        element_groups;
    std::vector<unsigned int>        body_of_group;
    /** Per body: its one-point (or own) group and its full-integration
        group (-1: none). */
    std::vector<std::array<int, 2>>  group_of_body;
    long                             first_inverted_cell = -1;
    unsigned long                    eroded_so_far       = 0;
    std::vector<std::string>         rows;
    /** This step's energy increments (internal, hourglass, eroded, number
        eroded, viscous), summed over the processes, and this process's
        eroded elements and their erosion.csv data. */
    std::array<double, 5>            increments{};
    std::vector<unsigned long>       eroded;
    std::vector<double>              eroded_info;
  };
} // namespace anvil::Element
