"""Transfer-function fitting (NAVFIT-like) and low-order equivalent systems (LOES).

:class:`TransferFunctionStructure` is a SISO model structure

    y/u = (b_m s^m + ... + b_1 s + b_0) / (s^n + a_{n-1} s^{n-1} + ... + a_0) * exp(-tau s)

whose coefficients are ordinary parameters of :func:`flightid.fit`, so the fit,
its CIFER cost, Cramér-Rao bounds, insensitivities, stability constraint,
multi-start and :func:`flightid.reduce` all apply unchanged.

:func:`fit_transfer_function` does the whole NAVFIT-style job in one call:
it starts the coefficients from a linear (Sanathanan-Koerner) fit of the
coherent data for a grid of delays and then minimises the CIFER cost.
:func:`loes_fit` fits a low-order equivalent system to a high-order model or a
measured response with unit coherence, and adds the handling-qualities mismatch
cost M = 20/n sum[(dG)^2 + 0.01745 (dP)^2] (dB, deg) to the cost table.
"""
from __future__ import annotations

import numpy as np
import control

from ._validation import integer, real_scalar
from .errors import IdentificationError, InputValueError
from .fitting import W_PHASE, FitResult, _wrap_deg, coherence_weight, fit
from .response import MeasuredResponse
from .structures import ModelStructure

__all__ = ["TransferFunctionStructure", "fit_transfer_function", "loes_fit", "loes_mismatch"]


class TransferFunctionStructure(ModelStructure):
    """SISO transfer function with an optional pure delay; coefficients are parameters.

    Parameters
    ----------
    num_order : int
        Numerator order m (parameters ``b0 .. bm``, coefficient of s^k is ``bk``).
    den_order : int
        Denominator order n >= 1, n >= m (monic; parameters ``a0 .. a{n-1}``).
    delay : bool
        Include the delay parameter ``tau`` [s].
    input, output : str
        Signal names.
    initial : dict, optional
        Initial values (default: every coefficient 1, ``tau`` 0).
    fixed : iterable of str
        Parameters held at their value (e.g. ``["tau"]`` or a known zero).

    Examples
    --------
    >>> s = TransferFunctionStructure(0, 1, initial={"b0": 2.0, "a0": 1.5, "tau": 0.05})
    >>> s.names
    ['b0', 'a0', 'tau']
    >>> h = s.frequency_response([1.5])[0, 0, 0]
    >>> round(float(abs(h)), 4)
    0.9428
    """

    def __init__(self, num_order, den_order, *, delay=True, input="u", output="y", initial=None, fixed=()):
        m = integer("num_order", num_order, minimum=0, error=InputValueError)
        n = integer("den_order", den_order, minimum=1, error=InputValueError)
        if m > n:
            raise InputValueError(f"num_order ({m}) must not exceed den_order ({n}): the model must be proper")
        self.num_order, self.den_order = m, n
        patterns = {"num": [[f"b{k}" for k in range(m + 1)]], "den": [[f"a{k}" for k in range(n)]],
                    "tau": [["tau"]] if delay else None}
        names = [f"b{k}" for k in range(m + 1)] + [f"a{k}" for k in range(n)] + (["tau"] if delay else [])
        start = {k: (0.0 if k == "tau" else 1.0) for k in names}
        start.update(dict(initial or {}))
        for k, v in start.items():
            real_scalar(f"initial[{k!r}]", v)
        self._init_parameters(patterns, [input], [output], start, fixed, None)

    def _undelayed(self, mats, s):
        b = mats["num"][0]
        a = np.append(mats["den"][0], 1.0)
        return (np.polyval(b[::-1], s) / np.polyval(a[::-1], s))[None, None, :]

    def _abcd(self, mats):
        b = mats["num"][0]
        a = mats["den"][0]
        n = a.size
        bb = np.zeros(n + 1)
        bb[:b.size] = b
        d = bb[n]
        r = bb[:n] - d * a                      # strictly proper remainder, ascending
        # observable canonical form: x1' = -a_{n-1} x1 + x2 + r_{n-1} u, ..., y = x1 + d u
        f = np.zeros((n, n))
        f[:, 0] = -a[::-1]
        f[:-1, 1:] = np.eye(n - 1)
        g = r[::-1].reshape(n, 1)
        c = np.zeros((1, n))
        c[0, 0] = 1.0
        return f, g, c, np.array([[d]])

    def transfer_function(self, values=None):
        """``(control.TransferFunction, delay [s])`` at ``values`` (default: current)."""
        mats = self.matrices(values)
        b = mats["num"][0][::-1]
        a = np.append(mats["den"][0], 1.0)[::-1]
        tf = control.tf(b, a, inputs=self.inputs, outputs=self.outputs)
        return tf, float(self._delays(mats)[0, 0])


