"""``central_force`` configs across its case space (see ``tests/claimgen/__init__.py``).

Every potential (V = −k/r, −k/rⁿ with n below, at and above 1 where the apsides turn back,
stand still and advance, −k/r − ε/r² with ε < 0, = 0 and > 0); bound orbits from circles
(both turning points at one radius) through near-circles (e ~ 10⁻³) to e = 0.85 (0.7 off
V = −k/r, where a plunge costs the Hamilton–Jacobi quadrature seconds), started anywhere
between the turning points, either sense of rotation, runs shorter and longer than two
radial periods; unbound orbits with E > 0 and, for V = −k/r, E a hair above 0 (a
parabola); equal and unequal masses.  Each scene is built from its turning points, so its
case is known by construction and a generated config is always valid.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

from reportgen.kinds.central_force import apsides

EXAMPLES = 8


def _potential(r, k, n, eps):
    return -k / r**n - eps / r**2


def _slope(r, k, n, eps):
    return k * n / r ** (n + 1) + 2 * eps / r**3


@st.composite
def configs(draw):
    potential = draw(st.sampled_from(["power", "kepler_inverse_cube", "kepler"]))
    m1 = draw(st.floats(0.2, 5.0))
    m2 = draw(st.sampled_from([None, m1]))
    m2 = draw(st.floats(0.2, 5.0)) if m2 is None else m2
    mu = m1 * m2 / (m1 + m2)
    k = draw(st.floats(0.2, 3.0))
    # the apsides regress, stand still or advance: n below, at or above 1; ε < 0, = 0, > 0
    turn = draw(st.sampled_from(["regress", "regress", "fixed", "advance", "advance"]))
    n, f_eps = 1.0, 0.0
    if potential == "power" and turn != "fixed":
        n = draw(st.floats(0.15, 0.9) if turn == "regress" else st.floats(1.1, 1.8))
    if potential == "kepler_inverse_cube" and turn != "fixed":
        f_eps = draw(st.floats(-0.6, -0.05) if turn == "regress" else st.floats(0.05, 0.6))
    bound = draw(st.sampled_from([True, True, False]))
    r1 = draw(st.floats(0.3, 2.0))  # pericentre
    if bound:
        shape = draw(st.sampled_from(["ellipse", "circle", "near-circle", "ellipse"]))
        top = 0.85 if potential == "kepler" else 0.7
        e = {"circle": 0.0, "near-circle": draw(st.floats(1e-3, 1e-2)),
             "ellipse": draw(st.floats(0.05, top))}[shape]
        r2 = r1 * (1 + e) / (1 - e)
        if e == 0.0:  # L² = μ r³ V'(r): the circular orbit at r1
            C = mu * r1**3 * _slope(r1, k, n, 0.0)
        else:  # V_eff(r1) = V_eff(r2) for the k part; ε only adds 2με to L²
            C = (2 * mu * (_potential(r2, k, n, 0.0) - _potential(r1, k, n, 0.0))
                 / (1 / r1**2 - 1 / r2**2))
        eps = f_eps * C / (2 * mu)
        L2 = C + 2 * mu * eps
        energy = L2 / (2 * mu * r1**2) + _potential(r1, k, n, eps)
        r0 = r1 + draw(st.floats(0.0, 1.0)) * (r2 - r1)
        L = math.sqrt(L2)
        if e == 0.0:
            period = 2 * math.pi * mu * r1**2 / L
        elif potential == "power":
            period = apsides.radial_period_power(r1, r2, n, L, mu)
        else:
            period = apsides.radial_period_inverse_cube(energy, mu, k)
        # shorter and longer than two radial periods (pericentres measured from the run)
        periods = draw(st.sampled_from([(2.4, 3.4), (0.7, 1.6)]))
        periods = draw(st.floats(*periods))
        t_end = periods * period
        per_period = max(200.0, 40.0 / (1 - e) ** 1.5)
        samples = int(min(4000, periods * per_period)) + 1
    else:
        parabola = potential == "kepler" and draw(st.sampled_from([False, True]))
        energy = (1e-12 if parabola else draw(st.floats(0.05, 1.5))) * k / r1**n
        eps = f_eps * k * r1 / 2
        L2 = 2 * mu * r1**2 * (energy - _potential(r1, k, n, eps))
        L = math.sqrt(L2)
        r0 = r1 * (1 + 2 * draw(st.floats(0.0, 1.0)))
        speed = math.sqrt(2 * (energy - _potential(r1, k, n, eps)) / mu)
        t_end = draw(st.floats(4.0, 15.0)) * r1 / speed
        samples = draw(st.integers(300, 900))
    # the state at r0: ṙ from the energy (either sign), the angular momentum's sense either way
    v_t = L / (mu * r0)
    radial2 = 2 * (energy - _potential(r0, k, n, eps)) / mu - v_t**2
    v_r = math.sqrt(max(radial2, 0.0)) * draw(st.sampled_from([1.0, -1.0]))
    v_t *= draw(st.sampled_from([1.0, -1.0]))
    angle = draw(st.floats(-math.pi, math.pi))
    c, s = math.cos(angle), math.sin(angle)
    params = {"m1": m1, "m2": m2, "k": k}
    if potential == "power":
        params.update(potential="power", n=n)
    elif potential == "kepler_inverse_cube":
        params.update(potential="kepler_inverse_cube", epsilon=eps)
    return {"kind": "central_force", "params": params,
            "initial": {"x": r0 * c, "y": r0 * s, "vx": v_r * c - v_t * s,
                        "vy": v_r * s + v_t * c},
            "run": {"t_end": t_end, "samples": samples, "study": False}}
