"""A 12-state coaxial structure whose inflow also answers each rotor's tip-path-plane *tilt*.

Why: held records of our coaxial wake (:mod:`~aircraft.identification.steady_gains`)
show the upper rotor's cyclic inflow answering a held tilt of its tip-path plane
(about -0.1 per rad on the on-axis harmonic) and hardly a steady flap *rate*. The
mechanism is physical: tilted, the upper blades move up to 0.1 R toward or away
from the lower rotor (0.14 R below) through the vertical gradient of the lower
rotor's induced velocity (a frozen-field Biot-Savart check on the trimmed wake
gives -0.061 per rad from the lower rotor's vortices alone; the held-tilt record
assigns -0.066 per rad to them, while the upper rotor's own tip vortices realign
with its tip-path plane). The structures of Eqs. 6.2-6.3 take flap rates only,
so a fit can mimic ``G_T beta = G_T beta_dot / s`` only by slow poles, which in
the aircraft integrate the *full* tip-path-plane rate, body rate included: an
inflow that answers the aircraft's bank angle.

:class:`Coaxial12StateTilt` adds the tilts as four integrator states
``xi = beta`` (``xi' = beta_dot``, exact in the wake, whose shaft is fixed) that
feed the near-wake cyclic rows through tilt gains tied by hover symmetry (per
rotor pair: an on-axis gain ``kon_<to><from>`` and a cross-axis gain
``kx_<to><from>``; in rotor frames the 1c entries of a cross-rotor pair change
sign, as the flap-rate ties of Eq. 6.3)::

    lam1sN_r' = ... + kon_rq beta1s_q + kx_rq beta1c_q
    lam1cN_r' = ... + s kon_rq beta1c_q - s kx_rq beta1s_q      (s = -1 cross-rotor, rotor frames)

(derivatives per radian of azimuth, as every F/G entry; tilts in rad).

Fitted to the same lambda/C and lambda/beta_dot responses (the tilt is
``beta_dot / (j omega)``, so rate and tilt are separated by their phase), it is
flown as an :class:`aircraft.inflow.tilt.TiltInflow`: the integrators are dropped
and the tilt gains read the aircraft's shaft-relative flapping states
(:class:`aircraft.helicopter.tilt_coupling.TiltCoupledHelicopter`).

::

    identify_inflow(config, hover, Coaxial12StateTilt(...)) -> IdentifiedModel
        .to_inflow() -> TiltInflow ──► TiltCoupledHelicopter ─ trim ─ linearize
"""
from __future__ import annotations

import numpy as np
from flightid import FGCStructure

from aircraft.inflow.base import rotor_suffix
from aircraft.inflow.tilt import TILT_HARMONICS, tilt_names

from .constrained import (PITT_PETERS_COLLECTIVE_GAIN, Coaxial12StateConstrained)

__all__ = ["Coaxial12StateTilt", "TiltFGCStructure", "TILT_GAIN_NAMES", "ON_AXIS_TILT_GAINS", "TILT_VARIANT",
           "tilt_inflow_from_record"]

#: Every tilt gain: on-axis (``kon``) and cross-axis (``kx``) per (to, from) rotor pair,
#: ``U`` the upper (first) and ``L`` the lower rotor whatever the signals' rotor names.
TILT_GAIN_NAMES = tuple(f"{k}_{r}{q}" for r in "UL" for q in "UL" for k in ("kon", "kx"))
#: The rotors' letters in the tilt gains' names, by position (upper, lower).
_GAIN_ROTORS = ("U", "L")

#: The on-axis tilt gains, the default: the fit's flap-rate responses are the on-axis
#: ones (lambda1s / beta1s_dot, lambda1c / beta1c_dot of every rotor pair, §6.4.3), so a
#: cross-axis gain would have no influence on the cost and could run off unseen.
ON_AXIS_TILT_GAINS = tuple(n for n in TILT_GAIN_NAMES if n.startswith("kon"))

#: The constrained structure the tilt gains are added to: variant 4 of
#: :data:`~studies.analysis.twelve_state_variants.VARIANTS` (first-order
#: collective, its gain held at Pitt-Peters', no far-far cross-rotor cyclic coupling)
#: with two more freedoms removed, measured on our wake's data set
#: (``rotorwake twelve-state-variants``):
#:
#: * the flap rates feed the near wake only (``g4_3, g4_8, g10_3, g10_8`` and their
#:   1c partners): the far-wake flap-rate gains and their slow poles were how the
#:   flap-rate-only fit imitated the tilt (an integrator of the rate); with the tilt
#:   an input, keeping them let the rate path's steady gain run to K_R ~ 26;
#: * no collective near-wake coupling lower -> upper (``f1_7``): its bound was 31 %
#:   in every variant that had it, and without it the fit has one bound over 20 %.
TILT_VARIANT = dict(collective_far_wake=False, a_priori=PITT_PETERS_COLLECTIVE_GAIN,
                    without=("f4_10", "f10_4", "g4_3", "g4_8", "g10_3", "g10_8", "f1_7"))


