"""Bare-airframe frequency responses of one aircraft with several inflow models.

::

    compare_bare_airframe({"Dynamic Climb": DynamicClimb(), "MFW ID 6-state": ...})
        -> BareAirframeComparison  .to_pandas()  .plot()  .systems  .trims

The dissertation's Figs. 7.3-7.11 compare the linearised aircraft built on
different inflow models: on-axis responses (p/delta_lat, q/delta_lon,
r/delta_ped, w/delta_col) and the off-axis p/delta_lon. Here each inflow model
gives one trim and one linear model (:func:`~aircraft.helicopter.linearize`,
pilot inputs of Eq. 7.19), evaluated on a common frequency grid; adding an
inflow model is one more dictionary entry. Rates are reported in deg/s and w
in ft/s per unit pilot input (as in the figures: pilot inputs are radians of
mixed swashplate angle, so the magnitudes read per rad); ``coupled=True`` gives
the single-axis plants of Eq. 7.21 instead (other axes held by coupling
numerators, as in Fig. 7.11).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import control
import numpy as np
import pandas as pd

from ..configs import FT
from .coupling import coupling_numerator
from .linearize import linearize
from .model import Helicopter, HelicopterSettings
from .trim import TrimCondition, trim

__all__ = ["DEFAULT_RESPONSE_PAIRS", "BareAirframeComparison", "compare_bare_airframe",
           "frequency_response_table"]

#: (output, input) pairs of Figs. 7.3-7.11: on-axis, then the key off-axis one
DEFAULT_RESPONSE_PAIRS = (("p", "delta_lat"), ("q", "delta_lon"), ("r", "delta_ped"),
                          ("w", "delta_col"), ("p", "delta_lon"))

# the loops Eq. 7.21 holds for each on-axis response
_HOLD = {"p": {"q": "delta_lon", "r": "delta_ped", "w": "delta_col"},
         "q": {"p": "delta_lat", "r": "delta_ped", "w": "delta_col"},
         "r": {"p": "delta_lat", "q": "delta_lon", "w": "delta_col"},
         "w": {"p": "delta_lat", "q": "delta_lon", "r": "delta_ped"}}

_UNITS = {"p": ("deg/s", np.degrees(1.0)), "q": ("deg/s", np.degrees(1.0)), "r": ("deg/s", np.degrees(1.0)),
          "w": ("ft/s", 1.0 / FT), "u": ("ft/s", 1.0 / FT), "v": ("ft/s", 1.0 / FT)}


def frequency_response_table(sys, pairs, omega, model="model"):
    """Magnitude [dB] and phase [deg] of SISO channels of ``sys`` on ``omega``.

    Parameters
    ----------
    sys : control.StateSpace
        Named inputs and outputs.
    pairs : sequence of (output, input)
    omega : array_like
        Frequencies [rad/s].
    model : str
        Value of the ``model`` column.

    Returns
    -------
    pandas.DataFrame
        Long table: ``model, response, output, input, omega, magnitude_db, phase_deg,
        unit``; outputs p, q, r in deg/s, u, v, w in ft/s, per rad of input.
        The phase is unwrapped along frequency.
    """
    omega = np.asarray(omega, float)
    rows = []
    for out, inp in pairs:
        if out not in sys.output_labels or inp not in sys.input_labels:
            raise ValueError(f"{model}: no channel {out}/{inp} (outputs {sys.output_labels[:9]}..., "
                             f"inputs {sys.input_labels})")
        siso = sys[sys.output_labels.index(out), sys.input_labels.index(inp)]
        unit, scale = _UNITS.get(out, ("SI", 1.0))
        h = np.asarray(siso(1j * omega)).ravel() * scale
        rows.append(pd.DataFrame({"model": model, "response": f"{out}/{inp}", "output": out, "input": inp,
                                  "omega": omega, "magnitude_db": 20 * np.log10(np.abs(h)),
                                  "phase_deg": np.degrees(np.unwrap(np.angle(h))), "unit": unit}))
    return pd.concat(rows, ignore_index=True)


@dataclass
class BareAirframeComparison:
    """Frequency responses of the aircraft with each inflow model.

    Attributes
    ----------
    table : pandas.DataFrame
        Long table of :func:`frequency_response_table`, all models.
    systems : dict
        Model name -> linear aircraft (``control.StateSpace``, pilot inputs).
    trims : dict
        Model name -> :class:`~aircraft.helicopter.TrimResult`.
    pairs : tuple
    coupled : bool
    """

    table: pd.DataFrame
    systems: dict = field(default_factory=dict)
    trims: dict = field(default_factory=dict)
    pairs: tuple = DEFAULT_RESPONSE_PAIRS
    coupled: bool = False

    def to_pandas(self) -> pd.DataFrame:
        """The long response table (one row per model, response and frequency)."""
        return self.table.copy()

    def difference(self, reference, band=(1.0, 10.0)) -> pd.DataFrame:
        """Largest magnitude [dB] and phase [deg] difference from ``reference`` in ``band``.

        Parameters
        ----------
        reference : str
            Model name to compare against.
        band : (float, float)
            Frequency band [rad/s].
        """
        t = self.table
        inb = t[(t.omega >= band[0]) & (t.omega <= band[1])]
        ref = inb[inb.model == reference].set_index(["response", "omega"])
        rows = []
        for (model, resp), g in inb[inb.model != reference].groupby(["model", "response"], sort=False):
            r = ref.loc[resp].reindex(g.omega.values)
            dmag = g.magnitude_db.values - r.magnitude_db.values
            dph = (g.phase_deg.values - r.phase_deg.values + 180) % 360 - 180
            rows.append({"model": model, "response": resp, "reference": reference,
                         "max_abs_magnitude_diff_db": float(np.max(np.abs(dmag))),
                         "max_abs_phase_diff_deg": float(np.max(np.abs(dph)))})
        return pd.DataFrame(rows)

    def plot(self, figsize=None):
        """Bode overlays, one column per response: magnitude (top), phase (bottom).

        Returns
        -------
        matplotlib.figure.Figure
        """
        from matplotlib.figure import Figure
        n = len(self.pairs)
        fig = Figure(figsize=figsize or (3.4 * n, 6), constrained_layout=True)
        axes = fig.subplots(2, n, sharex=True, squeeze=False)
        for j, (out, inp) in enumerate(self.pairs):
            resp = f"{out}/{inp}"
            for model, g in self.table[self.table.response == resp].groupby("model", sort=False):
                axes[0, j].semilogx(g.omega, g.magnitude_db, label=model)
                axes[1, j].semilogx(g.omega, g.phase_deg, label=model)
            unit = self.table[self.table.response == resp].unit.iloc[0]
            title = resp + (" (Eq. 7.21)" if self.coupled and inp == _on_axis_input(out) else "")
            axes[0, j].set_title(title)
            axes[0, j].set_ylabel(f"|{out}/{inp}| [dB, {unit}/rad]" if j == 0 else "")
            axes[1, j].set_ylabel("phase [deg]" if j == 0 else "")
            axes[1, j].set_xlabel("frequency [rad/s]")
            for ax in axes[:, j]:
                ax.grid(alpha=0.3, which="both")
        axes[0, 0].legend(fontsize=7)
        return fig


def _on_axis_input(out):
    return {"p": "delta_lat", "q": "delta_lon", "r": "delta_ped", "w": "delta_col"}.get(out)


def compare_bare_airframe(inflows, config=None, condition=None, omega=None,
                          pairs=DEFAULT_RESPONSE_PAIRS, coupled=False, settings=None):
    """Trim, linearise and evaluate the aircraft once per inflow model.

    Parameters
    ----------
    inflows : dict
        Name -> inflow model (an :class:`~aircraft.inflow.InflowModel`, fresh per
        entry: models are frozen at their trim) or an already linearised
        aircraft (``control.StateSpace`` with pilot inputs), e.g. to add a
        variant built elsewhere.
    config : AircraftConfig, optional
        Default :func:`aircraft.coaxial_compound` (hover rotor speed).
    condition : TrimCondition, optional
        Default hover.
    omega : array_like, optional
        Frequencies [rad/s]; default 200 log-spaced points over 0.1-30 rad/s
        (the hover band of Figs. 7.3-7.11).
    pairs : sequence of (output, input)
        Default :data:`DEFAULT_RESPONSE_PAIRS`.
    coupled : bool
        If True, on-axis responses are the coupling numerators of Eq. 7.21 (the
        other three axes held); off-axis pairs stay bare.
    settings : HelicopterSettings, optional
        Default 8 span points, 1 azimuth (exact in hover).

    Returns
    -------
    BareAirframeComparison
    """
    from ..configs import coaxial_compound
    if not inflows:
        raise ValueError("inflows is empty: give at least one name -> inflow model")
    config = config or coaxial_compound()
    condition = condition or TrimCondition()
    settings = settings or HelicopterSettings(n_span=8, n_average=1)
    omega = np.logspace(-1, np.log10(30.0), 200) if omega is None else np.asarray(omega, float)
    tables, systems, trims = [], {}, {}
    for name, model in inflows.items():
        if isinstance(model, control.StateSpace):
            sys = model
        else:
            tr = trim(Helicopter(config, model, settings), condition)
            sys = linearize(tr)
            trims[name] = tr
        systems[name] = sys
        for out, inp in pairs:
            chan = sys
            if coupled and inp == _on_axis_input(out):
                chan = coupling_numerator(sys, out, inp, _HOLD[out])
            tables.append(frequency_response_table(chan, [(out, inp)], omega, model=name))
    return BareAirframeComparison(pd.concat(tables, ignore_index=True), systems, trims, tuple(pairs), coupled)
