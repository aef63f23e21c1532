"""t(u) = ∫du/√f(u) of the heavy top continued over its Riemann surface (textbook ex. 4.10).

The top's cubic (notes (10.31); the textbook's (4.38)) is f(u) = β(u − u_X)(u − u_N)(u − u_U)
with u_X < u_N ≤ 1 < u_U (the textbook's names: u_X = cos θmax at the bottom of a wobble,
u_N = cos θmin, u_U the root past u = 1).  Written in v = u − u_X with the root gaps
d_N = u_N − u_X and d_U = u_U − u_X (so no digits cancel),

    w(v) = −√β · √v · √(v − d_N) · √(v − d_U)        (principal square roots)

is one branch of √f: each principal root is cut to the left of its zero, so the product
jumps sign on (−∞, 0) (three cut factors) and on (d_N, d_U) (one), and is continuous on
(0, d_N) (two) and (d_U, ∞) (none), where it is > 0 and < 0.  It is the textbook's first
sheet exactly: analytic off the cuts (−∞, u_X] and [u_N, u_U], with √f > 0 on (u_X, u_N).
The second sheet is −w.  A path here is a polyline; where a segment crosses the real axis
inside a cut it passes to the other sheet, elsewhere it stays (no tracking of a numerical
root by continuity, which can jump).

Each straight segment is integrated by Gauss–Legendre on panels, adaptively (two rules of
16 and 32 nodes must agree), through u = A + (B − A) sin²(πs/2) when an end is a branch
point (dv/w is then smooth in s), and through v = d_U sec²φ for the ray (d_U, ∞), where
dv/w = −2dφ/√(β(d_U − d_N cos²φ)) has no singularity left at either end.

Closed forms the results are checked against (notes §10.1; DLMF 19.2.8, 22.2): with
k² = d_N/d_U and λ = ½√(β d_U), the real period T = 2K(k²)/λ and the imaginary one
τ = 2K(1 − k²)/λ; the corners of ex. 4.10(a)'s rectangle are t(u_X) = 0, t(u_N) = T/2,
t(u_U) = T/2 + iτ/2 and t(∞) = iτ/2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .special import ellipk_carlson

_X16, _W16 = np.polynomial.legendre.leggauss(16)
_X32, _W32 = np.polynomial.legendre.leggauss(32)
#: an adaptive segment stops splitting once its two rules agree to this (relative to the
#: magnitude of the segment's integral, or absolutely when that is 0) ...
_RTOL = 1e-13
#: ... or after this many halvings of a panel
_MAX_DEPTH = 30


@dataclass(frozen=True)
class TopCubic:
    """f(u) = β(u − u_X)(u − u_N)(u − u_U) by its gaps; v = u − u_X."""

    beta: float
    u_X: float
    d_N: float  # u_N − u_X > 0
    d_U: float  # u_U − u_X > d_N

    @property
    def branch_points(self) -> tuple[float, float, float]:
        return (0.0, self.d_N, self.d_U)

    @property
    def m(self) -> float:
        """k² = (u_N − u_X)/(u_U − u_X)."""
        return self.d_N / self.d_U

    @property
    def rate(self) -> float:
        """λ = ½√(β(u_U − u_X))."""
        return 0.5 * math.sqrt(self.beta * self.d_U)

    @property
    def period(self) -> float:
        """T = 2K(k²)/λ, the nutation period (the rectangle's width 2 × T/2)."""
        return 2.0 * ellipk_carlson(1.0 - self.m) / self.rate

    @property
    def imaginary_period(self) -> float:
        """τ = 2K(1 − k²)/λ (the rectangle's height 2 × τ/2)."""
        return 2.0 * ellipk_carlson(self.m) / self.rate

    def root(self, v, sheet: int = 1, offsets=None):
        """The branch of √f on ``sheet`` (1 or −1) at ``v`` (complex; a real v on a cut is
        taken on the side of the sign of its zero imaginary part: +0 above, −0 below).
        ``offsets``: v − 0, v − d_N, v − d_U when the caller has them without cancellation."""
        if offsets is None:
            v = np.asarray(v, dtype=np.complex128)
            offsets = (v, v - self.d_N, v - self.d_U)
        x, y, z = offsets
        return (-sheet * math.sqrt(self.beta)) * np.sqrt(x) * np.sqrt(y) * np.sqrt(z)

    def on_cut(self, x: float) -> bool:
        """Whether the real point v = x lies inside a cut (crossing there changes sheet)."""
        return x < 0.0 or self.d_N < x < self.d_U


def _panel(g, a: float, b: float) -> tuple[complex, complex]:
    """∫_a^b g(s) ds by the 32- and the 16-node rule."""
    mid, half = 0.5 * (a + b), 0.5 * (b - a)
    hi = half * np.sum(_W32 * g(mid + half * _X32))
    lo = half * np.sum(_W16 * g(mid + half * _X16))
    return complex(hi), complex(lo)


def _adaptive(g, a: float = 0.0, b: float = 1.0) -> complex:
    """∫_a^b g(s) ds, halving panels until the two rules agree."""
    whole, _ = _panel(g, a, b)
    scale = max(abs(whole), 1e-300)
    total = 0.0 + 0.0j
    stack = [(a, b, 0)]
    while stack:
        lo_s, hi_s, depth = stack.pop()
        hi, lo = _panel(g, lo_s, hi_s)
        if abs(hi - lo) <= _RTOL * scale or depth >= _MAX_DEPTH:
            total += hi
        else:
            mid = 0.5 * (lo_s + hi_s)
            stack += [(mid, hi_s, depth + 1), (lo_s, mid, depth + 1)]
    return total


def segment(cubic: TopCubic, A: complex, B: complex, sheet: int = 1, side: int = 1) -> complex:
    """∫_A^B dv/w on ``sheet`` along the straight segment (which must not cross the real
    axis; ``side``: the half-plane a segment lying on the axis is taken in)."""
    A, B = complex(A), complex(B)
    d = B - A
    points = cubic.branch_points
    singular = any(z == p for z in (A, B) for p in points)
    on_axis = A.imag == 0.0 and B.imag == 0.0

    def offsets(s):
        """v − p for each branch point p at the parameter s, exact at an end p = A or B."""
        if singular:  # v = A + d sin²(πs/2); v − B = −d cos²(πs/2)
            sin2, cos2 = np.sin(0.5 * np.pi * s) ** 2, np.cos(0.5 * np.pi * s) ** 2
            out = [d * sin2 if p == A else (-d * cos2 if p == B else (A - p) + d * sin2)
                   for p in points]
        else:
            out = [(A - p) + d * s for p in points]
        if on_axis:  # on the axis itself: the side's signed zero imaginary part
            out = [o.real.astype(np.complex128) for o in out]
            out = out if side > 0 else [np.conj(o) for o in out]
        return out

    if singular:  # dv = d (π/2) sin(πs) ds, and dv/w is smooth in s
        def g(s):
            return d * 0.5 * np.pi * np.sin(np.pi * s) / cubic.root(None, sheet, offsets(s))
    else:
        def g(s):
            return d / cubic.root(None, sheet, offsets(s))
    return _adaptive(g)


def to_infinity_right(cubic: TopCubic, sheet: int = 1) -> complex:
    """∫ dv/w from u_U to +∞ along the real axis (from above), v = d_U sec²φ: the top side
    of ex. 4.10(a)'s rectangle; −T/2 on the first sheet."""
    def g(phi):
        return -2.0 * sheet / np.sqrt(cubic.beta * (cubic.d_U - cubic.d_N * np.cos(phi) ** 2))
    return _adaptive(g, 0.0, 0.5 * math.pi) + 0.0j


def to_infinity_left(cubic: TopCubic, sheet: int = 1) -> complex:
    """∫ dv/w from u_X to −∞ along the real axis (from above), v = −d_U tan²φ: the left
    side of the rectangle; iτ/2 on the first sheet."""
    def g(phi):  # v = −d_U tan²φ: dv = −2 d_U tanφ sec²φ dφ
        v = -cubic.d_U * np.tan(phi) ** 2 + 0.0j
        dv = -2.0 * cubic.d_U * np.tan(phi) / np.cos(phi) ** 2
        return dv / cubic.root(v, sheet)
    return _adaptive(g, 0.0, 0.5 * math.pi)


def path(cubic: TopCubic, points, sheet: int = 1) -> tuple[complex, int]:
    """∫ dv/w along the polyline ``points`` (v values, the first a start of known t = 0 such
    as u_X, v = 0), starting on ``sheet``: the integral and the sheet it ends on.  A segment
    crossing the real axis is split there and continues on the other sheet when the crossing
    lies inside a cut.  A corner may not lie on a cut (ValueError); a path that starts on
    the axis is taken from above until it leaves it."""
    total = 0.0 + 0.0j
    side = 1
    pts = [complex(p) for p in points]
    for p in pts[1:-1]:  # (an end on a cut is taken from above, as on the axis)
        if p.imag == 0.0 and cubic.on_cut(p.real):
            raise ValueError(f"a path's corner {p} lies on a cut: which side is meant?")
    for A, B in zip(pts[:-1], pts[1:], strict=True):
        if A.imag * B.imag < 0.0:  # crosses the axis at x
            x = A.real - A.imag * (B.real - A.real) / (B.imag - A.imag)
            total += segment(cubic, A, complex(x, 0.0), sheet)
            if cubic.on_cut(x):
                sheet = -sheet
            total += segment(cubic, complex(x, 0.0), B, sheet)
        else:
            total += segment(cubic, A, B, sheet, side)
        if B.imag != 0.0:
            side = 1 if B.imag > 0.0 else -1
    return total, sheet


def march(cubic: TopCubic, start: complex, t_start: complex, points, sheet: int = 1) -> np.ndarray:
    """t at each of ``points`` (a curve that crosses no cut), continuing from ``t_start``
    at ``start``: the integral accumulated segment by segment."""
    out = np.empty(len(points), dtype=np.complex128)
    t, here = complex(t_start), complex(start)
    for i, p in enumerate(points):
        t += path(cubic, [here, p], sheet)[0]
        out[i] = t
        here = complex(p)
    return out


@dataclass
class ContourMap:
    """Ex. 4.10(a)–(e) computed: the corners, the sides' pre-images, the four images of the
    grid (first sheet above and below the axis, second sheet through either cut), the loop
    round [u_N, u_U] (``loop``, iτ) and the one round [u_X, u_N] through both cuts
    (``corners["loop_real"]``, T), and each claim's defect [s] against its closed form."""

    cubic: TopCubic
    grid_v: np.ndarray  # complex, (lines, points): the grid in the upper half-plane
    images: dict[str, np.ndarray]  # complex, same shape: "upper", "lower", "left", "right"
    corners: dict[str, complex]
    sides: dict[str, float]  # the largest distance of a real piece's image from its side
    defects: dict[str, float]
    loop: complex


def _grid(cubic: TopCubic, lines: int = 9, points: int = 97) -> np.ndarray:
    """Horizontal lines Im v = y in the upper half-plane, y geometric from d_N/20 to 4 d_U,
    over Re v from −3 d_U to 4 d_U (and points crowded near the branch points)."""
    ys = np.geomspace(0.05 * cubic.d_N, 4.0 * cubic.d_U, lines)
    s = np.linspace(-1.0, 1.0, points)
    xs = 0.5 * cubic.d_U + 3.5 * cubic.d_U * np.sign(s) * np.abs(s) ** 1.5
    return xs[None, :] + 1j * ys[:, None]


def contour_map(cubic: TopCubic, lines: int = 9, points: int = 97) -> ContourMap:
    """Textbook ex. 4.10(a)–(e) for the top of ``cubic``, by contour integration (see the
    module docstring).  Defects are absolute, in the units of t."""
    T, tau = cubic.period, cubic.imaginary_period
    d_N, d_U = cubic.d_N, cubic.d_U
    grid = _grid(cubic, lines, points)
    # (a) the first sheet above the axis: up from u_X to the line's left end, then along it
    upper = np.empty_like(grid)
    for j, line in enumerate(grid):
        first = path(cubic, [0.0, line[0]])[0]
        upper[j] = march(cubic, line[0], first, line)
    # (b) below the axis through (u_X, u_N): from u_X to the midpoint, straight down to
    # the line's height, along it (never near a branch point)
    mid = 0.5 * d_N
    lower = np.empty_like(grid)
    for j, line in enumerate(np.conj(grid)):
        first = path(cubic, [0.0, mid, complex(mid, line[0].imag), line[0]])[0]
        lower[j] = march(cubic, line[0], first, line)
    # (c) to the second sheet through (−∞, u_X): down through the cut at −d_U/2, then on;
    # (d) through (u_N, u_U): down through the cut at its middle.  Each image is taken of
    # the lower half-plane's grid (the second sheet's points below the axis)
    h = 0.5 * d_U
    left = np.empty_like(grid)
    right = np.empty_like(grid)
    for j, line in enumerate(np.conj(grid)):
        for image, x in ((left, -0.5 * d_U), (right, 0.5 * (d_N + d_U))):
            first, sheet = path(cubic, [0.0, complex(x, h), complex(x, -h), line[0]])
            assert sheet == -1
            image[j] = march(cubic, line[0], first, line, sheet=-1)
    # corners and the real pieces approached from above
    t_N = segment(cubic, 0.0, d_N)
    t_U = t_N + segment(cubic, d_N, d_U)
    t_inf = t_U + to_infinity_right(cubic)
    t_inf_left = to_infinity_left(cubic)
    pieces = {
        "bottom": np.linspace(0.0, d_N, 41)[1:-1],
        "right": np.linspace(d_N, d_U, 41)[1:-1],
        "top": d_U * np.linspace(1.0, 40.0, 41)[1:],
        "left": -d_U * np.geomspace(1e-3, 40.0, 40),
    }
    images = {"bottom": march(cubic, 0.0, 0.0, pieces["bottom"]),
              "right": march(cubic, d_N, t_N, pieces["right"]),
              "top": march(cubic, d_U, t_U, pieces["top"]),
              "left": march(cubic, 0.0, 0.0, pieces["left"])}
    sides = {"bottom": float(np.max(np.abs(images["bottom"].imag))),
             "right": float(np.max(np.abs(images["right"].real - 0.5 * T))),
             "top": float(np.max(np.abs(images["top"].imag - 0.5 * tau))),
             "left": float(np.max(np.abs(images["left"].real)))}
    # (e) the loop round [u_N, u_U], clockwise: above it left to right, back below it; it
    # crosses the axis in (u_X, u_N) and past u_U, outside the cuts, so it stays on sheet 1
    a, b = 0.5 * d_N, d_U + 0.5 * (d_U - d_N)
    loop, end_sheet = path(cubic, [a, complex(a, h), complex(b, h), complex(b, -h),
                                   complex(a, -h), a])
    assert end_sheet == 1
    # ... and round [u_X, u_N], which crosses both cuts (so it closes on the first sheet)
    m = complex(0.5 * d_N, h)
    loop_real, end_sheet = path(cubic, [m, complex(0.5 * (d_N + d_U), h),
                                        complex(0.5 * (d_N + d_U), -h), complex(-0.5 * d_N, -h),
                                        complex(-0.5 * d_N, h), m])
    assert end_sheet == 1
    corners = {"u_N": t_N, "u_U": t_U, "infinity": t_inf, "infinity_left": t_inf_left,
               "loop_real": loop_real}
    defects = {
        "corner_u_N": abs(t_N - 0.5 * T),
        "corner_u_U": abs(t_U - complex(0.5 * T, 0.5 * tau)),
        "corner_infinity": abs(t_inf - 0.5j * tau),
        "infinity_both_ways": abs(t_inf - t_inf_left),
        "sides": max(sides.values()),
        "upper_in_rectangle": _outside(upper, 0.0, 0.5 * T, 0.0, 0.5 * tau),
        "lower_reflection": float(np.max(np.abs(lower - np.conj(upper)))),
        "lower_in_rectangle": _outside(lower, 0.0, 0.5 * T, -0.5 * tau, 0.0),
        "second_sheet_left": float(np.max(np.abs(left + lower))),
        "second_sheet_right": float(np.max(np.abs(right - (T - lower)))),
        "loop": abs(loop - 1j * tau),
        "loop_real": abs(loop_real - T),
    }
    return ContourMap(cubic, grid, {"upper": upper, "lower": lower, "left": left,
                                    "right": right}, corners, sides, defects, loop)


def _outside(t: np.ndarray, x0: float, x1: float, y0: float, y1: float) -> float:
    """How far the farthest of ``t`` lies outside the rectangle [x0, x1] × [y0, y1] (0 when
    all are in it)."""
    dx = np.maximum(np.maximum(x0 - t.real, t.real - x1), 0.0)
    dy = np.maximum(np.maximum(y0 - t.imag, t.imag - y1), 0.0)
    return float(np.max(np.hypot(dx, dy)))
