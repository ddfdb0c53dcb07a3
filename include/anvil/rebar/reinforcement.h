/**
 * @file
 * Reinforcement as a family of the scene: the bars of every 'Rebar NAME'
 * layout, their embedding in the host body, truss forces, bond-slip and the
 * bars' own nodes, their histories and fields (seed sections 5.1, 5.3, 5.4).
 */
#pragma once

#include <anvil/rebar/rebar.h>
#include <anvil/simulator/force_contributor.h>

namespace anvil::Rebar
{
  class Reinforcement : public ForceContributor
  {
  public:
    Reinforcement(Simulator &simulator, std::vector<Layout> layouts);

    std::string name() const override
    {
      return "rebar and bond";
    }
    bool empty() const override
    {
      return layouts.empty();
    }
    /** Embedding: each process locates the truss nodes in the host cells it
        owns; a node on a shared face goes to the cell with the smallest
        scene-wide id, so every partition embeds it the same way. */
    void   setup() override;
    /** Perfectly bonded bars: rho A l_trib to the host nodes through N_I. */
    void   add_mass(VectorType &mass) override;
    double add_forces(double dt) override;
    void   update_velocity(double dt_previous, double dt, OwnMotion &motion) override;
    void   update_position(double dt) override;
    void   add_kinetic_energy(double &kinetic) const override;
    void   add_momentum(double dt, std::vector<double> &momentum) const override;
    std::string describe() const override;
    void   write_summary(std::ostream &out) const override;
    void   write_history(double t, double dt) override;
    /** rebar_NAME_NNNN.vtu (line cells: axial force, stress, effective
        plastic strain; bond-slip: slip and bond stress at the nodes) and
        rebar_NAME.pvd. */
    void   output_frame(double t, unsigned int count) override;
    void serialize(StateArchive &ar) override
    {
      for (auto &t : bars)
        t.serialize(ar);
    }

  private:
    std::vector<Layout>      layouts;
    std::vector<Trusses>     bars;
  };
} // namespace anvil::Rebar
