"""How a run ended: the one status vocabulary, from the compiled drivers to the report.

Every :class:`Status` member is spelled three ways, all defined here and nowhere else:

* its value, a string (``"step_underflow"``): :attr:`.base.Solution.code`, the solver
  policy's ``solver_status`` (:data:`.base.RunStatus` is this enum; the policy archives
  only :data:`POLICY_STATUSES`),
  the sweep's per-member status (:data:`reportgen.core.ensemble.STATUS_NAMES`);
* its integer :attr:`~Status.code`: what a compiled driver returns.  The drivers use the
  plain ``int`` constants :mod:`.compiled` makes from these (``compiled.UNDERFLOW =
  Status.STEP_UNDERFLOW.code``), which numba freezes into the machine code;
  :meth:`Status.from_code` reads a returned code back;
* its :attr:`~Status.verdict`, the archived run ``status``: ``"ok"``, ``"unstable"`` or
  ``"failed"``.  (The fourth run status, ``"inaccurate"``, is no solver outcome: a run that
  ended ok is judged against its reference afterwards,
  :meth:`reportgen.scene.simulation.Simulation.judge_accuracy`.)

Pure Python (no numba): listing the methods imports this module.
"""

from __future__ import annotations

import enum


class Status(enum.StrEnum):
    """How one run ended (the value is its archived spelling; ``code`` the driver's int)."""

    def __new__(cls, value: str, code: int, verdict: str):
        member = str.__new__(cls, value)
        member._value_ = value
        member._code = code
        member._verdict = verdict
        return member

    OK = "ok", 0, "ok"
    #: the state, the right-hand side at the end of an attempt, or the step size became
    #: NaN or inf (an adaptive run: the last attempted step was not finite)
    NONFINITE = "nonfinite", 1, "failed"
    #: the adaptive step fell below 10 eps |t| (or t + h == t) with finite values
    STEP_UNDERFLOW = "step_underflow", 2, "failed"
    #: the step budget (``max_steps``: attempted steps, accepted and rejected) ran out,
    #: or a fixed step needs more steps than the budget
    MAX_STEPS = "max_steps", 3, "failed"
    #: the Newton iteration of an implicit method did not converge
    NEWTON = "newton", 4, "failed"
    #: a period measured on an ensemble (a kind's sweep): the member cannot oscillate
    #: (initial state or parameters outside the libration region, or not finite)
    NOT_LIBRATING = "not_librating", 5, "failed"
    #: a period measured on an ensemble: fewer than two crossings before the horizon
    NO_PERIOD = "no_period", 6, "failed"
    #: a fixed-step kernel was given a step it cannot take: h not positive and finite, or
    #: more than ``compiled.MAX_FIXED_STEPS`` steps in one output interval
    BAD_STEP = "bad_step", 7, "failed"
    #: a peer (scipy) solver reported failure
    SOLVER_ERROR = "solver_error", 8, "failed"
    # the solver policy's own outcomes (:data:`.base.RunStatus` is this enum)
    #: a method named explicitly looks stiff (kept, flagged)
    STIFF = "stiff", 9, "unstable"
    #: the automatic choice met stiffness and used an implicit method
    SWITCHED = "switched", 10, "ok"
    #: any other failure, as the policy archives it (step underflow, Newton, scipy, ...)
    FAILED = "failed", 11, "failed"

    @property
    def code(self) -> int:
        """The integer a compiled driver returns for this status."""
        return self._code

    @property
    def verdict(self) -> str:
        """The archived run ``status``: ``"ok"``, ``"unstable"`` or ``"failed"``."""
        return self._verdict

    @property
    def policy(self) -> Status:
        """The status the solver policy archives for a run that ended so (its
        ``solver_status``): itself when the policy names it, else FAILED."""
        return self if self in POLICY_STATUSES else Status.FAILED

    @classmethod
    def from_code(cls, code: int) -> Status:
        """The status of a driver's integer ``code``."""
        return _BY_CODE[int(code)]


#: the statuses the solver policy archives as ``solver_status`` (:func:`.policy.solve`)
POLICY_STATUSES = frozenset({Status.OK, Status.STIFF, Status.MAX_STEPS, Status.NONFINITE,
                             Status.FAILED, Status.SWITCHED})
_BY_CODE = {s.code: s for s in Status}
assert len(_BY_CODE) == len(Status), "status codes must be distinct"
