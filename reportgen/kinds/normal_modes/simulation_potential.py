"""``normal_modes`` from a potential written as formulas (``[system]``, textbook §5.1): the
equilibrium found from the guess, M and A there, and what the archive keeps of them."""

from __future__ import annotations

import numpy as np

from ...lazy import lazy_module
from ...scene.config import ConfigError
from ...scene.schema import symbol_text
from .config import NormalModesConfig

small_oscillations = lazy_module("reportgen.core.small_oscillations")

#: a mode of two coordinates is named in or out of phase only when both move by at least
#: this share of the larger (else a coordinate barely moves and the sign says nothing)
PHASE_SHARE = 1e-6


class PotentialSimulation:
    """The equilibrium of a written U(q) or L(q, q̇) and the matrices M and A there
    (mixed into the kind's simulation; ``config.system`` is set)."""

    config: NormalModesConfig

    def _refused(self, key: str, detail: str) -> ConfigError:
        return ConfigError([f"{self.source.label}: key '{key}': {detail}"])

    def formula_system(self):
        """The parsed system (memoized; SymPy work): U, its derivatives, M(q)."""
        if getattr(self, "_formula_system", None) is None:
            s = self.config.system
            try:
                self._formula_system = small_oscillations.potential_system(
                    s.coordinates, U=s.U, T=s.T, M=s.M, L=s.L, params=self.config.params)
            except small_oscillations.PotentialError as exc:
                raise self._refused(exc.key, exc.detail) from None
        return self._formula_system

    def guess(self) -> np.ndarray:
        """The search's start: ``system.guess``, 0 for a coordinate it leaves out."""
        s = self.config.system
        return np.array([float(s.guess.get(c, 0.0)) for c in s.coordinates])

    def equilibrium(self):
        """The stationary point found from the guess, with M and A there (memoized).

        ConfigError (exit 2, nothing run) when none is found, when M is not positive
        definite there, or when it is not a minimum of U: small oscillations about a
        maximum or saddle grow (textbook §5.1 expands about a *stable* equilibrium)."""
        if getattr(self, "_equilibrium", None) is None:
            system = self.formula_system()
            try:
                found = small_oscillations.find_equilibrium(system, self.guess())
            except small_oscillations.PotentialError as exc:
                raise self._refused(exc.key, exc.detail) from None
            if found.stability == "unstable":
                where = small_oscillations.where_text(system, found.q)
                raise self._refused("system.guess", (
                    f"the stationary point found from the guess "
                    f"({small_oscillations.where_text(system, found.guess)}) is {where}, not a "
                    f"minimum of U: A a = ω² M a has ω² = {float(found.omega2.min()):.6g} < 0 "
                    "(a maximum or saddle, unstable); small oscillations need a stable "
                    "equilibrium: start the search nearer a minimum"))
            self._equilibrium = found
        return self._equilibrium

    def coordinate_symbols(self) -> list[str]:
        """Each coordinate's symbol as TeX: ``theta1`` -> ``\\theta_{1}``."""
        return self.formula_system().coordinate_tex()

    def coordinate_words(self) -> list[str]:
        """Each coordinate's symbol as text (θ₁), its name where text has no spelling."""
        return [symbol_text(tex) or name
                for tex, name in zip(self.coordinate_symbols(), self.config.system.coordinates,
                                     strict=True)]

    def exact_potential_frequencies(self) -> tuple[np.ndarray, str] | None:
        """Two coordinates: ω from the secular equation, a quadratic in ω², in closed form."""
        if len(self.config.system.coordinates) != 2:
            return None
        found = self.equilibrium()
        omega2 = small_oscillations.secular_omega2(found.M, found.A)
        return (np.sqrt(np.clip(omega2, 0.0, None)),
                "det(A − ω² M) = 0 for two coordinates: a quadratic in ω², solved in closed "
                "form for the frequencies (textbook §5.1)")

    def potential_mode_types(self, modes) -> list[str]:
        """Two coordinates: each vibration "in phase" or "out of phase" by the signs of its
        components (both moving by at least :data:`PHASE_SHARE` of the larger); otherwise,
        and for more coordinates, "normal mode"; zero modes "zero mode (neutral)"."""
        types = ["zero mode (neutral)"] * modes.n_zero
        for k in range(modes.n_zero, modes.modes.shape[1]):
            eta = modes.modes[:, k]
            both = eta.size == 2 and float(np.min(np.abs(eta))) >= PHASE_SHARE * float(
                np.max(np.abs(eta)))
            types.append(("in phase" if eta[0] * eta[1] > 0 else "out of phase") if both
                         else "normal mode")
        return types

    def potential_analysis(self, results) -> None:
        """What the archive keeps of the equilibrium and of the written system."""
        system, found = self.formula_system(), self.equilibrium()
        a = results.analysis
        a.update({
            "given": system.given,
            "coordinate_symbols": self.coordinate_symbols(),
            "potential_latex": system.latex(system.U),
            "equilibrium_guess": found.guess, "equilibrium": found.q,
            "equilibrium_potential": found.potential,
            "equilibrium_gradient": found.gradient,
            "equilibrium_gradient_norm": found.gradient_norm,
            "equilibrium_residual": found.residual,
            "equilibrium_residual_tol": small_oscillations.STATIONARY_RTOL,
            "equilibrium_evaluations": found.evaluations,
            "hessian_positive_definite": found.stability == "stable",
            "equilibrium_stability": found.stability,
            "hessian_finite_difference": found.hessian_fd_difference,
            "finite_difference_step": found.fd_step,
        })
        if system.L is not None:
            a["lagrangian_latex"] = system.latex(system.L)
        if system.T is not None:
            a["kinetic_latex"] = system.latex(system.T)
        if self.config.system.coordinate_unit is not None:
            a["coordinate_unit"] = self.config.system.coordinate_unit
