"""The hover structures of the dissertation, in our rotor frames.

Each structure knows its signals (swashplate controls swept, load and flap-rate
inputs, inflow outputs), builds the :mod:`flightid` parametric structure
(:class:`flightid.MLTauStructure` / :class:`flightid.FGCStructure`) from initial
values, proposes a data-driven start from measured lambda/C responses, maps a
printed model onto its parameters, and turns fitted values into an
:class:`aircraft.inflow.IdentifiedInflow`.

==========================  ===================================================  ============
structure                   form                                                 parameters
==========================  ===================================================  ============
:class:`SingleRotor3State`  Tables 4.1-4.2: diagonal M, Lbar, tau, cyclic tied   6
:class:`Coaxial6State`      Eq. 5.3 / §5.3: 2x2 blocks of diagonal 3x3, ties     24
:class:`Coaxial12State`     Eqs. 6.2-6.3: near/far wake F/G/C, flap-rate inputs  66 (42 tied)
==========================  ===================================================  ============

``M`` multiplies d/dpsi (rotor-azimuth time, dimensionless, Eq. 5.3; Tables 4.1-4.2
print ``M/Omega`` in seconds: divide by Omega); delays are in seconds. The frame
conversion from the printed common frame is :mod:`aircraft.inflow.frames`:
in our frames the hover roll/pitch symmetry ties the *cross-rotor* cosine terms
to the sine terms with a minus sign (``m36 = -m25``, ``m63 = -m52``), while the
dissertation's common frame ties them with a plus sign.
"""
from __future__ import annotations

import numpy as np

from aircraft.inflow.published import fgc_state_names

from .base import PITT_PETERS_M11, PITT_PETERS_M22, InflowStructure, _low_frequency_inverse

__all__ = ["SingleRotor3State", "Coaxial6State", "Coaxial12State"]

class SingleRotor3State(InflowStructure):
    """3-state single rotor in hover (Tables 4.1-4.2; Pitt-Peters form, §4.3).

    Diagonal ``M``, ``Lbar``, ``tau``; the cyclic rows are tied by hover symmetry
    (``m22 = m33``, ``l22 = l33``, ``t22 = t33``, §4.3.1.2): 6 parameters. A single
    rotor has one frame, so ``frame`` does not matter.

    Parameters
    ----------
    frame : {"rotor", "printed"}
        Frame of the parameters (no effect for a single rotor).
    rotors : (str,), optional
        Name of the rotor in the signals (default ``("",)``: no suffix).
    """

    key = "single_rotor_3state"
    rotors = ("",)
    protected = ("m11", "m22")

    def build(self, initial, omega, fixed=()):
        from flightid import MLTauStructure
        diag = lambda p: [[f"{p}11", 0, 0], [0, f"{p}22", 0], [0, 0, f"{p}22"]]   # noqa: E731
        return MLTauStructure(diag("m"), diag("l"), diag("t"), inputs=self.inputs, outputs=self.outputs,
                              initial=dict(initial), fixed=fixed, omega=omega)

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """``l11``, ``l22`` from the inverted low-frequency lambda/C (the cyclic value
        is the mean of the 1s and 1c diagonals); Pitt-Peters ``M``; 20 ms delays."""
        l0 = _low_frequency_inverse(lam_over_c, n_points, coherence_min=coherence_min)
        return {"m11": PITT_PETERS_M11, "m22": PITT_PETERS_M22, "l11": float(l0[0, 0]),
                "l22": float(0.5 * (l0[1, 1] + l0[2, 2])), "t11": 0.02, "t22": 0.02}

    def published_values(self, model):
        m = model.M * model.omega if model.time == "seconds" else model.M   # to azimuth time
        return {"m11": float(m[0, 0]), "m22": float(m[1, 1]), "l11": float(model.Lbar[0, 0]),
                "l22": float(model.Lbar[1, 1]), "t11": float(model.tau[0, 0]), "t22": float(model.tau[1, 1])}

#: The 24 free parameters of §5.3 (rows 3 and 6 repeat 2 and 5 by ties).
_COAX6_FREE = [(1, 1), (2, 2), (1, 4), (2, 5), (4, 1), (5, 2), (4, 4), (5, 5)]