def _linear_start(w, h, wgt, m, n, tau):
    """Sanathanan-Koerner linear fit of b, a to h * exp(j w tau); returns (b, a, rel. residual)."""
    s = 1j * w
    hd = h * np.exp(1j * w * tau)
    den_prev = np.ones_like(s)
    for _ in range(5):
        sc = wgt / np.maximum(np.abs(den_prev), 1e-300)
        # N(s) - H D(s) = H s^n: unknowns b0..bm, a0..a_{n-1}
        cols = [s ** k for k in range(m + 1)] + [-hd * s ** k for k in range(n)]
        mat = np.column_stack(cols) * sc[:, None]
        rhs = hd * s ** n * sc
        big = np.vstack([mat.real, mat.imag])
        sol, *_ = np.linalg.lstsq(big, np.concatenate([rhs.real, rhs.imag]), rcond=None)
        b, a = sol[:m + 1], sol[m + 1:]
        den_prev = np.polyval(np.append(a, 1.0)[::-1], s)
    model = np.polyval(b[::-1], s) / den_prev
    res = np.sqrt(np.sum(wgt ** 2 * np.abs(np.log(model / hd)) ** 2) / np.sum(wgt ** 2))
    return b, a, res


def _stable(a):
    """Denominator coefficients (ascending, monic implied) with RHP roots reflected."""
    roots = np.roots(np.append(a, 1.0)[::-1])
    roots = np.where(roots.real > 0, -roots.real + 1j * roots.imag, roots)
    roots = np.where(np.abs(roots.real) < 1e-6, roots - 1e-3, roots)
    return np.real(np.poly(roots))[::-1][:-1]


def fit_transfer_function(data, num_order, den_order, *, delay=True, output=None, input=None,
                          initial=None, fixed=(), coherence_min=0.6, frequency_ranges=None,
                          **fit_kwargs) -> FitResult:
    """Fit a numerator/denominator transfer function (+ delay) to a measured response.

    Parameters
    ----------
    data : MeasuredResponse
        The response with coherence.
    num_order, den_order : int
        Numerator and denominator orders (``0 <= num_order <= den_order``, ``den_order >= 1``).
    delay : bool
        Fit a delay ``tau`` [s].
    output, input : str, optional
        The pair fitted (default: the response's only pair).
    initial : dict, optional
        Start values; default from a linear Sanathanan-Koerner fit of the
        coherent points for a grid of 41 delays in [0, 2 pi / w_hi] s (the best one).
    fixed : iterable of str
        Parameters held at their start value.
    coherence_min : float
        Coherence threshold of the default fitted range and of the linear start.
    frequency_ranges : (float, float), optional
        Fitted range [rad/s] (default: coherent range).
    **fit_kwargs
        Passed on to :func:`flightid.fit` (``n_omega``, ``starts``, ...).

    Returns
    -------
    FitResult
        Parameters ``b*``, ``a*``, ``tau`` with CIFER Cramér-Rao bounds and
        insensitivities; ``structure.transfer_function()`` gives the model.

    Examples
    --------
    >>> import numpy as np
    >>> from flightid import MeasuredResponse
    >>> w = np.geomspace(0.3, 30, 60)
    >>> h = 4.0 / (1j * w + 2.0) * np.exp(-0.04j * w)
    >>> r = MeasuredResponse(h[None, None], w, np.ones((1, 1, 60)), ["u"], ["y"])
    >>> res = fit_transfer_function(r, 0, 1)
    >>> [round(res.structure.values[k], 3) for k in ("b0", "a0", "tau")]
    [4.0, 2.0, 0.04]
    """
    if not isinstance(data, MeasuredResponse):
        raise InputValueError(f"data must be a MeasuredResponse, got {type(data).__name__}")
    output = data.output_labels[0] if output is None else output
    input = data.input_labels[0] if input is None else input
    structure = TransferFunctionStructure(num_order, den_order, delay=delay, input=input, output=output)
    h, coh = data.element(output, input)
    w = data.omega
    if frequency_ranges is not None:
        lo, hi = frequency_ranges
    else:
        good = np.flatnonzero(coh >= coherence_min)
        if good.size < num_order + den_order + 2:
            raise IdentificationError(f"{output}/{input} has {good.size} points with coherence >= "
                                      f"{coherence_min}: too few for the {num_order + den_order + 2} "
                                      "coefficients (lower coherence_min or give frequency_ranges)")
        lo, hi = w[good[0]], w[good[-1]]
    start = dict(initial or {})
    missing = [k for k in structure.names if k not in start]
    if missing:
        sel = (w >= lo) & (w <= hi) & (coh >= min(coherence_min, 0.99))
        wg = np.sqrt(coherence_weight(coh[sel]))
        taus = np.linspace(0.0, 2 * np.pi / hi, 41) if delay else [0.0]
        best = min((_linear_start(w[sel], h[sel], wg, num_order, den_order, tau) + (tau,) for tau in taus),
                   key=lambda r: r[2])
        b, a, _, tau = best
        guess = {**{f"b{k}": v for k, v in enumerate(b)}, **{f"a{k}": v for k, v in enumerate(_stable(a))}}
        if delay:
            guess["tau"] = tau
        start = {**{k: guess[k] for k in missing}, **start}
    structure = structure.with_values(start).fix(list(fixed)) if fixed else structure.with_values(start)
    return fit(structure, data, frequency_ranges=(lo, hi), coherence_min=coherence_min, **fit_kwargs)


