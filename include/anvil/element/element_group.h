/**
 * @file
 * The explicit element loop: 8-node hexahedra with one-point integration and
 * Flanagan-Belytschko hourglass control, or full 2x2x2 integration, in the
 * total or updated Lagrangian formulation.
 *
 * This is the fast path of the code (../STYLE "hot loops"): state lives in
 * contiguous arrays in element order, shape-function derivatives are
 * compile-time tables on the natural element [-1,1]^3, nothing is allocated
 * or looked up per element per step, and no FEValues is reinitialised.
 * The reference path is deal.II's FEValues; tests/unit/patch_test checks that
 * both agree.
 *
 * Vertex numbering is deal.II's lexicographic one: vertex I = i + 2j + 4k has
 * natural coordinates (2i-1, 2j-1, 2k-1). The seed's Figure 2 numbers the
 * vertices counter-clockwise per face; the base vectors Lambda_1..3 and
 * Gamma_1..4 of seed Eq. (42) are therefore re-derived here as products of
 * the natural coordinates: Lambda_a = xi_a, Gamma_1 = xi eta,
 * Gamma_2 = eta zeta, Gamma_3 = xi zeta, Gamma_4 = xi eta zeta.
 */
#pragma once

#include <anvil/utilities/state_archive.h>

#include <anvil/material_model/interface.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace anvil::Element
{
  /** Per-item arrays stored by batch of B = Interface::batch_size items
      (the hourglass state, the materials' hot history): value k of item i
      at n_values B (i / B) + B k + i % B, so that a batch reads and writes
      value k of its lanes as one aligned vector. Such arrays hold whole
      batches (batch_major_size()). */
  inline std::size_t batch_major_entry(const std::size_t  i,
                                       const unsigned int k,
                                       const unsigned int n_values)
  {
    constexpr unsigned int B = MaterialModel::Interface::batch_size;
    return std::size_t(n_values) * B * (i / B) + std::size_t(B) * k + i % B;
  }
  inline std::size_t batch_major_size(const std::size_t n_items, const unsigned int n_values)
  {
    constexpr unsigned int B = MaterialModel::Interface::batch_size;
    return std::size_t(n_values) * B * ((n_items + B - 1) / B);
  }

  /** Element integration rule. */
  enum class Integration
  {
    /** Centroid, seed Eq. (39), with hourglass control. */
    one_point,
    /** 2x2x2 Gauss points. */
    full
  };

  /** Hourglass control of one-point elements (seed section 3.7). */
  enum class HourglassType
  {
    none,
    /** Viscous form, seed Eq. (44) with the Flanagan-Belytschko
        orthogonalised base vectors gamma (FB 1981, Eq. 42). */
    viscous,
    /** Stiffness form: the same modes resisted in proportion to the
        accumulated hourglass displacement. */
    stiffness
  };

  std::string to_string(Integration i);
  std::string to_string(HourglassType h);

  /**
   * Row-sum lumped mass of one hexahedron, m_I = rho_0 int N_I dV_0 (seed
   * Eq. (35)), by 2x2x2 Gauss quadrature (exact for the trilinear map).
   * Computed from the element's own vertices only, so the result does not
   * depend on which elements were evaluated before (unlike FEValues, which
   * reuses Jacobians of a translated previous cell).
   */
  void lumped_mass(const double (&X)[8][3], double density, double (&mass)[8]);

  /** What one pass of the element loop reports. */
  struct LoopResult
  {
    /** Smallest L_e / c_e over the elements. Units: s. */
    double critical_time_step = 1e300;
    /** Increment of internal (strain) energy this step. Units: J. */
    double internal_energy_increment = 0;
    /** Increment of hourglass energy this step. Units: J. */
    double hourglass_energy_increment = 0;
    /** Work of the bulk viscosity pressure this step (dissipated). Units: J. */
    double viscous_energy_increment = 0;
    /** Index of the first element whose Jacobian is not positive, or -1. */
    long int inverted_element = -1;
    /** Energy (internal and hourglass) of the owned elements eroded this
        step, already taken out of the two increments above. Units: J. */
    double eroded_energy_increment = 0;
    /** Global ids of the elements (owned and ghost) eroded this step. */
    std::vector<unsigned long> eroded_elements;

    /** Add the energies, erosions and first inverted element of @p r,
        another part of the same step (its step is left to the caller). */
    void add(const LoopResult &r)
    {
      internal_energy_increment += r.internal_energy_increment;
      hourglass_energy_increment += r.hourglass_energy_increment;
      viscous_energy_increment += r.viscous_energy_increment;
      eroded_energy_increment += r.eroded_energy_increment;
      eroded_elements.insert(eroded_elements.end(), r.eroded_elements.begin(), r.eroded_elements.end());
      if (inverted_element < 0)
        inverted_element = r.inverted_element;
    }
  };

  /**
   * All elements of one body on this MPI rank: they share a material,
   * formulation, integration rule and hourglass control.
   */
  class ElementGroup
  {
  public:
    ElementGroup(const MaterialModel::Interface &material,
                 Formulation                     formulation,
                 Integration                     integration,
                 HourglassType                   hourglass,
                 double                          hourglass_coefficient);

    /**
     * Add one element. @p node holds, for each of the 8 vertices in
     * lexicographic order, the local index of its x component in the nodal
     * vectors (y and z follow at +1, +2). @p X are the reference vertex
     * coordinates. @p cell_index is a user tag (deal.II's active cell
     * index) used by output. A ghost element (@p owned false) computes its
     * forces like any other, so that every owned node receives the
     * contributions of all its elements in the same order on any number of
     * processes, but adds nothing to the energies. @p strength_factor
     * scales the strengths of materials that accept one (an imperfection).
     */
    void add_element(const std::array<unsigned int, 8> &node,
                     const double (&X)[8][3],
                     unsigned int  cell_index,
                     bool          owned           = true,
                     unsigned long global_id       = static_cast<unsigned long>(-1),
                     double        strength_factor = 1.);

    /**
     * Bulk viscosity (ABAQUS/Explicit's and LS-DYNA's artificial viscosity):
     * in compression (tr D < 0) the pressure
     *   q = rho L (b_2^2 L (tr D)^2 - b_1 c tr D)
     * joins the stress in the nodal forces (not the material's stress), its
     * work is reported as viscous energy, and the stable step becomes
     * L / c (sqrt(1 + xi^2) - xi), xi = b_1 - b_2^2 L tr D / c. Zero
     * coefficients switch it off. Call before finalize().
     */
    void set_bulk_viscosity(double linear, double quadratic);

    /** Allocate stress and history storage once all elements are added,
        and let the material set up each point's history (characteristic
        length cbrt(V_0) of the element, strength factor). */
    void finalize();

    /**
     * The stable step L_e / c assumes that each of an element's nodes
     * carries an eighth of its mass. Row-sum lumping gives a node where few
     * elements meet at wide angles less (the corner of a cube mapped onto a
     * ball: 0.47 of the eighths around it), and that node's frequency rises
     * by the inverse square root. @p ratio holds, per node (indexed like
     * the nodal vectors' x entries, ghosts included), m_I over the sum of
     * the eighths of the masses of the elements around it; each element's
     * step is scaled by the square root of the smallest ratio over its
     * nodes (at most 1). Call after finalize().
     */
    void set_nodal_mass_ratio(const double *ratio);

    /**
     * The squared stable step of the viscous hourglass force f_I = -k
     * gamma_I (gamma . v), k = Q rho V^(2/3) c / 4 (seed Eq. (44)), of an
     * element of mass @p element_mass = rho V. On a checkerboard mode
     * (|gamma|^2 = 8, a node's share of the mass rho V / 8) it is a damper
     * c_d / m = 64 k / (rho V) on the last half step's velocities, stable
     * for dt <= 2 m / c_d = rho V / (32 k) = V^(1/3) / (8 Q c): never below
     * L_e / c for Q <= 1/8, 0.42 L_e / c on a cube at Q = 0.3. The lightest
     * node's share of the mass scales it like the element's own step.
     */
    static double viscous_hourglass_step2(const double element_mass, const double k,
                                          const double node_mass_factor)
    {
      const double dt = element_mass / (32. * k);
      return dt * dt * node_mass_factor;
    }
    /** The viscous damper's coefficient Q rho V^(2/3) c / 4 (seed Eq.
        (44)), c = sqrt(M / rho), as the reference loop computes it. */
    double viscous_hourglass_coefficient(const double rho, const double volume, const double M) const
    {
      const double c = std::sqrt(M / rho);
      return 0.25 * hourglass_coefficient * rho * std::cbrt(volume * volume) * c;
    }
    /** An element's distortion factor min(1, (V / A_max)^2 / (2 / max
        |grad xi|)^2) times its nodes' mass factor: (V / A_max)^2 is the
        squared height of a parallelepiped, 4 / @p grad2 that of the
        characteristic length. */
    static double shape_factor_of(const double volume, const double A2, const double grad2,
                                  const double node_mass_factor)
    {
      return std::min(1., volume * volume / A2 * grad2 / 4.) * node_mass_factor;
    }
    /** The squared stable step (2 / max |grad xi|)^2 shape rho / M of seed
        Eq. (23), times the bulk viscosity's factor. */
    static double element_step2_of(const double grad2, const double shape, const double rho, const double M,
                                   const double dt_bulk2)
    {
      return 4. / grad2 * shape * rho / M * dt_bulk2;
    }

    /**
     * The explicit element loop: from current positions @p x and
     * velocities @p v (the half-step velocity that brought the mesh to x),
     * update stresses over @p dt (the time since the last call; 0 at the
     * start) and subtract the internal and hourglass forces from @p force.
     */
    LoopResult compute_internal_forces(const double *x,
                                       const double *v,
                                       double        dt,
                                       double       *force);

    /**
     * The same as compute_internal_forces(), always through the reference
     * element-by-element loop (for tests of the fast path).
     */
    LoopResult compute_internal_forces_reference(const double *x,
                                                 const double *v,
                                                 double        dt,
                                                 double       *force);

    unsigned int n_elements() const
    {
      return cell_index.size();
    }
    unsigned int n_quadrature_points() const
    {
      return n_qp;
    }
    unsigned int element_cell_index(const unsigned int e) const
    {
      return cell_index[e];
    }
    bool element_is_owned(const unsigned int e) const
    {
      return energy_weight[e] != 0.;
    }
    /** Scene-wide element id (the coarse cell), the same on every rank. */
    unsigned long element_global_id(const unsigned int e) const
    {
      return global_id[e];
    }
    /** Whether element e has been eroded (material failure). */
    bool element_is_eroded(const unsigned int e) const
    {
      return !alive.empty() && !alive[e];
    }
    /** History variable k of quadrature point q of element e. */
    double history_variable(const unsigned int e, const unsigned int q, const unsigned int k) const
    {
      const std::size_t p = e * n_qp + q;
      return k < n_hot ? history[hot_entry(p, k)] : cold_history[n_cold * p + k - n_hot];
    }
    /** All history variables of quadrature point q of element e (n_history()
        values) into @p h. */
    void copy_history(const unsigned int e, const unsigned int q, double *h) const
    {
      for (unsigned int k = 0; k < n_hist; ++k)
        h[k] = history_variable(e, q, k);
    }
    /** The material's history_value() of variable k at quadrature point q
        of element e (a stored or derived value). */
    double history_output(const unsigned int e, const unsigned int q, const unsigned int k) const
    {
      double h[MaterialModel::Interface::max_history];
      copy_history(e, q, h);
      return material.history_value(h, k);
    }
    const std::array<unsigned int, 8> element_nodes(const unsigned int e) const;

    /** Stress at quadrature point q of element e (Voigt): Cauchy for
        updated Lagrangian, second Piola-Kirchhoff for total Lagrangian. */
    const double *stress(const unsigned int e, const unsigned int q) const
    {
      return &stresses[6 * (e * n_qp + q)];
    }
    double *stress(const unsigned int e, const unsigned int q)
    {
      return &stresses[6 * (e * n_qp + q)];
    }
    /** Accumulated internal and hourglass energy of element e. Units: J. */
    double element_internal_energy(const unsigned int e) const
    {
      return internal_energy[e];
    }
    double element_hourglass_energy(const unsigned int e) const
    {
      return hourglass_energy[e];
    }
    /** What a step changes in the material state of the elements, copied
        out (snapshot()) and back (restore()): an evaluation of the forces
        that must leave it as it was (the forces of a mesh refined during
        the run, at dt = 0, where a viscous regularisation would otherwise
        return the stress to the rate-independent surface). The bulk
        viscosity's pressure is not part of it: the evaluation's (zero at
        dt = 0) is the one its forces hold, and the next step's viscous
        work starts from it. */
    struct Snapshot
    {
      std::vector<double>        stresses, history, cold_history, modes, resistance, internal, hourglass;
      std::vector<unsigned char> alive;
    };
    Snapshot snapshot() const
    {
      return {stresses,        history,         cold_history, hourglass_modes, hourglass_resistance,
              internal_energy, hourglass_energy, alive};
    }
    void restore(Snapshot &&s)
    {
      stresses             = std::move(s.stresses);
      history              = std::move(s.history);
      cold_history         = std::move(s.cold_history);
      hourglass_modes      = std::move(s.modes);
      hourglass_resistance = std::move(s.resistance);
      internal_energy      = std::move(s.internal);
      hourglass_energy     = std::move(s.hourglass);
      alive                = std::move(s.alive);
    }
    /** The change of the own elements' elastic energy that a load onto a
        refined or coarsened mesh made (StateArchive::element_transfer()),
        booked in their internal energy. Units: J. */
    double transfer_energy() const
    {
      return adapted_energy;
    }
    double element_reference_volume(const unsigned int e) const
    {
      return reference_volume[e];
    }

    Formulation get_formulation() const
    {
      return formulation;
    }
    const MaterialModel::Interface &get_material() const
    {
      return material;
    }

    /** Bytes of state held per element (solver arrays only). */
    double memory_per_element() const;

    /** The stable step of element @p e at rest in the positions @p X,
        before the safety factor: the step the loop takes for it (seed Eq.
        (23) with its characteristic length min(2 / max |grad xi|, V /
        A_max), the mass scaling's factor, the bulk viscosity's factor at
        rest, and the viscous hourglass damper's own bound), so that the
        report before a run names the elements that set the step. */
    double stable_step(unsigned int e, const double (&X)[8][3]) const;

    /** Batches the batched loop handed to the reference loop because an
        element's Jacobian was not positive (tests: the fast path must have
        run). */
    unsigned long n_reference_fallbacks() const
    {
      return reference_fallbacks;
    }

    /**
     * Cauchy stress (Voigt) averaged over the element from the stored
     * stresses and current positions @p x.
     */
    void cauchy_stress(const unsigned int e,
                       const double      *x,
                       double            *sigma) const;

    /** Measure what the elements cost ('Rebalance interval'): the loop's
        time per batch of W elements (the batched one-point loop), per
        element (the fully integrated one) or for the whole group (the
        element-by-element loops), summed over the calls since
        reset_timing(). */
    void time_elements(bool on);
    void reset_timing()
    {
      std::fill(chunk_seconds.begin(), chunk_seconds.end(), 0.);
    }
    /** Element @p e's share of the measured time: its chunk's over the
        chunk's elements. Units: s. */
    double element_seconds(unsigned int e) const;
    /** The group's measured time. Units: s. */
    double measured_seconds() const;

    /** Whether the group computes bulk viscosity (a coefficient > 0). */
    bool bulk_viscosity() const
    {
      return bulk_linear > 0 || bulk_quadratic > 0;
    }

  private:
    /** The reference loop, one element at a time, over [begin, end). */
    template <Formulation F, Integration I, HourglassType H>
    LoopResult loop(const double *x,
                    const double *v,
                    double        dt,
                    double       *force,
                    unsigned int  begin,
                    unsigned int  end);

    /** The fast loop for one-point updated Lagrangian elements: batches of
        8 elements in structure-of-arrays form, vectorised across them. */
    template <HourglassType H>
    LoopResult batched_loop(const double *x, const double *v, double dt, double *force);
    /** The fast loop for fully integrated updated Lagrangian elements:
        an element's 8 points are the lanes of a batch (the same arithmetic
        as loop() with the points' material update batched). */
    LoopResult full_batched_loop(const double *x, const double *v, double dt, double *force);
    /** Squared stable step (L_e / c)^2 of element @p e from its nodal
        positions @p xe, volume, max |grad xi|^2 and bulk viscosity factor;
        refreshes its shape factor when due. */
    double element_step2(unsigned int e, const double (&xe)[8][3], double volume, double max_grad2,
                         double dt_bulk2);
    /** Erode element @p e (with @p nq points) in this step's @p result. */
    void erode(unsigned int e, unsigned int nq, LoopResult &result);

    const MaterialModel::Interface &material;
    const Formulation               formulation;
    const Integration               integration;
    const HourglassType             hourglass;
    const double                    hourglass_coefficient;
    /** Bulk viscosity coefficients b_1 (linear) and b_2 (quadratic). */
    double                          bulk_linear    = 0;
    double                          bulk_quadratic = 0;
    /** (sqrt(1 + b_1^2) - b_1)^2: the step factor where tr D >= 0. */
    double                          bulk_dt_factor2_expansion = 1;
    /** The bulk viscosity pressure of the last step per point, for the
        trapezoidal viscous work. */
    std::vector<double> bulk_pressure;
    /** q, and the factor (sqrt(1 + xi^2) - xi)^2 on the squared stable
        step, at a point with volumetric rate @p trD, length @p L, density
        @p rho and wave speed @p c. */
    double bulk_viscosity_pressure(double trD, double L, double rho, double c, double &dt_factor2) const
    {
      return bulk_viscosity_pressure(trD, L, rho, c, bulk_linear, bulk_quadratic,
                                     bulk_dt_factor2_expansion, dt_factor2);
    }
    /** The same with the coefficients as arguments: branch-free (both
        sides computed, one selected), so that a loop over a batch
        vectorises. */
    static double bulk_viscosity_pressure(const double trD, const double L, const double rho,
                                          const double c, const double b1, const double b2,
                                          const double expansion_factor2, double &dt_factor2)
    {
      const double compression = trD < 0 ? 1. : 0.;
      const double xi          = b1 - b2 * b2 * L * trD / c;
      const double s           = std::sqrt(1. + xi * xi) - xi;
      dt_factor2 = compression * (s * s) + (1. - compression) * expansion_factor2;
      return compression * (rho * L * (b2 * b2 * L * trD * trD - b1 * c * trD));
    }
    /** The same for the batched loops, from Z = rho / |grad xi|^2 (= m /
        (V |grad xi|^2), m the element's or point's mass): with rho L^2 =
        4 Z, rho L c = 2 S and L / c = 2 S / M, S = sqrt(M Z), one square
        root of Z and no division; branch-free. */
    static double bulk_viscosity_pressure_of_Z(const double trD, const double Z, const double M,
                                               const double b1, const double b2,
                                               const double expansion_factor2, double &dt_factor2)
    {
      const double S           = std::sqrt(M * Z);
      const double compression = trD < 0 ? 1. : 0.;
      const double xi          = b1 - 2. * b2 * b2 * (S / M) * trD;
      const double sx          = std::sqrt(1. + xi * xi) - xi;
      dt_factor2 = compression * (sx * sx) + (1. - compression) * expansion_factor2;
      return compression * (4. * b2 * b2 * Z * trD * trD - 2. * b1 * S * trD);
    }
    const unsigned int              n_qp;
    double                          adapted_energy = 0;
    const unsigned int              n_hist;
    /** The history's split (MaterialModel::Interface::n_hot_history()):
        the first n_hot values of every point in history, stored by batch
        of W points (hot_entry()), the other n_cold in cold_history, n_cold
        contiguous values a point. */
    const unsigned int              n_hot;
    const unsigned int              n_cold;
    /** Where hot value k of point p is (batch_major_entry()). */
    std::size_t hot_entry(const std::size_t p, const unsigned int k) const
    {
      return batch_major_entry(p, k, n_hot);
    }
    /** Point p's whole history, a copy in @p buffer, which store_history()
        writes back (nullptr for a model without history). */
    double *point_history(const std::size_t p, double *buffer)
    {
      if (n_hist == 0)
        return nullptr;
      copy_history(p / n_qp, p % n_qp, buffer);
      return buffer;
    }
    void store_history(const std::size_t p, const double *h)
    {
      if (h == nullptr)
        return;
      for (unsigned int k = 0; k < n_hot; ++k)
        history[hot_entry(p, k)] = h[k];
      std::copy_n(h + n_hot, n_cold, cold_history.data() + n_cold * p);
    }
    /** The material's point_failed() and stiffness_fraction() of point p. */
    bool point_failed(const std::size_t p)
    {
      double buffer[MaterialModel::Interface::max_history];
      return material.point_failed(point_history(p, buffer));
    }
    /** (It reads hot values only: a copy of those.) */
    double stiffness_fraction(const std::size_t p) const
    {
      double h[MaterialModel::Interface::max_history];
      for (unsigned int k = 0; k < n_hot; ++k)
        h[k] = history[hot_entry(p, k)];
      return material.stiffness_fraction(h);
    }
    /** The split history of the batch of points p0, ..., p0 + W - 1 (p0 a
        multiple of W) as stored: hot value k of its lanes at hot_batch +
        W k. (A lane that is not one of these points is redirected by the
        caller, which then clears hot_batch.) */
    MaterialModel::Interface::BatchHistory batch_history(const std::size_t p0)
    {
      MaterialModel::Interface::BatchHistory h;
      h.n_hot      = n_hot;
      h.n_cold     = n_cold;
      h.hot_stride = W;
      h.hot_batch  = history.data() + hot_entry(p0, 0);
      for (unsigned int l = 0; l < W; ++l)
        {
          h.hot[l]  = h.hot_batch + l;
          h.cold[l] = cold_history.data() + n_cold * (p0 + l);
        }
      return h;
    }

    /** The nodes' first nodal-vector entries, by batch of W elements and
        node-major within a batch (node(e, n)), so that the batched loop
        reads a batch's node n as one vector. */
    std::vector<unsigned int> nodes;
    /** Per batch: whether every node of it lies below the group's last
        node, so that the nodal vector holds the four values the batched
        gather reads from each (its three and one more). */
    std::vector<unsigned char> batch_wide;
    static constexpr unsigned int W = MaterialModel::Interface::batch_size;
    unsigned int node(const unsigned int e, const unsigned int n) const
    {
      return nodes[(e / W) * 8 * W + n * W + e % W];
    }
    std::vector<unsigned int> cell_index;
    std::vector<unsigned long> global_id;
    /** 1 for intact elements, 0 for eroded ones; empty for materials that
        cannot fail. */
    std::vector<unsigned char> alive;
    std::vector<double>       reference_volume;
    /** 1 for owned elements, 0 for ghost elements. */
    std::vector<double> energy_weight;
    /** Total Lagrangian: inverse reference Jacobian (9) per point. */
    std::vector<double> jacobian_inverse_ref;
    /** Weight times reference Jacobian determinant per point. */
    std::vector<double> jxw_ref;
    std::vector<double> stresses;
    /** The points' history (see n_hot and hot_entry()). */
    std::vector<double> history;
    std::vector<double> cold_history;
    /** Stiffness hourglass control: accumulated modes q_aj (12 an
        element, stored by batch: hourglass_entry() in element_group.cc). */
    std::vector<double> hourglass_modes;
    /** Hourglass resistance r_aj of the previous step (12 an element,
        stored like the modes), for the trapezoidal hourglass work. */
    std::vector<double> hourglass_resistance;
    std::vector<double> internal_energy;
    std::vector<double> hourglass_energy;
    /**
     * Per element, (V / A_max)^2 / (2 / max |grad xi|)^2 (at most 1): how
     * much the element's distortion lowers its stable step below the
     * centroid measure. The face areas cost a quarter of a one-point
     * element's step, and distortion changes slowly, so it is refreshed
     * every shape_refresh_interval calls (the first call included).
     */
    std::vector<double> shape_factor;
    /** Per element, the smallest over its nodes of m_I / sum_e (m_e / 8)
        (at most 1; set_nodal_mass_ratio()), a factor of shape_factor. */
    std::vector<double> mass_factor;
    unsigned long reference_fallbacks = 0;
    static constexpr unsigned int shape_refresh_interval = 8;
    unsigned int                  n_calls                = 0;
    bool                          refresh_shape          = true;
    /** Strength factor per element, until finalize() hands it to the
        material. */
    std::vector<double> strength_factors;
    /** History of the padding lanes of a batch, stored like one batch
        (sized in finalize(), copied in before every use, so not part of
        the checkpoint). */
    std::vector<double> scratch_history;
    std::vector<double> scratch_cold_history;
    /** Full integration, updated Lagrangian: full_batched_loop() (false
        only while compute_internal_forces_reference() runs loop()). */
    bool batch_points = true;
    /** time_elements(): the elements a chunk of the measured time covers
        (0: not measured) and each chunk's seconds. */
    unsigned int        timing_chunk = 0;
    std::vector<double> chunk_seconds;
    /** The loop this group's kind runs (compute_internal_forces()). */
    LoopResult dispatch_loop(const double *x, const double *v, double dt, double *force);
    /** In a loop that times its chunks: adds the time since the last mark
        to chunk @p c and marks now. */
    void tick(std::chrono::steady_clock::time_point &mark, const unsigned int c)
    {
      const auto now = std::chrono::steady_clock::now();
      chunk_seconds[c] += std::chrono::duration<double>(now - mark).count();
      mark = now;
    }

  public:
    /** Everything a step changes (checkpoints): the elements' state by
        their scene-wide id in the keyed table @p table (the owned ones
        written, the owned and ghost ones read). */
    void serialize(StateArchive &ar, const std::string &table);
  };
} // namespace anvil::Element