class Coaxial6State(InflowStructure):
    """6-state coaxial rotor in hover (Eq. 5.3, the 24-parameter structure of §5.3).

    Each 3x3 block of ``M``, ``Lbar``, ``tau`` is diagonal; the 1c rows repeat the 1s
    rows (hover roll/pitch symmetry). In our rotor frames (default) the cross-rotor
    cosine terms are tied to the sine terms with opposite sign for ``M`` and ``Lbar``
    (``m36 = -m25``, ``m63 = -m52``, ``l36 = -l25``, ``l63 = -l52``); in the printed
    frame with the same sign, as §5.3 lists them. Delays are durations and keep
    plain ties.

    Parameters
    ----------
    frame : {"rotor", "printed"}
        ``"rotor"``: our per-rotor frames (default); ``"printed"``: the
        dissertation's common frame.
    rotors : (str, str), optional
        Upper and lower rotor names of the signals (default ``("U", "L")``), e.g.
        the aircraft's (:func:`~aircraft.inflow.base.config_rotor_names`).

    Examples
    --------
    >>> Coaxial6State(rotors=("upper", "lower")).inputs[:3]
    ['CT_upper', 'CL_upper', 'CM_upper']
    """

    key = "coaxial_6state"
    rotors = ("U", "L")
    protected = ("m11", "m22", "m44", "m55")

    def build(self, initial, omega, fixed=()):
        from flightid import MLTauStructure
        sign = "-" if self.frame == "rotor" else ""

        def pattern(p, s):
            return [[f"{p}11", 0, 0, f"{p}14", 0, 0],
                    [0, f"{p}22", 0, 0, f"{p}25", 0],
                    [0, 0, f"{p}22", 0, 0, f"{s}{p}25"],
                    [f"{p}41", 0, 0, f"{p}44", 0, 0],
                    [0, f"{p}52", 0, 0, f"{p}55", 0],
                    [0, 0, f"{s}{p}52", 0, 0, f"{p}55"]]
        return MLTauStructure(pattern("m", sign), pattern("l", sign), pattern("t", ""),
                              inputs=self.inputs, outputs=self.outputs, initial=dict(initial),
                              fixed=fixed, omega=omega)

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """``Lbar`` from the inverse of the measured low-frequency lambda/C (real part,
        mean of the ``n_points`` lowest frequencies); ``M`` diagonal from Pitt-Peters
        in hover, cyclic cross terms 0.05 and collective cross terms 0; delays
        20 ms (own rotor) and 50 ms (cross). A start from the printed Eq. 5.3 values
        ended in a degenerate, near-singular ``M`` (J_ave 1300) in our wake."""
        l0 = _low_frequency_inverse(lam_over_c, n_points, coherence_min=coherence_min)
        init = {"m11": PITT_PETERS_M11, "m44": PITT_PETERS_M11, "m22": PITT_PETERS_M22, "m55": PITT_PETERS_M22, "m14": 0.0, "m41": 0.0,
                "m25": 0.05, "m52": 0.05, "t11": 0.02, "t22": 0.02, "t44": 0.02, "t55": 0.02,
                "t14": 0.05, "t41": 0.05, "t25": 0.05, "t52": 0.05}
        for i, j in _COAX6_FREE:
            init[f"l{i}{j}"] = float(l0[i - 1, j - 1])
        return init

    def extra_starts(self, lam_over_c, omega):
        """The equation-error start (:func:`~aircraft.identification.starts.equation_error_start`,
        ``M`` from ``Im(H^-1)`` over 1-10 rad/s), when it is stable.

        On exact data of a physically sized 6-state model the :meth:`initial_values`
        start stops at J_ave ~690 and this one recovers the model
        (``tests/aircraft/identification/test_coaxial_6state_start.py``). On our default coaxial hover wake it
        is unstable (the lower rotor's collective mass comes out at -0.18) and is not
        offered; a fit from an unstable start is refused anyway.
        """
        from ..starts import equation_error_start
        try:
            values = equation_error_start(self, lam_over_c, omega)
        except (ValueError, np.linalg.LinAlgError):
            return []          # no data in the band, or a singular block: no such start
        if not self.build(values, omega).is_stable():
            return []
        return [("equation-error M (1-10 rad/s)", values)]

    def published_values(self, model):
        """Eq. 5.3's values on the 24 parameters, converted to ``self.frame``."""
        from aircraft.inflow.published import in_rotor_frames
        if self.frame == "rotor" and model.frame == "printed":
            model = in_rotor_frames(model)
        vals = {}
        for name, mat in (("m", model.M), ("l", model.Lbar), ("t", model.tau)):
            for i, j in _COAX6_FREE:
                vals[f"{name}{i}{j}"] = float(mat[i - 1, j - 1])
        return vals