class TiltFGCStructure(FGCStructure):
    """:class:`flightid.FGCStructure` whose four trailing tilt integrators are not inflow poles.

    The integrators (``xi' = beta_dot``, zero rows of ``F``) carry an input, the
    tilt; ``F`` is block triangular, so the inflow's poles are those of its
    leading block, and the fit's stability guard looks at those only.

    Parameters
    ----------
    F, G, C, tau, inputs, outputs, initial, fixed, states, D :
        As :class:`flightid.FGCStructure`; the last :attr:`n_integrators` rows of
        ``F`` must be zero (checked when the poles are asked for).
    omega : float
        Rotor speed [rad/s] of the azimuth time scale.
    """

    n_integrators = 4

    def poles(self, values=None):
        a = self._abcd(self.matrices(values))[0]
        n = a.shape[0] - self.n_integrators
        if np.any(a[n:] != 0.0):
            raise ValueError("the tilt integrators' rows of F must be zero")
        return np.linalg.eigvals(a[:n, :n])


_NEAR_1S = (3, 9)          # 1-based rows of the near-wake lam1s states (Eq. 6.2), upper then lower
_NEAR_1C = (5, 11)


class Coaxial12StateTilt(Coaxial12StateConstrained):
    """:class:`Coaxial12StateConstrained` plus tip-path-plane tilt inputs (16 states).

    Parameters
    ----------
    tilt : iterable of str, optional
        The tilt gains to fit (default :data:`ON_AXIS_TILT_GAINS`); the others are
        zero. Cross-axis gains (``kx_*``) are only seen by a fit that includes the
        cross-axis flap-rate responses, which the staged plan does not.
    rotors : (str, str), optional
        Upper and lower rotor names of the signals (default ``("U", "L")``); the
        tilt gains keep their names (``U`` upper, ``L`` lower).
    **constrained
        As :class:`Coaxial12StateConstrained` (default :data:`TILT_VARIANT`).

    Raises
    ------
    ValueError
        A tilt name that is not in :data:`TILT_GAIN_NAMES`, or none at all.
    """

    key = "coaxial_12state_tilt"

    def __init__(self, tilt=ON_AXIS_TILT_GAINS, *, rotors=None, **constrained):
        super().__init__(**(constrained or TILT_VARIANT), rotors=rotors)
        tilt = [tilt] if isinstance(tilt, str) else list(tilt)
        bad = [n for n in tilt if n not in TILT_GAIN_NAMES]
        if bad:
            raise ValueError(f"tilt names {bad} are not tilt gains; they are {list(TILT_GAIN_NAMES)}")
        if not tilt:
            raise ValueError("tilt is empty: without tilt gains use Coaxial12StateConstrained")
        self.tilt = tuple(n for n in TILT_GAIN_NAMES if n in tilt)

    def spec(self):
        out = super().spec()
        out["tilt"] = list(self.tilt)
        return out

    def __repr__(self):
        return f"Coaxial12StateTilt(tilt={self.tilt!r}, {super().__repr__()[len('Coaxial12StateConstrained('):]}"

    @property
    def tilt_names(self):
        """The tilt inputs, in the integrator states' order: ``beta1s_U, beta1c_U, beta1s_L, beta1c_L``."""
        return tilt_names(self.rotors)

    @property
    def states(self):
        return list(super().states) + [f"tilt_{n}" for n in self.tilt_names]

    def _tilt_entries(self):
        """``{(row, column): (name, sign)}`` of the tilt gains in F (0-based; columns 12-15)."""
        out = {}
        for ir, r in enumerate(_GAIN_ROTORS):
            for iq, q in enumerate(_GAIN_ROTORS):
                c1s, c1c = 12 + 2 * iq, 13 + 2 * iq
                mirror = -1.0 if (r != q and self.frame == "rotor") else 1.0
                s_row, c_row = _NEAR_1S[ir] - 1, _NEAR_1C[ir] - 1
                for name, entries in ((f"kon_{r}{q}", [(s_row, c1s, 1.0), (c_row, c1c, mirror)]),
                                      (f"kx_{r}{q}", [(s_row, c1c, 1.0), (c_row, c1s, -mirror)])):
                    if name in self.tilt:
                        for i, j, sign in entries:
                            out[(i, j)] = (name, sign)
        return out

    def build(self, initial, omega, fixed=()):
        if not (omega and omega > 0):
            raise ValueError(f"Coaxial12StateTilt needs the rotor speed omega > 0 [rad/s], got {omega!r}")
        F12, G12, C12, tau = self._fgc_patterns()
        F = [list(row) + [0] * 4 for row in F12] + [[0] * 16 for _ in range(4)]
        for (i, j), (name, sign) in self._tilt_entries().items():
            F[i][j] = name if sign > 0 else f"-{name}"
        G = [list(row) for row in G12] + [[0] * len(self.inputs) for _ in range(4)]
        # xi' = beta_dot in azimuth time: d xi / d psi = beta_dot / Omega
        rates = [f"{b}_dot{rotor_suffix(r)}" for r in self.rotors for b in TILT_HARMONICS]
        for m, rate in enumerate(rates):
            G[12 + m][self.inputs.index(rate)] = 1.0 / float(omega)
        C = np.hstack([np.asarray(C12, float), np.zeros((len(self.outputs), 4))])
        return self._assemble(TiltFGCStructure, F, G, C, tau, initial, omega, fixed)

    def parameter_names(self):
        return sorted(set(super().parameter_names()) | set(self.tilt))

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        vals = super().initial_values(lam_over_c, n_points, coherence_min)
        vals.update({n: 0.0 for n in self.tilt})      # the fit's stage 2 frees them
        return vals

    def staged_plan(self):
        plan = super().staged_plan()
        # the tilt gains enter with the flap-rate gains: both are read from the
        # lambda / beta_dot responses, which that stage adds
        stage = next((st for st in plan if any("beta" in inp for _, inp in st.add_pairs)), None)
        if stage is None or isinstance(stage.free, str):
            raise RuntimeError("the 12-state staged plan has no stage that adds the flap-rate responses")
        stage.name = f"{stage.name} and tilt gains"
        stage.free = list(stage.free) + list(self.tilt)
        return plan

    def to_inflow(self, values, omega, *, loads_ref=None, inflow_ref=None, pade_order=2, name=None):
        """A :class:`aircraft.inflow.tilt.TiltInflow`: the 12 inflow states, and the tilt
        gains as an input matrix on the shaft-relative tilts (the integrators dropped)."""
        fgc = self.build(values, omega)
        mats = fgc.matrices()
        return _tilt_inflow(omega * np.asarray(mats["F"]), omega * np.asarray(mats["G"]), fgc.C, mats.get("tau"),
                            rotors=self.rotors, inputs=self.inputs, loads_ref=loads_ref, inflow_ref=inflow_ref,
                            name=name or f"identified {self.key}", pade_order=pade_order)


