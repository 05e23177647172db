"""Identified (perturbation) inflow models inside the aircraft: :class:`IdentifiedInflow`.

An identified model is a perturbation about the trim it was identified at:
``x' = A x + B (u - u_ref)``, ``lambda = lambda_ref + C x + D (u - u_ref)`` with
u the loads (and flap rates for F/G/C models with wake distortion), in seconds.
Its reference inflow travels with it. For printed models that give no trim
inflow, :meth:`IdentifiedInflow.from_published` takes the reference inflow from a
momentum-based model's steady state at the model's trim loads (documented there).
"""
from __future__ import annotations

import control
import numpy as np

from .base import InflowModel, RotorOperatingPoint, flap_rate_names, inflow_names, load_names
from .pitt_peters import InflowError

__all__ = ["IdentifiedInflow"]


class IdentifiedInflow(InflowModel):
    """Wrap an identified inflow model (any order, delays as Padé states).

    Parameters
    ----------
    system : control.StateSpace
        Inputs named with the canonical load names (optionally followed by
        flap-rate names), outputs the inflow names, time in seconds.
    rotors : tuple of str
    loads_ref : array_like
        Loads (C_T, C_L, C_M per rotor) at the identification trim.
    inflow_ref : array_like
        Inflow harmonics at that trim (what the blade sees, interference included).
    """

    def __init__(self, system, rotors=("U", "L"), loads_ref=None, inflow_ref=None, name="identified"):
        self.rotors = tuple(rotors)
        sys = control.ss(system)
        loads = load_names(self.rotors)
        rates = flap_rate_names(self.rotors)
        inputs = list(sys.input_labels)
        if inputs == loads:
            self.uses_flap_rates = False
        elif inputs == loads + rates:
            self.uses_flap_rates = True
        else:
            raise InflowError(f"identified model inputs {inputs} must be {loads} (+ {rates})")
        if list(sys.output_labels) != inflow_names(self.rotors):
            raise InflowError(f"identified model outputs {sys.output_labels} must be {inflow_names(self.rotors)}")
        if np.any(np.abs(np.asarray(sys.D)) > 1e-12):
            # a direct load -> inflow feedthrough would close an algebraic loop with
            # the blade-element loads; identified inflow models are strictly proper
            raise InflowError("identified inflow model has a feedthrough (D != 0): not supported")
        if sys.nstates and np.max(np.linalg.eigvals(sys.A).real) >= 0:
            raise InflowError("the identified inflow model is unstable: refusing to use it in the aircraft")
        self.system = sys
        self.name = name
        n = len(self.rotors)
        self.loads_ref = np.zeros(3 * n) if loads_ref is None else np.asarray(loads_ref, float)
        self.inflow_ref = np.zeros(3 * n) if inflow_ref is None else np.asarray(inflow_ref, float)
        if self.loads_ref.shape != (3 * n,) or self.inflow_ref.shape != (3 * n,):
            raise InflowError(f"loads_ref and inflow_ref need {3 * n} entries")

    @property
    def state_names(self):
        return list(self.system.state_labels)

    def _u(self, loads, rates):
        du = np.asarray(loads, float) - self.loads_ref
        if du.shape != self.loads_ref.shape:
            raise InflowError(f"loads must have {self.loads_ref.size} entries")
        if self.uses_flap_rates:
            r = np.zeros(2 * len(self.rotors)) if rates is None else np.asarray(rates, float)
            du = np.concatenate([du, r])
        return du

    def derivatives(self, x, loads, ops, rates=None):
        return self.system.A @ np.asarray(x, float) + self.system.B @ self._u(loads, rates)

    def inflow(self, x, loads, ops):
        return self.inflow_ref + self.system.C @ np.asarray(x, float)   # D == 0 (checked)

    def steady_state(self, loads, ops):
        return -np.linalg.solve(self.system.A, self.system.B @ self._u(loads, None))

    def linear(self, loads, ops):
        sys = control.ss(self.system.A, self.system.B, self.system.C, self.system.D,
                         inputs=self.input_names, outputs=self.output_names, states=self.state_names,
                         name=self.name)
        x0 = self.steady_state(loads, ops)
        sys.trim_states, sys.trim_inputs = x0, np.concatenate([loads, np.zeros(len(self.rate_names))])
        sys.trim_outputs = self.inflow(x0, loads, ops)
        return sys

    # -- constructors -----------------------------------------------------------
    @classmethod
    def from_matrices(cls, M, L, tau=None, *, omega, rotors=("U", "L"), loads_ref=None, inflow_ref=None,
                      pade_order=None, name="identified M/Lbar/tau"):
        """From the M/Lbar/tau form (azimuth time with ``omega`` [rad/s], delays [s],
        row-wise per Eq. 2.16), delays absorbed by Padé into a minimal realisation."""
        from flightid import MLTauStructure
        M, L = np.asarray(M, float), np.asarray(L, float)
        tau = np.zeros_like(M) if tau is None else np.asarray(tau, float)
        values = {}

        def pattern(mat, p):
            rows = []
            for i in range(mat.shape[0]):
                row = []
                for j in range(mat.shape[1]):
                    if mat[i, j] != 0:
                        values[f"{p}{i}_{j}"] = mat[i, j]
                        row.append(f"{p}{i}_{j}")
                    else:
                        row.append(0.0)
                rows.append(row)
            return rows
        structure = MLTauStructure(pattern(M, "m"), pattern(L, "l"), pattern(tau, "t"),
                                   inputs=load_names(rotors), outputs=inflow_names(rotors),
                                   initial=values, omega=omega)
        return cls(structure.to_statespace(pade_order=pade_order), rotors, loads_ref, inflow_ref, name)

    @classmethod
    def from_published(cls, model, reference=None, pade_order=None):
        """A printed model of :mod:`aircraft.inflow.published` as an aircraft inflow model.

        The dissertation prints no trim inflow for its identified models; the
        reference inflow is the steady state of ``reference`` (default:
        :class:`~aircraft.inflow.coaxial.DynamicClimb` for coaxial models) at the
        model's trim thrusts with zero hub moments, in hover at ``model.omega``.
        """
        from .coaxial import DynamicClimb
        from .pitt_peters import PittPeters
        rotors = tuple(model.rotors)
        cts = [model.condition.get(f"CT_{r}" if r else "CT") for r in rotors]
        if any(c is None for c in cts):
            raise InflowError(f"{model.name}: no trim thrust in its condition {model.condition}")
        loads_ref = np.concatenate([[c, 0.0, 0.0] for c in cts])
        reference = reference or (DynamicClimb() if len(rotors) == 2 else PittPeters(rotors))
        ops = tuple(RotorOperatingPoint(omega=model.omega) for _ in rotors)
        x = reference.steady_state(loads_ref, ops)
        inflow_ref = reference.inflow(x, loads_ref, ops)
        return cls.from_matrices(model.M, model.L, model.tau, omega=model.omega, rotors=rotors,
                                 loads_ref=loads_ref, inflow_ref=inflow_ref, pade_order=pade_order,
                                 name=model.name)
