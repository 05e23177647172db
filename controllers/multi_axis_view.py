"""One axis of a multi-axis EMF design seen as a single-axis design.

The specs (:func:`controllers.evaluate_specs`, :func:`controllers.hq_window`) read a
single-axis design's methods; :class:`AxisView` gives them for one axis of a
:class:`~controllers.multi_axis.MultiAxisEMF` with every loop closed, so the same
spec objects grade a single-axis and a multi-axis design.
"""
from __future__ import annotations

import numpy as np

from .emf import FrequencyFunction, _eval

__all__ = ["AxisView"]


class AxisView:
    """One axis of a :class:`MultiAxisEMF` with every loop closed, shaped like a single-axis design.

    Gives the methods the specs read (:func:`controllers.evaluate_specs`,
    :func:`controllers.hq_window`): ``broken_loop`` (loop broken at this axis's
    actuator, the other loops closed), ``disturbance_response``,
    ``attitude_response``, ``mixer_response_pilot``/``_disturbance``,
    ``commanded_attitude``, ``closed_loop_poles`` (the whole closed loop's) and
    ``rate_response_system`` (Padé state space).

    Parameters
    ----------
    emf : MultiAxisEMF
    axis : str
        One of ``emf.axes``.
    """

    def __init__(self, emf, axis):
        self.emf, self.axis = emf, axis
        self.gains = emf.loops[axis].gains
        self.equivalent_delay = emf.loops[axis].equivalent_delay

    def broken_loop(self):
        return self.emf.broken_loop(self.axis)

    def disturbance_response(self):
        return self.emf.disturbance_response(self.axis)

    def attitude_response(self):
        return self.emf.command_response(self.axis, self.axis, "attitude")

    def roll_rate_response(self):
        return self.emf.command_response(self.axis, self.axis, "rate")

    def mixer_response_pilot(self):
        return self.emf.mixer_response(self.axis, self.axis)

    def mixer_response_disturbance(self):
        return FrequencyFunction(self.emf._disturbance(self.axis, "mixer"), f"delta_mx_{self.axis}/att_d")

    def commanded_attitude(self):
        lp = self.emf.loops[self.axis]
        return FrequencyFunction(lambda s: _eval(lp.command_model.tf(), s) * np.exp(-s * lp.equivalent_delay),
                                 "att_cm/delta")

    def closed_loop_poles(self, pade_order=3):
        return self.emf.closed_loop_poles(pade_order)

    def feedback_poles(self, pade_order=3):
        return self.emf.feedback_poles(pade_order)

    def rate_response_system(self, pade_order=3):
        cl = self.emf.closed_loop(pade_order)
        return cl[cl.output_labels.index(f"rate_{self.axis}"), cl.input_labels.index(f"stick_s_{self.axis}")]

    def broken_loop_statespace(self, pade_order=3):
        return self.emf.broken_loop_statespace(self.axis, pade_order)