# Eq. 6.3's pattern, 1-based (row, column) in Eq. 6.2's state and input order
# (inputs CT_U, CL_U, b1s_U, CM_U, b1c_U, CT_L, CL_L, b1s_L, CM_L, b1c_L). The
# printed G has 11 columns; its rows 6 and 12 put the far-wake 1c flap-rate term
# of the other rotor in an 11th column, read here as the 10th (Eq. 6.9 prints
# these entries, +0.255 and +0.330, in column 10).
_EQ62_INPUTS = ["CT_U", "CL_U", "beta1s_dot_U", "CM_U", "beta1c_dot_U",
                "CT_L", "CL_L", "beta1s_dot_L", "CM_L", "beta1c_dot_L"]


def _eq62_inputs(rotors):
    """Eq. 6.2's input order with the signals of rotors ``rotors`` (upper, lower)."""
    return [f"{stem}_{r}" for r in rotors for stem in ("CT", "CL", "beta1s_dot", "CM", "beta1c_dot")]

def _g_free():
    """G's free entries: per rotor's rows (lam0N, lam0F, lam1sN, lam1sF, lam1cN, lam1cF):
    lam0N <- both CT; lam0F <- the lower rotor's CT (as printed); lam1sN <- CL, b1s;
    lam1sF <- b1s; lam1cN <- CM, b1c; lam1cF <- b1c, each from both rotors."""
    out = set()
    for r0 in (0, 6):
        out |= {(r0 + 1, 1), (r0 + 1, 6), (r0 + 2, 6)}
        out |= {(r0 + 3, c + o) for c in (2, 3) for o in (0, 5)}
        out |= {(r0 + 4, 3), (r0 + 4, 8)}
        out |= {(r0 + 5, c + o) for c in (4, 5) for o in (0, 5)}
        out |= {(r0 + 6, 5), (r0 + 6, 10)}
    return sorted(out)

def _f_free():
    out = set()
    for r0 in (0, 6):
        for c0 in (0, 6):
            # per harmonic: near <- near; far <- near and far (Eq. 6.1 form, every rotor pair)
            for h in (0, 2, 4):
                out |= {(r0 + h + 1, c0 + h + 1), (r0 + h + 2, c0 + h + 1), (r0 + h + 2, c0 + h + 2)}
    return sorted(out)

_G_FREE = _g_free()
_F_FREE = _f_free()
# 1s <-> 1c partners (1-based, Eq. 6.2 orders) for the hover symmetry ties
_STATE_PARTNER = {3: 5, 4: 6, 9: 11, 10: 12}
_INPUT_PARTNER = {2: 4, 3: 5, 7: 9, 8: 10}
_UPPER_STATES, _UPPER_INPUTS = set(range(1, 7)), set(range(1, 6))

