"""The coaxial 6-state with every coupling hover's axisymmetry allows.

Eq. 5.3 keeps, per harmonic, a diagonal 2x2 block between the rotors and sets
every coupling of a rotor's ``lam1s`` with a ``C_M`` (and ``lam1c`` with a
``C_L``) to zero. Hover's axisymmetry does not require that. Turning the wake
by an azimuth ``psi`` turns each rotor's cyclic harmonics by ``R(psi)`` (in our
per-rotor frames the lower rotor's by ``R(-psi)``), and a matrix left unchanged
by every such turn has, for each 2x2 cyclic block,

=======================  ========================  =========================
block                    our rotor frames          printed common frame
=======================  ========================  =========================
own rotor (U<-U, L<-L)   ``[[a, b], [-b, a]]``     ``[[a, b], [-b, a]]``
cross rotor              ``[[a, b], [b, -a]]``     ``[[a, b], [-b, a]]``
=======================  ========================  =========================

A scaled rotation for a rotor's own block (a swirl of the pattern), a scaled
reflection for the cross-rotor blocks in our mirrored frames. Eq. 5.3 is the
``b = 0`` case. :class:`Coaxial6StateAxisymmetric` adds the four ``b`` terms
to each of ``M`` and ``Lbar`` (``m23, m56, m26, m53``; ``l23, l56, l26, l53``),
with the delays of the block they sit in: 32 parameters, the most general
first-order 6-state with Eq. 5.3's states and delays that a hover wake can
have (``tests/aircraft/identification/test_coaxial_hover_symmetry.py`` checks that the invariant
matrices are exactly this 12-dimensional set).

Why it exists: our coaxial hover wake's measured lambda/C has coherent
(0.86-0.99 above 1.5 rad/s) off-harmonic elements of this form, for example
``lam1s_U/C_M^L`` 3.0 and ``lam1c_U/C_L^L`` 2.9 at 1.6 rad/s against 5.5 for
``lam1s_U/C_L^L``, with the signs the table predicts. Eq. 5.3 cannot produce
them, so its fit never sees them.
"""
from __future__ import annotations

import numpy as np

from .base import PITT_PETERS_M11, _low_frequency_inverse
from .hover import Coaxial6State

__all__ = ["Coaxial6StateAxisymmetric", "PITT_PETERS_COLLECTIVE_MASS"]

#: Pitt-Peters' hover apparent mass 8/(3 pi) (azimuth time) on each rotor's own
#: collective inflow: the a priori value of the scale our nearly rank-one collective
#: lambda/C block cannot fix (``six_state_diagnostics`` measures that rank)
PITT_PETERS_COLLECTIVE_MASS = {"m11": PITT_PETERS_M11, "m44": PITT_PETERS_M11}


