"""Constrained 12-state coaxial structures: freedoms of the near/far-wake model removed by name.

The 12-state near/far-wake model fitted to our coaxial hover wake
(:class:`~aircraft.identification.Coaxial12State` with delays and far-wake
loads, shipped as ``coaxial_hover_12state``) has four flat directions and
Cramér-Rao bounds up to ~1000 %. Most of its poorly determined parameters sit in
the collective near/far block: our collective lambda/C block is nearly rank-one
(the 6-state's diagnosis), so apparent mass and inflow gain are fixed only in
combination, and a second (far-wake) collective state adds a further free time
scale. :class:`Coaxial12StateConstrained` removes such freedoms by name:

* ``collective_far_wake=False``: the far-wake collective states ``lam0F`` are
  switched off (their rows of F and G are zero, the pole a constant -1 per
  radian of azimuth, never excited), so the collective is first order, as in the
  6-state models;
* ``a_priori``: parameters held at given values (constants of the structure, not
  parameters; tied 1c entries follow their 1s partner with its sign), e.g. the
  collective near-wake ``G`` diagonal at the inverse Pitt-Peters apparent mass
  ``3 pi / 8`` (:data:`PITT_PETERS_COLLECTIVE_GAIN`; with no lower-to-upper mass
  coupling ``G = M^-1`` has exactly this diagonal);
* ``without``: parameters removed (held at zero), e.g. the cross-rotor far-far
  cyclic couplings ``f4_10`` and ``f10_4``: on our wake ``f4_10`` forms a flat
  direction with ``f4_9`` (it scales a far-wake state that barely reaches the
  outputs), and ``f10_4`` takes its place when it alone is removed.
"""
from __future__ import annotations

import math

import numpy as np

from .base import PITT_PETERS_M11
from .hover import _F_FREE, Coaxial12State, _eq62_inputs

__all__ = ["Coaxial12StateConstrained", "PITT_PETERS_COLLECTIVE_GAIN", "VARIANTS"]

PITT_PETERS_COLLECTIVE_GAIN = {"g1_1": 1.0 / PITT_PETERS_M11, "g7_6": 1.0 / PITT_PETERS_M11}

_COLLECTIVE_FAR_ROWS = (2, 8)    # lam0F_U, lam0F_L (1-based, Eq. 6.2 order)


