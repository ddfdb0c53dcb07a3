"""Closed forms the concrete tests check against, written from the
publications and independently of the C++ code:

- fib Model Code 2010, section 5.1: Table 5.1-8 (eps_c1, eps_c,lim), E_ci
  (Eq. 5.1-21), the compressive curve Eq. (5.1-26), f_ctm (Eq. 5.1-3) and
  G_F (Eq. 5.1-9);
- the dynamic increase factors of the seed's Eqs. (64)-(67) in the
  continuous form (1.026 alpha, log gamma = 6.156 alpha - log10(30)/3).
"""
import math

# f_ck (MPa), eps_c1 (per mille), eps_c,lim (per mille)
MC2010_TABLE = [(12, 1.8, 3.5), (16, 1.9, 3.5), (20, 2.1, 3.5), (25, 2.2, 3.5),
                (30, 2.3, 3.5), (35, 2.3, 3.5), (40, 2.4, 3.5), (45, 2.5, 3.5),
                (50, 2.6, 3.4), (55, 2.6, 3.4), (60, 2.7, 3.3), (70, 2.7, 3.2),
                (80, 2.8, 3.1), (90, 2.9, 3.0), (100, 3.0, 3.0), (110, 3.0, 3.0),
                (120, 3.0, 3.0)]


def mc2010_constants(fcm):
    """(E_ci, eps_c1, eps_c,lim, k) for the mean strength fcm (Pa)."""
    fck = fcm / 1e6 - 8
    for (f0, e0, l0), (f1, e1, l1) in zip(MC2010_TABLE, MC2010_TABLE[1:]):
        if fck <= f1:
            t = (fck - f0) / (f1 - f0)
            break
    eps_c1 = 1e-3 * (e0 + t * (e1 - e0))
    eps_lim = 1e-3 * (l0 + t * (l1 - l0))
    E_ci = 21.5e9 * (fcm / 10e6) ** (1 / 3)
    return E_ci, eps_c1, eps_lim, E_ci * eps_c1 / fcm


def mc2010_compression(fcm, eps):
    """Eq. (5.1-26): compressive stress magnitude at strain magnitude eps
    (valid up to eps_c,lim)."""
    _, eps_c1, _, k = mc2010_constants(fcm)
    eta = eps / eps_c1
    return fcm * (k * eta - eta ** 2) / (1 + (k - 2) * eta)


def mc2010_elastic_limit(fcm):
    """(eps, E): the strain where Eq. (5.1-26) reaches 0.4 f_cm, by bisection,
    and the secant modulus E = 0.4 f_cm / eps there (Anvil's E)."""
    lo, hi = 0.0, mc2010_constants(fcm)[1]
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mc2010_compression(fcm, mid) < 0.4 * fcm else (lo, mid)
    return lo, 0.4 * fcm / lo


def mc2010_tensile_strength(fcm):
    fck = fcm / 1e6 - 8
    return 1e6 * (0.3 * fck ** (2 / 3) if fck <= 50 else 2.12 * math.log(1 + fcm / 10e6))


def mc2010_fracture_energy(fcm):
    return 73 * (fcm / 1e6) ** 0.18


def cdif(rate, fcu):
    alpha = 1 / (5 + 0.75 * fcu / 1e6)
    if rate <= 30e-6:
        return 1.0
    if rate <= 30:
        return (rate / 30e-6) ** (1.026 * alpha)
    return 10 ** (6.156 * alpha - math.log10(30) / 3) * rate ** (1 / 3)


def tdif(rate, fc):
    delta = 1 / (1 + 8 * fc / 10e6)
    if rate <= 1e-6:
        return 1.0
    if rate <= 1:
        return (rate / 1e-6) ** delta
    return 10 ** (6 * delta - 2) * (rate / 1e-6) ** (1 / 3)


def material_block(fc=45.4e6, extra="", indent=""):
    """The Material subsection of a concrete scene or driver file."""
    text = f"""subsection Material
  set Model = concrete damaged plasticity
  subsection concrete damaged plasticity
    set Compressive strength = {fc}
    set Dilation angle = 36
{extra}  end
end
"""
    return "".join(indent + line + "\n" for line in text.splitlines())


def pulled_bar_overrides(n, end_time, history_interval, lateral=None, length=0.1, width=0.01):
    """Overrides of tests/concrete/pulled_bar.prm (test_scene) for n
    elements along and lateral = n // 10 across: the subdivisions, the
    weakened row just beyond mid-length, the probe in the first element,
    the end time and the history interval."""
    dx = length / n
    m = lateral if lateral else max(n // 10, 1)
    return {"Simulation/End time": end_time, "Simulation/History interval": history_interval,
            "Body bar/Mesh/Subdivisions": f"{n}, {m}, {m}",
            "Body bar/Imperfection/Lower corner": f"{0.5 * length + 0.1 * dx}, -1, -1",
            "Body bar/Imperfection/Upper corner": f"{0.5 * length + 0.9 * dx}, 1, 1",
            "Probe end/Point": f"{dx / 2}, {width / 2}, {width / 2}"}