class Coaxial6StateAxisymmetric(Coaxial6State):
    """Eq. 5.3's 6-state plus the 1s/1c couplings hover's axisymmetry allows (module docstring).

    ``lambda = (M d/dpsi + Lbar)^-1 C`` with 12 parameters in each of ``M``
    (azimuth time, dimensionless) and ``Lbar`` [load coefficient per inflow],
    and 8 delays [s]. The ``b`` terms: ``p23`` (upper rotor's own, entry
    (lam1s_U, CM_U); (lam1c_U, CL_U) is ``-p23``), ``p56`` (the lower rotor's
    own), ``p26`` (upper from lower: (lam1s_U, CM_L); (lam1c_U, CL_L) is ``p26``
    in our frames, ``-p26`` printed) and ``p53`` (lower from upper). They share
    the delays ``t22``, ``t55``, ``t25``, ``t52`` of their blocks.

    Parameters
    ----------
    frame : {"rotor", "printed"}
        Our per-rotor frames (default) or the dissertation's common frame.
    bands : sequence of (float, float)
        Bands [rad/s] of the equation-error starts (:meth:`equation_error_start`),
        each offered by :meth:`extra_starts` when stable. Two by default: the delays
        bias the estimate more the higher the band, while our wake's cyclic response
        is first order only above ~4 rad/s, so neither band is right every time.
    a_priori : mapping of str to float, optional
        Parameters held at values known before the fit (not identified): every start
        and fit uses these values and leaves them fixed, and a fitted model reports
        them with status "fixed". For example :data:`PITT_PETERS_COLLECTIVE_MASS`
        (registered as ``"coaxial_6state_axisymmetric_pp_collective_mass"``).
    rotors : (str, str), optional
        Upper and lower rotor names of the signals (default ``("U", "L")``).
    """

    key = "coaxial_6state_axisymmetric"
    #: every parameter of :meth:`build`: M and Lbar entries, then the block delays [s]
    parameter_names = tuple(f"{p}{ij}" for p in "ml" for ij in ("11", "14", "22", "23", "25", "26",
                                                                "41", "44", "52", "53", "55", "56")) + tuple(
        f"t{ij}" for ij in ("11", "14", "22", "25", "41", "44", "52", "55"))

    def __init__(self, frame="rotor", bands=((1.0, 10.0), (4.0, 20.0)), a_priori=None, *, rotors=None):
        super().__init__(frame, rotors=rotors)
        checked = []
        for band in bands:
            try:
                lo, hi = (float(b) for b in band)
            except (TypeError, ValueError):
                raise ValueError(f"each band must be (low, high) rad/s, got {band!r}") from None
            if not (0.0 < lo < hi):
                raise ValueError(f"band must be (low, high) rad/s with 0 < low < high, got {band!r}")
            checked.append((lo, hi))
        if not checked:
            raise ValueError("bands must hold at least one (low, high) band [rad/s]")
        self.bands = tuple(checked)
        self.a_priori = self._checked_a_priori(a_priori)

    def _checked_a_priori(self, a_priori):
        if a_priori is None:
            return {}
        if not hasattr(a_priori, "items"):
            raise TypeError(f"a_priori must map parameter names to values, got {type(a_priori).__name__}")
        names = set(self.parameter_names)
        out = {}
        for name, value in a_priori.items():
            if name not in names:
                raise ValueError(f"a_priori names an unknown parameter {name!r}; the parameters are "
                                 f"{sorted(names)}")
            if isinstance(value, (bool, complex)) or not np.isscalar(value) or not np.isfinite(value):
                raise ValueError(f"a_priori value of {name!r} must be a finite real number, got {value!r}")
            out[name] = float(value)
        return out

    def spec(self):
        out = {**super().spec(), "bands": [list(b) for b in self.bands]}
        if self.a_priori:   # only when set: the plain structure's hash is unchanged
            out["a_priori"] = dict(sorted(self.a_priori.items()))
        return out

    def __repr__(self):
        extra = f", a_priori={self.a_priori!r}" if self.a_priori else ""
        return f"{type(self).__name__}(frame={self.frame!r}, bands={self.bands!r}{extra}{self._rotors_repr()})"

    def build(self, initial, omega, fixed=()):
        """The flightid structure from ``initial`` values, the :attr:`a_priori` values
        overriding them and fixed along with ``fixed``."""
        values = {**dict(initial), **self.a_priori}
        return self._build(values, omega, tuple(dict.fromkeys([*fixed, *self.a_priori])))

    def _build(self, initial, omega, fixed):
        from flightid import MLTauStructure
        rotor = self.frame == "rotor"
        cross_b = "" if rotor else "-"     # the cross-rotor b term's second entry
        cross_a = "-" if rotor else ""     # Eq. 5.3's tie of the cross-rotor 1c term

        def pattern(p):
            return [[f"{p}11", 0, 0, f"{p}14", 0, 0],
                    [0, f"{p}22", f"{p}23", 0, f"{p}25", f"{p}26"],
                    [0, f"-{p}23", f"{p}22", 0, f"{cross_b}{p}26", f"{cross_a}{p}25"],
                    [f"{p}41", 0, 0, f"{p}44", 0, 0],
                    [0, f"{p}52", f"{p}53", 0, f"{p}55", f"{p}56"],
                    [0, f"{cross_b}{p}53", f"{cross_a}{p}52", 0, f"-{p}56", f"{p}55"]]
        # delays are durations: each b term takes its block's delay, plain ties
        tau = [["t11", 0, 0, "t14", 0, 0],
               [0, "t22", "t22", 0, "t25", "t25"],
               [0, "t22", "t22", 0, "t25", "t25"],
               ["t41", 0, 0, "t44", 0, 0],
               [0, "t52", "t52", 0, "t55", "t55"],
               [0, "t52", "t52", 0, "t55", "t55"]]
        return MLTauStructure(pattern("m"), pattern("l"), tau, inputs=self.inputs, outputs=self.outputs,
                              initial=dict(initial), fixed=fixed, omega=omega)

    def initial_values(self, lam_over_c, n_points=3, coherence_min=None):
        """The low-frequency start: ``Lbar`` (every term, ``b`` included) from the real part
        of the inverse of the ``n_points`` lowest frequencies, projected on the ties; ``M``
        Pitt-Peters' diagonal, cross terms as :meth:`Coaxial6State.initial_values`, ``b``
        terms zero. On our coaxial hover wake the fit from it stopped at J_ave 922 with
        a 500 rad/s undamped pair; :meth:`extra_starts` offers the start that works."""
        init = dict(super().initial_values(lam_over_c, n_points, coherence_min))
        init.update({f"{p}{ij}": 0.0 for p in "ml" for ij in ("23", "56", "26", "53")})
        return self._project(init, {"Lbar": _low_frequency_inverse(lam_over_c, n_points,
                                                                coherence_min=coherence_min)})

    def equation_error_start(self, lam_over_c, omega, band):
        """The equation-error start over ``band``: ``H^-1 = Lbar + j (omega/Omega) M``.

        ``Lbar`` is the mean of ``Re(H^-1)`` and ``M`` the least-squares slope of
        ``Im(H^-1)`` against ``omega/Omega`` over the band, each averaged over the
        entries a parameter is tied to (with the ties' signs); delays as
        :meth:`initial_values`.

        Parameters
        ----------
        lam_over_c : flightid.MeasuredResponse
        omega : float
            Rotor speed [rad/s].
        band : (float, float)
            Frequencies used [rad/s].

        Returns
        -------
        dict or None
            The values; None when the band holds fewer than two frequencies or the
            measured block is singular there.
        """
        w = np.asarray(lam_over_c.omega, dtype=float)
        sel = np.flatnonzero((w >= band[0]) & (w <= band[1]))
        if sel.size < 2:
            return None
        oi = [lam_over_c.output_labels.index(o) for o in self.outputs]
        ii = [lam_over_c.input_labels.index(i) for i in self.inputs]
        h = np.moveaxis(lam_over_c.frdata[np.ix_(oi, ii)][:, :, sel], -1, 0)
        try:
            h_inv = np.linalg.inv(h)
        except np.linalg.LinAlgError:
            return None
        x = w[sel] / float(omega)
        return self._project(self.initial_values(lam_over_c),
                             {"Lbar": h_inv.real.mean(axis=0),
                              "M": np.tensordot(x, h_inv.imag, axes=(0, 0)) / float(x @ x)})

    def extra_starts(self, lam_over_c, omega):
        """The equation-error starts (:meth:`equation_error_start`), one per band of
        :attr:`bands` where it exists and is stable.

        On our coaxial hover wake the 4-20 rad/s start has Pitt-Peters-sized cyclic
        masses; on exact data of a model with 0.1 s cross-rotor delays only the
        1-10 rad/s start is stable (``tests/aircraft/identification/test_coaxial_6state_axisymmetric.py``).
        """
        out = []
        for lo, hi in self.bands:
            values = self.equation_error_start(lam_over_c, omega, (lo, hi))
            if values is not None and self.build(values, omega).is_stable():
                out.append((f"equation-error Lbar and M ({lo:g}-{hi:g} rad/s)", values))
        return out

    def _project(self, init, matrices):
        """``init`` with each parameter of ``matrices`` ("M", "Lbar") set to the mean, with
        the ties' signs, of the entries it is tied to."""
        out = dict(init)
        built = self.build(out, 1.0)
        for key, mat in matrices.items():
            sums, counts = {}, {}
            for i, j, name, sign in built._patterns[key].refs:
                sums[name] = sums.get(name, 0.0) + sign * float(mat[i, j])
                counts[name] = counts.get(name, 0) + 1
            out.update({name: sums[name] / counts[name] for name in sums})
        return out

    def published_values(self, model):
        """Eq. 5.3's values with every ``b`` term zero (Eq. 5.3 is the ``b = 0`` case)."""
        vals = super().published_values(model)
        vals.update({f"{p}{ij}": 0.0 for p in "ml" for ij in ("23", "56", "26", "53")})
        return vals