class Coaxial12StateConstrained(Coaxial12State):
    """:class:`Coaxial12State` (tied, with delays and far-wake loads) with freedoms removed by name.

    Parameters
    ----------
    collective_far_wake : bool
        Keep the far-wake collective states (default True: Eq. 6.3). False makes
        the collective first order (their rows of F and G zero).
    a_priori : mapping of str to float, optional
        Parameters held at these values (per radian of azimuth, as every F/G
        entry); they are constants of the structure and part of its identity
        (:meth:`spec`).
    without : iterable of str
        Parameters held at zero.
    frame : {"rotor", "printed"}
    rotors : (str, str), optional
        Upper and lower rotor names of the signals (default ``("U", "L")``).

    Raises
    ------
    ValueError
        An unknown or repeated name, a name both held and removed, or a value
        that is not a finite real number.
    """

    key = "coaxial_12state_constrained"

    def __init__(self, collective_far_wake=True, a_priori=None, without=(), frame="rotor", *, rotors=None):
        super().__init__(frame=frame, tied=True, delays=True, far_wake_loads=True, rotors=rotors)
        self.collective_far_wake = bool(collective_far_wake)
        rows_off = () if self.collective_far_wake else _COLLECTIVE_FAR_ROWS
        self._f_entries = [(i, j) for i, j in _F_FREE if i not in rows_off]
        self._g_free = [(i, j) for i, j in self._g_free if i not in rows_off]
        known = set(super().parameter_names())
        if not self.collective_far_wake:   # the names the switched-off rows carried
            known = {n for n in known if not any(n.startswith(f"{p}{r}_") for p in "fg" for r in rows_off)}
        self.a_priori = {}
        for name, value in dict(a_priori or {}).items():
            if name not in known:
                raise ValueError(f"a_priori names {name!r}, not a parameter of this structure; it has "
                                 f"{sorted(known)[:8]}...")
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"a_priori value of {name!r} must be a finite real number, got {value!r}") from None
            if not math.isfinite(value):
                raise ValueError(f"a_priori value of {name!r} must be a finite real number, got {value!r}")
            self.a_priori[name] = value
        if isinstance(without, str):
            without = [without]
        self.without = tuple(sorted(set(without)))
        bad = [n for n in self.without if n not in known]
        if bad:
            raise ValueError(f"without names {bad}, not parameters of this structure")
        both = sorted(set(self.without) & set(self.a_priori))
        if both:
            raise ValueError(f"{both} both held a priori and removed")

    def spec(self):
        out = super().spec()
        out["constrained"] = {"collective_far_wake": self.collective_far_wake,
                              "a_priori": dict(sorted(self.a_priori.items())), "without": list(self.without)}
        return out

    def __repr__(self):
        return (f"Coaxial12StateConstrained(collective_far_wake={self.collective_far_wake}, "
                f"a_priori={self.a_priori!r}, without={self.without!r}{self._rotors_repr()})")

    def _entry(self, p, i, j):
        """Pattern entry (i, j) (1-based): a name, or a constant when held or removed."""
        name = self._name(p, i, j)
        base, sign = name.lstrip("-"), (-1.0 if name.startswith("-") else 1.0)
        if base in self.without:
            return 0
        if base in self.a_priori:
            return sign * self.a_priori[base]
        return name

    def _tau_pattern(self):
        """The delays' pattern with the removed ones zero and the held ones at their values."""
        tau = super()._tau_pattern()
        if tau is None:
            return None
        # delays carry no sign in the ties, so a name is the parameter itself; the
        # base class asks before the constraints are set (then there are none)
        without, held = getattr(self, "without", ()), getattr(self, "a_priori", {})
        return [[(0 if n in without else held.get(n, n)) if isinstance(n, str) else n
                 for n in row] for row in tau]

    def build(self, initial, omega, fixed=()):
        from flightid import FGCStructure
        return self._assemble(FGCStructure, *self._fgc_patterns(), initial, omega, fixed)

    def _assemble(self, cls, F, G, C, tau, initial, omega, fixed):
        """``cls(F, G, C, tau, ...)`` with this structure's parameters started at ``initial``."""
        names = set(self.parameter_names())
        init = {n: float(v) for n, v in dict(initial).items() if n in names}
        missing = names - set(init)
        if missing:
            raise KeyError(f"no initial value for {sorted(missing)[:6]}... ({len(missing)} parameters)")
        return cls(F, G, C, tau, inputs=self.inputs, outputs=self.outputs, initial=init,
                   fixed=[f for f in fixed if f in names], omega=omega, states=self.states)

    def _fgc_patterns(self):
        """``F`` (12 x 12), ``G`` (12 x inputs) patterns, ``C`` (6 x 12) and the delays' pattern."""
        F = [[0] * 12 for _ in range(12)]
        for i, j in self._f_entries:
            F[i - 1][j - 1] = self._entry("f", i, j)
        if not self.collective_far_wake:
            for r in _COLLECTIVE_FAR_ROWS:     # a stable constant pole: the state is never excited
                F[r - 1][r - 1] = -1.0
        G62 = [[0] * 10 for _ in range(12)]
        for i, j in self._g_free:
            G62[i - 1][j - 1] = self._entry("g", i, j)
        eq62 = _eq62_inputs(self.rotors)
        G = [[row[eq62.index(c)] for c in self.inputs] for row in G62]
        C = np.zeros((6, 12))
        for k in range(6):
            C[k, 2 * k] = C[k, 2 * k + 1] = 1.0
        return F, G, C, self._tau_pattern()

    def parameter_names(self):
        """Names of the free-able parameters (after ties, without the held and removed ones)."""
        tau = self._tau_pattern() or []
        out = ({self._name("f", i, j).lstrip("-") for i, j in self._f_entries}
               | {self._name("g", i, j).lstrip("-") for i, j in self._g_free}
               | {n for row in tau for n in row if isinstance(n, str)})
        return sorted(out - set(self.a_priori) - set(self.without))

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        keep = set(self.parameter_names())
        vals = super().initial_values(lam_over_c, n_points, coherence_min)
        return {k: v for k, v in vals.items() if k in keep}

    def staged_plan(self):
        keep = set(self.parameter_names())
        plan = super().staged_plan()
        for stage in plan:
            if not isinstance(stage.free, str):
                stage.free = [n for n in stage.free if n in keep]
        return [s for s in plan if isinstance(s.free, str) or s.free or s.add_pairs]

    def published_values(self, model):
        keep = set(self.parameter_names())
        return {k: v for k, v in super().published_values(model).items() if k in keep}


#: The variants compared by the study, from the shipped structure to the most constrained.
VARIANTS = {
    "shipped (Eq. 6.3 + delays + far-wake loads)": dict(),
    "first-order collective": dict(collective_far_wake=False),
    "first-order collective, Pitt-Peters collective gain": dict(
        collective_far_wake=False, a_priori=PITT_PETERS_COLLECTIVE_GAIN),
    # on our wake f4_10 ran to ~230 in a flat direction with f4_9 (it scales a far-wake
    # state that barely reaches the outputs); removing it alone let f10_4, its mirror
    # (lower far <- upper far), take the same role (12 bounds over 20 %, max 208 %)
    "first-order collective, Pitt-Peters collective gain, without far-far cross-rotor cyclic": dict(
        collective_far_wake=False, a_priori=PITT_PETERS_COLLECTIVE_GAIN, without=("f4_10", "f10_4")),
}
