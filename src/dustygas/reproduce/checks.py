"""Quantitative checks of a figure: a number from its data against a published or analytic value.

A figure declares its checks with ``@figure(..., checks=my_checks)``; ``my_checks(output)``
reads the files the figure wrote into ``output`` and returns a list of :class:`Check`. The
gallery shows each one (pass/fail with the values), ``dustygas reproduce`` prints them and
exits with status 1 if one fails::

    def fig3_5_checks(output: Path) -> list[Check]:
        data = read_table(output / "fig3_5.csv")
        peak = data["minus_vr_over_vK"].max()
        return [compare("peak -v_r/v_K (eq. 3.23 at tau_s = 1)", peak, 3.7688e-3, rtol=1e-3)]

>>> compare("pi", 3.14159, 3.141592653589793, rtol=1e-5).passed
True
>>> compare("pi", 3.0, 3.141592653589793, rtol=1e-3).describe()
'pi: 3 vs 3.14159 (rtol 0.001): FAIL'

A check whose premise the data do not meet (a run too short to judge a steady state, say) is
made with :func:`not_judged`: it is neither passed nor failed, and every report says so with its
reason; a figure with such a check still passes if no other check fails.

>>> not_judged("steady layer", 1.17, "the run is 10 orbits, a steady state needs 20").describe()
'steady layer: 1.17 not judged (the run is 10 orbits, a steady state needs 20)'
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

__all__ = ["Check", "compare", "within", "not_judged", "verdict"]


@dataclass(frozen=True)
class Check:
    """One quantitative check: ``value`` against ``expected`` within ``tolerance``.

    ``reference`` names where ``expected`` comes from (an equation, a paper, a table).
    ``judged`` is False for a check the data cannot decide (:func:`not_judged`; ``passed`` is
    then False too, and ``tolerance`` holds the reason).
    """

    name: str
    value: float
    expected: float | str
    tolerance: str
    passed: bool
    reference: str = ""
    judged: bool = True

    def describe(self) -> str:
        """One line: ``name: value vs expected (tolerance): PASS|FAIL``, or ``name: value not
        judged (reason)``."""
        if not self.judged:
            return f"{self.name}: {self.value:.6g} not judged ({self.tolerance})"
        exp = f"{self.expected:.6g}" if isinstance(self.expected, (int, float)) else str(self.expected)
        return f"{self.name}: {self.value:.6g} vs {exp} ({self.tolerance}): {'PASS' if self.passed else 'FAIL'}"

    def to_dict(self) -> dict[str, Any]:
        out = asdict(self)
        for key in ("value", "expected"):
            if isinstance(out[key], float) and not math.isfinite(out[key]):
                out[key] = str(out[key])
        return out


def compare(name: str, value: float, expected: float, rtol: float | None = None, atol: float | None = None,
            reference: str = "") -> Check:
    """``|value - expected| <= atol + rtol |expected|`` (give ``rtol``, ``atol`` or both)."""
    if rtol is None and atol is None:
        raise ValueError("compare: give rtol or atol")
    r, a = rtol or 0.0, atol or 0.0
    value, expected = float(value), float(expected)
    ok = math.isfinite(value) and abs(value - expected) <= a + r * abs(expected)
    parts = ([f"rtol {r:g}"] if rtol is not None else []) + ([f"atol {a:g}"] if atol is not None else [])
    return Check(name, value, expected, ", ".join(parts), bool(ok), reference)


def within(name: str, value: float, low: float, high: float, reference: str = "") -> Check:
    """``low <= value <= high``."""
    value = float(value)
    ok = math.isfinite(value) and low <= value <= high
    return Check(name, value, f"[{low:.6g}, {high:.6g}]", "range", bool(ok), reference)


def not_judged(name: str, value: float, reason: str, reference: str = "") -> Check:
    """A check the data cannot decide, with the ``reason`` (shown in its place of a tolerance)."""
    return Check(name, float(value), "not judged", reason, False, reference, judged=False)


def verdict(check: dict[str, Any]) -> str:
    """``PASS``, ``FAIL`` or ``NOT JUDGED`` for a check as stored in a manifest (:meth:`Check.to_dict`)."""
    if not check.get("judged", True):
        return "NOT JUDGED"
    return "PASS" if check["passed"] else "FAIL"
