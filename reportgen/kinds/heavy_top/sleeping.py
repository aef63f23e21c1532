"""The heavy top asleep: the facts and words of a top started next to the vertical, and
the ``[sleeping]`` sweep across its threshold I3² ω3² = 4 I1 Mgl, notes (10.49)–(10.50)
(mixed into :class:`.simulation.HeavyTopSimulation`)."""

from __future__ import annotations

import math

import numpy as np

from ...lazy import lazy_module
from ...scene.content import fmt
from ...scene.results import Results

model_core = lazy_module("reportgen.core.models.heavy_top")
theory = lazy_module("reportgen.core.heavy_top_theory")
kinematics = lazy_module("reportgen.core.heavy_top_kinematics")
integrators = lazy_module("reportgen.core.integrators")


class SleepingTop:
    """A sleeping top's stored facts, its behaviour in words, and the ``[sleeping]`` sweep."""

    #: a start tilted less than this [rad] is a sleeping top: its behaviour is its stability
    SLEEPING_TILT = 1e-3
    #: a stable sleeping top "stays upright" while its lower turning circle θ2 is below this
    #: [rad] (~5.7°; a start with φ̇0 or θ̇0 can throw it out further)
    STAYS_UPRIGHT = 0.1
    #: a stable top's tilt "stays of the order of the initial" while θ2/θ1 is below this
    OF_THE_ORDER = 10.0
    #: an unstable top "tilts away" in a run whose largest tilt exceeds this many initial ones
    TILTS_AWAY = 10.0

    def _sleeping_facts(self, results: Results) -> dict:
        """What a sleeping top's words follow, each with its threshold: whether it stays
        upright (stable, θ2 < STAYS_UPRIGHT), whether its tilt stays of the order of the
        initial one (θ2/θ1 < OF_THE_ORDER), whether this run shows it tilting away (largest
        tilt ≥ TILTS_AWAY θ0)."""
        a = results.analysis
        theta0, theta2 = float(a["theta0"]), float(a["theta2"])
        reached = float(np.max(results.runs["main"]["theta"]))
        growth = theta2 / float(a["theta1"]) if a["theta1"] > 0 else math.nan
        return {"sleeping_top": True, "sleeping_tilt_below": self.SLEEPING_TILT,
                "tilt_growth": growth, "tilt_of_the_order_below": self.OF_THE_ORDER,
                "tilt_of_the_order": bool(a["sleeping_stable"] and theta0 > 0
                                          and growth < self.OF_THE_ORDER),
                "stays_upright": bool(a["sleeping_stable"] and theta2 < self.STAYS_UPRIGHT),
                "stays_upright_below": self.STAYS_UPRIGHT,
                "tilt_reached": reached, "tilts_away_factor": self.TILTS_AWAY,
                "tilted_away": bool(theta0 > 0 and reached >= self.TILTS_AWAY * theta0)}

    def _sleeping_behaviour(self, results: Results) -> str:
        """Stable or unstable, in words: ω3 against the threshold 2√(I1 Mgl)/I3, notes (10.50),
        the growth rate γ = √(Mgl/I1 − (I3 ω3/(2 I1))²) of a small tilt, and what this run
        did (:meth:`_sleeping_facts`)."""
        a = results.analysis
        w3, threshold, gamma = a["omega3"], a["sleeping_threshold_omega3"], \
            a["sleeping_growth_rate"]
        spin = (f"|ω3| = {fmt(abs(w3), 3)} rad/s is {'above' if a['sleeping_stable'] else 'below'}"
                f" the threshold 2√(I1 Mgl)/I3 = {fmt(threshold, 3)} rad/s")
        reached = (f"θ goes from {fmt(a['theta0'], 2)} to at most {fmt(a['tilt_reached'], 3)} "
                   "rad")
        grows = f"a small tilt grows as exp(γt), γ = √(Mgl/I1 − (I3 ω3/(2 I1))²) = {fmt(gamma, 3)} 1/s"
        if a["case"] == "sleeping":
            if a["sleeping_stable"]:
                return (f"stable equilibrium: the top starts exactly upright and stays there "
                        f"({spin}, so a small tilt would stay small; {reached})")
            return (f"unstable equilibrium: the top starts exactly upright and stays there only "
                    f"because nothing tilts it ({spin}: {grows}; {reached})")
        if a["sleeping_stable"]:
            upright = "the sleeping top stays upright" if a["stays_upright"] else (
                f"the upright is stable, but this start takes the axis out to θ2 = "
                f"{fmt(a['theta2'], 3)} rad")
            return f"stable: {upright} ({spin}; {reached})"
        away = "the sleeping top tilts away" if a["tilted_away"] else (
            "the upright is unstable, but this run is too short to show much of it")
        return f"unstable: {away} ({spin}); {grows}; {reached}"

    def _sleeping_sweep(self) -> dict:
        """Tops tilted by ``tilt`` at several spins across the threshold notes (10.50)."""
        p, sl, run = self.config.params, self.config.sleeping, self.config.run
        t_end = sl.t_end or run.t_end
        t = np.linspace(0.0, t_end, 1001)
        ratios = np.array(sorted(sl.omega3_over_threshold), dtype=float)
        thetas, status = [], []
        y0 = model_core.spin_free_initial_state(sl.tilt, 0.0, 0.0)
        for ratio in ratios:
            model = model_core.spin_free_model(p.I1, p.I3, p.Mgl, ratio * self.threshold)
            sol = integrators.integrate(model, y0, t, method="dop853", rtol=run.rtol, atol=run.atol)
            thetas.append(kinematics.tilt_angle(sol.y[:, :4]))  # F' and the body share θ
            status.append(sol.status)
        thetas = np.array(thetas)
        return {
            "t": t, "omega3_over_threshold": ratios, "omega3": ratios * self.threshold,
            "theta": thetas, "theta_max": thetas.max(axis=1), "tilt": sl.tilt,
            "growth_rate": np.array([theory.sleeping_growth_rate(p.I1, p.I3, p.Mgl,
                                                                 x * self.threshold)
                                     for x in ratios]),
            "status": [str(s) for s in status],
        }