class Coaxial12State(InflowStructure):
    """12-state near/far-wake coaxial model with flap-rate inputs (Eqs. 6.2-6.3, 6.8-6.9).

    States (Eq. 6.2) ``lam0N, lam0F, lam1sN, lam1sF, lam1cN, lam1cF`` per rotor,
    ``lambda = lambda_N + lambda_F``; inputs the loads and the flap rates
    ``beta1s_dot, beta1c_dot`` [rad/s] per rotor (canonical order; Eq. 6.2's own order
    is kept in the parameter names ``f<row>_<col>``, ``g<row>_<col>``, 1-based).
    Free entries: Eq. 6.3's pattern, 66 (F 36, G 30). With ``tied=True`` (default) the 1c rows
    repeat the 1s rows (hover symmetry), with a minus sign on cross-rotor entries
    in our rotor frames (as for :class:`Coaxial6State`); ``tied=False`` frees every
    entry of the pattern (it then represents the printed Eqs. 6.8-6.9 exactly,
    whose 1s and 1c moment columns carry opposite signs, see
    :mod:`aircraft.inflow.published`). Identifying it needs flap-rate excitation
    independent of the loads (prescribed tip-path-plane sweeps, §6.3); the
    pipeline checks for it.

    Parameters
    ----------
    frame : {"rotor", "printed"}
        ``"rotor"``: our per-rotor frames (default); ``"printed"``: the
        dissertation's common frame.
    tied : bool
        Tie the 1c rows to the 1s rows (default); ``False`` frees every entry.
    delays : bool
        Add the 6-state model's time delays [s] on the lambda/C pairs of the same
        harmonic (own and cross rotor, 1c tied to 1s: ``t11 t14 t22 t25 t41 t44
        t52 t55``, as :class:`Coaxial6State`); Eq. 6.2 has none. In our wake the
        lower rotor's cyclic inflow answers the upper rotor's loads about 50 ms
        late (the 6-state fit's ``t52``), which no combination of the first-order
        near/far states reproduces: without the delays the 12-state fitted the
        cross-rotor cyclic responses 2.5x worse than the 6-state. Default False
        (the printed structure).
    far_wake_loads : bool
        Also feed the cyclic far-wake states from the cyclic loads of both rotors
        (``lam1sF <- C_L``, ``lam1cF <- C_M``: 8 entries, 4 parameters after the
        ties), which Eq. 6.3 feeds only from the flap rates and the near wake
        (Eq. 6.7's forward-flight G has them). In our coaxial hover wake the lower
        rotor's cyclic inflow reverses sign over ~2 s after a cyclic step (late /
        early response -3.7, ``results/coaxial_quasi_steady/settling.csv``): a
        slow far-wake response to the loads themselves. Default False (Eq. 6.3).
    rotors : (str, str), optional
        Upper and lower rotor names of the signals (default ``("U", "L")``); the
        parameter names (Eq. 6.2's rows and columns) do not change.
    """

    key = "coaxial_12state"
    rotors = ("U", "L")
    form = "fgc"
    uses_flap_rates = True
    protected = tuple(f"f{k}_{k}" for k in range(1, 13))

    def __init__(self, frame="rotor", tied=True, delays=False, far_wake_loads=False, *, rotors=None):
        super().__init__(frame, rotors=rotors)
        self.tied = bool(tied)
        self.delays = bool(delays)
        self.far_wake_loads = bool(far_wake_loads)
        extra = set()
        if self.far_wake_loads:
            for r0 in (0, 6):       # lam1sF <- CL_U, CL_L; lam1cF <- CM_U, CM_L (Eq. 6.2 orders)
                extra |= {(r0 + 4, 2), (r0 + 4, 7), (r0 + 6, 4), (r0 + 6, 9)}
        self._g_free = sorted(set(_G_FREE) | extra)

    #: A bound on each fit's cost evaluations: with ~50 parameters an unbounded
    #: trust-region run crawled for over 10 minutes along the flat directions the
    #: CR bounds then report, and the reduction's ~50 refits at 400 evaluations
    #: took 90 s each; 150 evaluations (~25 s) brought the all-parameter stage from
    #: J_ave 109 to 76 on our wake's data, each refit starts at the previous optimum.
    fit_options = {"max_nfev": 150}

    def spec(self):
        out = {**super().spec(), "tied": self.tied, "fit_options": dict(self.fit_options)}
        if self.delays:          # absent when False: the hashes of delay-free models stay
            out["delays"] = True
        if self.far_wake_loads:  # likewise
            out["far_wake_loads"] = True
        return out

    def __repr__(self):
        extra = ", far_wake_loads=True" if self.far_wake_loads else ""
        return (f"Coaxial12State(frame={self.frame!r}, tied={self.tied}, delays={self.delays}{extra}"
                f"{self._rotors_repr()})")

    def _tau_pattern(self):
        """6 x 10 delay names (canonical inputs) or None: the 6-state's pattern on the loads."""
        if not self.delays:
            return None
        tau = [[0] * len(self.inputs) for _ in range(6)]
        for i in range(6):
            for j in range(6):
                if i % 3 == j % 3:
                    ii, jj = (i - 1 if i % 3 == 2 else i), (j - 1 if j % 3 == 2 else j)   # 1c -> 1s
                    tau[i][j] = f"t{ii + 1}{jj + 1}"
        return tau

    @property
    def states(self):
        return fgc_state_names(self.rotors)

    def _name(self, p, i, j):
        """Parameter name of entry (i, j) (1-based), following the ties."""
        partner_col = _STATE_PARTNER if p == "f" else _INPUT_PARTNER
        if self.tied and i in _STATE_PARTNER.values() and j in partner_col.values():
            ii = next(k for k, v in _STATE_PARTNER.items() if v == i)
            jj = next(k for k, v in partner_col.items() if v == j)
            cross = (i in _UPPER_STATES) != (j in (_UPPER_STATES if p == "f" else _UPPER_INPUTS))
            sign = "-" if (cross and self.frame == "rotor") else ""
            return f"{sign}{p}{ii}_{jj}"
        return f"{p}{i}_{j}"

    def build(self, initial, omega, fixed=()):
        from flightid import FGCStructure
        F = [[0] * 12 for _ in range(12)]
        for i, j in _F_FREE:
            F[i - 1][j - 1] = self._name("f", i, j)
        G62 = [[0] * 10 for _ in range(12)]
        for i, j in self._g_free:
            G62[i - 1][j - 1] = self._name("g", i, j)
        # columns to the canonical input order (loads, then flap rates)
        eq62 = _eq62_inputs(self.rotors)
        G = [[row[eq62.index(c)] for c in self.inputs] for row in G62]
        C = np.zeros((6, 12))
        for k in range(6):
            C[k, 2 * k] = C[k, 2 * k + 1] = 1.0
        names = {n.lstrip("-") for row in F + G for n in row if isinstance(n, str)}
        init = {n: float(v) for n, v in dict(initial).items() if n in names}
        missing = names - set(init)
        if missing:
            raise KeyError(f"no initial value for {sorted(missing)[:6]}... ({len(missing)} parameters)")
        tau = self._tau_pattern()
        if tau is not None:
            names |= {n for row in tau for n in row if isinstance(n, str)}
            init = {n: float(v) for n, v in dict(initial).items() if n in names}
            missing = names - set(init)
            if missing:
                raise KeyError(f"no initial value for {sorted(missing)[:6]}... ({len(missing)} parameters)")
        return FGCStructure(F, G, C, tau, inputs=self.inputs, outputs=self.outputs, initial=init,
                            fixed=[f for f in fixed if f in names], omega=omega, states=self.states)

    def parameter_names(self):
        """Names of the structure's parameters (after ties)."""
        tau = self._tau_pattern() or []
        return sorted({self._name("f", i, j).lstrip("-") for i, j in _F_FREE}
                      | {self._name("g", i, j).lstrip("-") for i, j in self._g_free}
                      | {n for row in tau for n in row if isinstance(n, str)})

    def _delay_names(self):
        return sorted({n for row in (self._tau_pattern() or []) for n in row if isinstance(n, str)})

    def _names(self, pattern, p):
        """Parameter names (after ties) of 1-based entries ``pattern`` of F or G."""
        return list(dict.fromkeys(self._name(p, i, j).lstrip("-") for i, j in pattern))

    # the near-wake states and the load columns (1-based, Eq. 6.2 orders) of each inflow
    # harmonic lam0_U, lam1s_U, lam1c_U, lam0_L, lam1s_L, lam1c_L
    _NEAR = (1, 3, 5, 7, 9, 11)
    _LOAD_COLS = (1, 2, 4, 6, 7, 9)

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """Near wake = the quasi-steady 6-state model; far wake switched off.

        Near-wake states: ``F_N = -M^-1 Lbar``, ``G_N = M^-1`` with the Pitt-Peters
        hover ``M`` (azimuth time) and ``Lbar`` from the inverted low-frequency
        lambda/C over the load inputs, on the near-wake entries of Eq. 6.3 (same
        harmonic, both rotors), so that the start already reproduces the measured
        quasi-steady gains. Far-wake states: a stable pole of -0.25 per radian of
        azimuth and zero gains (the staged plan frees them later); flap-rate gains
        0.01 so the lambda/beta_dot responses are not identically zero.
        """
        l0 = _low_frequency_inverse(lam_over_c, n_points, inputs=list(self.loads), coherence_min=coherence_min)
        m = np.array([PITT_PETERS_M11, PITT_PETERS_M22, PITT_PETERS_M22] * 2)
        vals = {n: 0.0 for n in self.parameter_names()}
        near = {state: k for k, state in enumerate(self._NEAR)}
        cols = {col: k for k, col in enumerate(self._LOAD_COLS)}
        for i, j in _F_FREE:
            name = self._name("f", i, j)
            if name.lstrip("-") != f"f{i}_{j}":
                continue                      # a tied 1c entry: set through its 1s partner
            if i in near and j in near:       # near <- near: -M^-1 Lbar
                vals[name] = -l0[near[i], near[j]] / m[near[i]]
            elif i == j:                      # far-wake pole
                vals[name] = -0.25
        for i, j in self._g_free:
            name = self._name("g", i, j)
            if name.lstrip("-") != f"g{i}_{j}":
                continue
            if i in near and j in cols and near[i] == cols[j]:
                vals[name] = 1.0 / m[near[i]]
            elif i in near and "beta" in _EQ62_INPUTS[j - 1]:
                vals[name] = 0.01
        for name in self._delay_names():     # 20 ms own rotor, 50 ms cross (the 6-state's start)
            vals[name] = 0.02 if name[1] == name[2] else 0.05
        return vals

    def staged_plan(self):
        """§6.4.3 for our wake's 12-state hover model (the dissertation's steps 1-3, 5, 6):

        1. near-wake terms of the loads (the quasi-steady 6-state part) on the
           twelve lambda/C responses, on- and off-rotor;
        2. those fixed, the near-wake flap-rate gains with the eight
           lambda/beta_dot responses added;
        3. those fixed, the far-wake states (poles, near-to-far couplings, gains);
        4. every parameter together.
        """
        from flightid.staging import Stage
        near_f = [(i, j) for i, j in _F_FREE if i in self._NEAR and j in self._NEAR]
        near_g = [(i, j) for i, j in self._g_free if i in self._NEAR and "beta" not in _EQ62_INPUTS[j - 1]]
        flap_g = [(i, j) for i, j in self._g_free if i in self._NEAR and "beta" in _EQ62_INPUTS[j - 1]]
        far_f = [(i, j) for i, j in _F_FREE if i not in self._NEAR]
        far_g = [(i, j) for i, j in self._g_free if i not in self._NEAR]
        harm = {"lam0": "CT", "lam1s": "CL", "lam1c": "CM"}
        load_pairs = [(f"{h}_{r}", f"{c}_{q}") for h, c in harm.items() for r in self.rotors for q in self.rotors]
        flap_pairs = [(f"lam1{a}_{r}", f"beta1{a}_dot_{q}") for a in "sc" for r in self.rotors for q in self.rotors]
        return [
            Stage("1 near wake, load responses", free=self._names(near_f, "f") + self._names(near_g, "g")
                  + self._delay_names(), pairs=load_pairs),
            Stage("2 near-wake flap-rate gains", free=self._names(flap_g, "g"), add_pairs=flap_pairs),
            Stage("3 far wake", free=self._names(far_f, "f") + self._names(far_g, "g")),
            Stage("4 all together", free="all"),
        ]

    def published_values(self, model):
        """Eqs. 6.8-6.9 (converted to ``self.frame``, F and G per d/dpsi) on the parameters.

        Only exact for ``tied=False``; with ties the 1s entry is taken.
        """
        from aircraft.inflow.published import in_rotor_frames
        if self.frame == "rotor" and model.frame == "printed":
            model = in_rotor_frames(model)
        F = model.F / model.omega
        cols = list(model.input_order)
        G = model.G[:, [cols.index(c) for c in _EQ62_INPUTS]] / model.omega
        vals = {}
        for i, j in _F_FREE:
            name = self._name("f", i, j)
            if name.lstrip("-") == f"f{i}_{j}":
                vals[f"f{i}_{j}"] = float(F[i - 1, j - 1])
        for i, j in self._g_free:
            name = self._name("g", i, j)
            if name.lstrip("-") == f"g{i}_{j}":
                vals[f"g{i}_{j}"] = float(G[i - 1, j - 1])
        return vals

