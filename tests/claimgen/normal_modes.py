"""Normal-mode configs across the kind's case space (see tests/claimgen/__init__.py).

Molecules with and without a centre of inversion -- linear Y–X–Y with equal end masses
and bonds (CO₂-like, also all three atoms alike), linear X–Y–Z (OCS-like), bent
triatomics symmetric (H₂O-like) and not (HOD-like, unequal bonds), linear four-atom
X–Y–Y–X (C₂H₂-like) and its unsymmetric kin, pyramidal four-atom (NH₃-like), diatomics;
atoms by element or by mass alone -- then chains (fixed and free ends), coupled pendula
(two: in and out of phase; more: nodes), matrices, and potentials written as formulas
(the double pendulum from L; wells in one to three coordinates with T or M, stable or with
a flat direction, neutral), some with a time evolution.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

EXAMPLES = 8

ELEMENTS = ("H", "C", "N", "O", "F", "S", "Cl")


@st.composite
def _atom(draw, element: str | None = None):
    """An atom: by element (molecular units take its mass) or by a mass alone [u]."""
    if element is None:
        element = draw(st.sampled_from(ELEMENTS))
    return element


def _atoms(elements, positions, masses=None):
    out = []
    for a, (e, x) in enumerate(zip(elements, positions, strict=True)):
        atom = {"position": [float(v) for v in x]}
        if masses is not None:
            atom["mass"] = float(masses[a])
        else:
            atom["element"] = e
        out.append(atom)
    return out


def _bonds(pairs, ks):
    return [{"atoms": list(p), "k": float(k)} for p, k in zip(pairs, ks, strict=True)]


def _angles(triples, ks):
    return [{"atoms": list(t), "k": float(k)} for t, k in zip(triples, ks, strict=True)]


_K = st.floats(2.0, 18.0)
_KB = st.floats(0.2, 1.2)
_R = st.floats(0.9, 1.8)
_MASS = st.floats(1.0, 40.0)


@st.composite
def linear_triatomic(draw):
    """Y–X–Y (symmetric: equal ends, bonds and lengths; or all three alike) or X–Y–Z."""
    case = draw(st.sampled_from(["symmetric", "all alike", "unsymmetric", "unequal bonds"]))
    centre = draw(st.sampled_from(ELEMENTS[1:]))
    end = draw(st.sampled_from(ELEMENTS))
    other = draw(st.sampled_from([e for e in ELEMENTS if e != end]))
    r1, k1 = draw(_R), draw(_K)
    r2, k2 = (r1, k1) if case in ("symmetric", "all alike") else (draw(_R), draw(_K))
    elements = {"symmetric": [end, centre, end], "all alike": [end, end, end],
                "unsymmetric": [end, centre, other], "unequal bonds": [end, centre, end]}[case]
    if case == "unequal bonds" and abs(r1 - r2) < 0.05 and abs(k1 - k2) < 0.5:
        r2 += 0.2
    positions = [[-r1, 0, 0], [0, 0, 0], [r2, 0, 0]]
    return {"atoms": _atoms(elements, positions),
            "bonds": _bonds([(0, 1), (1, 2)], [k1, k2]),
            "angles": _angles([(0, 1, 2)], [draw(_KB)])}


@st.composite
def bent_triatomic(draw):
    """Y–X–Y bent (symmetric) or with unequal ends, bonds or masses; by element or mass."""
    case = draw(st.sampled_from(["symmetric", "unequal ends", "unequal bonds", "masses"]))
    half = math.radians(draw(st.floats(95.0, 160.0))) / 2
    r1, k1 = draw(_R), draw(_K)
    r2, k2 = (r1, k1) if case in ("symmetric", "masses", "unequal ends") else (
        draw(_R), draw(_K))
    positions = [[-r1 * math.sin(half), r1 * math.cos(half), 0], [0, 0, 0],
                 [r2 * math.sin(half), r2 * math.cos(half), 0]]
    end = draw(st.sampled_from(ELEMENTS))
    centre = draw(st.sampled_from(ELEMENTS[1:]))
    elements = [end, centre, draw(st.sampled_from([e for e in ELEMENTS if e != end]))
                if case == "unequal ends" else end]
    masses = None
    if case == "masses":  # atoms given by their masses alone
        m_end = draw(_MASS)
        masses = [m_end, draw(_MASS), m_end if draw(st.booleans()) else m_end * 1.5]
    return {"atoms": _atoms(elements, positions, masses),
            "bonds": _bonds([(0, 1), (1, 2)], [k1, k2]),
            "angles": _angles([(0, 1, 2)], [draw(_KB)])}


@st.composite
def linear_four_atom(draw):
    """X–Y–Y–X (C₂H₂-like, a centre of inversion) or X–Y–Z–W without one."""
    symmetric = draw(st.booleans())
    ends = draw(st.sampled_from(ELEMENTS[:2])), draw(st.sampled_from(ELEMENTS[:3]))
    mids = draw(st.sampled_from(ELEMENTS[1:4])), draw(st.sampled_from(ELEMENTS[1:4]))
    r_end, r_mid, k_end, k_mid = draw(_R), draw(_R), draw(_K), draw(_K)
    if symmetric:
        elements = [ends[0], mids[0], mids[0], ends[0]]
        r_end2, k_end2 = r_end, k_end
    else:
        elements = [ends[0], mids[0], mids[1], ends[1]]
        r_end2, k_end2 = draw(_R), draw(_K)
    h = r_mid / 2
    positions = [[-h - r_end, 0, 0], [-h, 0, 0], [h, 0, 0], [h + r_end2, 0, 0]]
    kb = draw(_KB)
    return {"atoms": _atoms(elements, positions),
            "bonds": _bonds([(0, 1), (1, 2), (2, 3)], [k_end, k_mid, k_end2]),
            "angles": _angles([(0, 1, 2), (1, 2, 3)], [kb, kb if symmetric else draw(_KB)])}


@st.composite
def pyramid(draw):
    """X at the apex of three Y (NH₃-like), all alike or one Y different."""
    r, k, kb = draw(_R), draw(_K), draw(_KB)
    height = draw(st.floats(0.3, 0.8)) * r
    rho = math.sqrt(r * r - height * height)
    positions = [[0, 0, height]] + [[rho * math.cos(2 * math.pi * s / 3),
                                     rho * math.sin(2 * math.pi * s / 3), 0] for s in range(3)]
    apex = draw(st.sampled_from(("N", "P", "C")))
    leg = draw(st.sampled_from(("H", "F", "Cl")))
    odd = draw(st.booleans())
    elements = [apex, leg, leg, draw(st.sampled_from([e for e in ("H", "F", "Cl")
                                                      if e != leg])) if odd else leg]
    return {"atoms": _atoms(elements, positions),
            "bonds": _bonds([(0, 1), (0, 2), (0, 3)], [k, k, draw(_K) if odd else k]),
            "angles": _angles([(1, 0, 2), (2, 0, 3), (3, 0, 1)], [kb, kb, kb])}


@st.composite
def diatomic(draw):
    a, b = draw(st.sampled_from(ELEMENTS)), draw(st.sampled_from(ELEMENTS))
    r = draw(_R)
    return {"atoms": _atoms([a, b], [[0, 0, 0], [r, 0, 0]]),
            "bonds": _bonds([(0, 1)], [draw(_K)])}


@st.composite
def molecule(draw):
    scene = draw(st.one_of(linear_triatomic(), bent_triatomic(), linear_four_atom(),
                           pyramid(), diatomic()))
    if draw(st.booleans()):  # a time evolution from a small displacement (Å), in τ
        n = len(scene["atoms"])
        d = draw(st.lists(st.floats(-0.02, 0.02), min_size=3 * n, max_size=3 * n))
        d[0] = d[0] or 0.01
        scene["evolve"] = {"displacement": d, "t_end": draw(st.floats(10.0, 40.0))}
    return scene


@st.composite
def chain(draw):
    scene = {"chain": {"n": draw(st.integers(1, 8)), "m": draw(st.floats(0.5, 3.0)),
                       "k": draw(st.floats(0.5, 3.0)),
                       "ends": draw(st.sampled_from(["fixed", "free"]))}}
    if scene["chain"]["ends"] == "free" and scene["chain"]["n"] == 1:
        scene["chain"]["ends"] = "fixed"
    return scene


@st.composite
def pendula(draw):
    return {"pendula": {"n": draw(st.integers(1, 5)), "m": draw(st.floats(0.5, 2.0)),
                        "l": draw(st.floats(0.5, 2.0)), "k": draw(st.floats(0.1, 5.0))}}


@st.composite
def matrices(draw):
    n = draw(st.integers(1, 3))
    m = [draw(st.floats(0.5, 3.0)) for _ in range(n)]
    k = [draw(st.floats(0.5, 5.0)) for _ in range(n + 1)]
    if draw(st.booleans()):  # a stiff pair: ω ratio past 10³
        m, k, n = [1.0, 1e-2], [1.0, 1e4 * draw(st.floats(1.0, 3.0)), 0.0], 2
    A = [[0.0] * n for _ in range(n)]
    for s in range(n + 1):  # springs between neighbours and to the walls
        for i in (s - 1, s):
            if 0 <= i < n:
                A[i][i] += k[s]
        if 1 <= s < n:
            A[s - 1][s] -= k[s]
            A[s][s - 1] -= k[s]
    return {"M": [[m[i] if i == j else 0.0 for j in range(n)] for i in range(n)], "A": A}


_DOUBLE_L = ("(m1 + m2)/2*l1**2*a_dot**2 + m2/2*l2**2*b_dot**2"
             " + m2*l1*l2*a_dot*b_dot*cos(a - b) + (m1 + m2)*g*l1*cos(a) + m2*g*l2*cos(b)")


@st.composite
def potential(draw):
    """A system written as formulas: the double pendulum from L (in and out of phase), or a
    well in one to three coordinates -- stable, or flat along the last coordinate (neutral)
    -- with a kinetic energy T or a mass matrix M(q); the guess beside the minimum."""
    if draw(st.booleans()):
        params = {k: draw(st.floats(0.3, 3.0)) for k in ("m1", "m2", "l1", "l2")}
        params["g"] = 9.81
        system = {"coordinates": ["a", "b"], "L": _DOUBLE_L,
                  "guess": {"a": draw(st.floats(-0.4, 0.4)), "b": draw(st.floats(-0.4, 0.4))}}
        return {"params": params, "system": system}
    n = draw(st.integers(1, 3))
    names = ["x", "y", "z"][:n]
    flat = n > 1 and draw(st.booleans())  # the last coordinate missing from U: neutral
    params = {f"k{i}": draw(st.floats(0.5, 4.0)) for i in range(n - flat)}
    terms = [f"k{i}/2*({c} - 0.5)**2 + {c}**4/4" for i, c in enumerate(names[:n - flat])]
    if n - flat > 1:
        params["c"] = draw(st.floats(0.1, 0.4))
        terms.append(f"c*({names[0]} - {names[1]})**2")
    system = {"coordinates": names, "U": " + ".join(terms),
              "guess": {c: draw(st.floats(0.2, 0.8)) for c in names}}
    if draw(st.booleans()):
        system["T"] = " + ".join(f"{1 + i}*{c}_dot**2/2" for i, c in enumerate(names))
    else:
        system["M"] = [[(f"1 + {c}**2" if i == j else 0.0) for j in range(n)]
                       for i, c in enumerate(names)]
    return {"params": params, "system": system}


@st.composite
def configs(draw):
    scene = draw(st.one_of(molecule(), molecule(), molecule(), chain(), pendula(),
                           matrices(), potential()))
    config = {"kind": "normal_modes", **scene}
    if "evolve" not in config and "atoms" not in config and draw(st.booleans()):
        n = (config["chain"]["n"] if "chain" in config else
             config["pendula"]["n"] if "pendula" in config else
             len(config["system"]["coordinates"]) if "system" in config else len(config["M"]))
        config["evolve"] = {"displacement": [0.05 * (s + 1) for s in range(n)],
                            "t_end": draw(st.floats(2.0, 10.0))}
    if "evolve" in config:
        config["run"] = {"samples": 401, "study": False}
    return config