def loes_mismatch(model_response, data_response):
    """Handling-qualities LOES mismatch M = 20/n sum[(dG)^2 + 0.01745 (dP)^2] (dG in dB, dP in deg).

    Parameters
    ----------
    model_response, data_response : array_like, complex
        The low-order and the high-order (or measured) responses on one grid.

    Returns
    -------
    float
    """
    hm, hd = np.asarray(model_response), np.asarray(data_response)
    dg = 20 * np.log10(np.abs(hm)) - 20 * np.log10(np.abs(hd))
    dp = _wrap_deg(np.degrees(np.angle(hm) - np.angle(hd)))
    return float(20.0 / hd.size * np.sum(dg ** 2 + W_PHASE * dp ** 2))


def loes_fit(system, num_order, den_order, *, w_min=0.1, w_max=10.0, n_omega=30, delay=True,
             initial=None, fixed=(), **fit_kwargs) -> FitResult:
    """Low-order equivalent system of a high-order model or a measured response.

    Parameters
    ----------
    system : control.LTI or MeasuredResponse
        The high-order SISO system (python-control model, evaluated exactly on
        the grid; unit coherence) or a measured response.
    num_order, den_order : int
        Orders of the equivalent system (e.g. 1 and 2 for the pitch-rate LOES
        ``K (s + 1/T_theta2) e^{-tau s} / (s^2 + 2 zeta w s + w^2)``).
    w_min, w_max : float
        Matching range [rad/s] (0.1-10 rad/s in the handling-qualities specifications).
    n_omega : int
        Log-spaced matching frequencies.
    delay : bool
        Include the equivalent delay [s].
    initial, fixed, **fit_kwargs :
        As for :func:`fit_transfer_function`.

    Returns
    -------
    FitResult
        ``cost_table`` has a ``mismatch`` column (and ``cost_table.attrs["mismatch"]``).

    Examples
    --------
    >>> import control
    >>> hos = control.tf([3.0, 3.0], [1.0, 2.0, 9.0]) * control.tf([25.0], [1.0, 25.0])
    >>> res = loes_fit(hos, 1, 2)
    >>> round(res.structure.values["tau"], 2), bool(res.cost_table.mismatch.iloc[0] < 1)
    (0.04, True)
    """
    w_min = real_scalar("w_min", w_min, positive=True, unit="rad/s")
    w_max = real_scalar("w_max", w_max, positive=True, unit="rad/s")
    if not w_min < w_max:
        raise InputValueError(f"need w_min < w_max [rad/s], got {w_min}, {w_max}")
    n_omega = integer("n_omega", n_omega, minimum=3, error=InputValueError)
    if isinstance(system, MeasuredResponse):
        data = system
    elif isinstance(system, control.LTI):
        if system.ninputs != 1 or system.noutputs != 1:
            raise InputValueError(f"system must be SISO, got {system.noutputs} x {system.ninputs}")
        w = np.geomspace(w_min, w_max, n_omega)
        h = np.asarray(system(1j * w)).reshape(1, 1, -1)
        data = MeasuredResponse(h, w, np.ones(h.shape), ["u"], ["y"], name="high-order system")
    else:
        raise InputValueError(f"system must be a control.LTI or a MeasuredResponse, got {type(system).__name__}")
    result = fit_transfer_function(data, num_order, den_order, delay=delay, initial=initial, fixed=fixed,
                                   frequency_ranges=(w_min, w_max), n_omega=n_omega, **fit_kwargs)
    p = result.pairs[0]
    m = loes_mismatch(result.structure.frequency_response(p.omega)[0, 0], p.h)
    result.cost_table["mismatch"] = m
    result.cost_table.attrs["mismatch"] = m
    return result