def _tilt_inflow(F, G, C, tau, *, rotors, inputs, loads_ref, inflow_ref, name, pade_order):
    """TiltInflow from the 16-state form [1/s]: the leading states and their delays are the
    inflow model, the columns of ``F`` on the four trailing integrators the tilt matrix."""
    from aircraft.inflow import IdentifiedInflow
    from aircraft.inflow.tilt import TiltInflow
    n = F.shape[0] - 4
    base = IdentifiedInflow.from_fgc(F[:n, :n], G[:n], C[:, :n], rotors=rotors, input_order=inputs,
                                     loads_ref=loads_ref, inflow_ref=inflow_ref, name=name, tau=tau,
                                     pade_order=pade_order)
    return TiltInflow.from_inflow(base, F[:n, n:], tilt_names(rotors), inflow_block=F[:n, :n])




def tilt_inflow_from_record(record, pade_order=None):
    """A shipped :class:`Coaxial12StateTilt` model file as a flyable :class:`~aircraft.inflow.tilt.TiltInflow`.

    The file holds the fitted 16-state ``F, G, C`` [1/s] with the four tilt
    integrators (so :meth:`ModelRecord.to_inflow` refuses it: the integrators are
    marginally stable); here they are dropped and their columns of ``F`` become
    the tilt input matrix.

    Parameters
    ----------
    record : ModelRecord or str
        The record, or a shipped model's name / a file path (:func:`load_record`).
    pade_order : int, optional
        Padé order of the delays (default the record's).

    Raises
    ------
    ModelFileError
        A record of another structure, or one whose integrator rows are not zero.
    """
    from aircraft.inflow.model_files import ModelFileError, load_record
    rec = load_record(record) if not hasattr(record, "matrices") else record
    key = (rec.settings.get("structure") or {}).get("key")
    if key != Coaxial12StateTilt.key:
        raise ModelFileError(f"{rec.name}: not a {Coaxial12StateTilt.key} model (structure {key!r})")
    F, G, C = (np.asarray(rec.matrices[k], float) for k in ("F", "G", "C"))
    n = F.shape[0] - 4
    if F.shape != (16, 16) or np.any(F[n:] != 0.0) or np.any(C[:, n:] != 0.0):
        raise ModelFileError(f"{rec.name}: the tilt integrators' rows of F (and columns of C) must be zero")
    return _tilt_inflow(F, G, C, rec.matrices.get("tau"), rotors=rec.rotors, inputs=rec.inputs,
                        loads_ref=rec.loads_ref, inflow_ref=rec.inflow_ref, name=rec.name,
                        pade_order=pade_order or rec.pade_order)
