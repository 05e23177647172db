"""The coaxial's 200 kt trim with each propeller model, beside the dissertation's rotor thrusts.

::

    propeller_models_at_200kt(inflows)   C_T per rotor, propeller pitch, thrust and power
                                         for the uniform-inflow and blade-element propellers

The dissertation trims the aircraft at 200 kt to a rotor angle of attack of
2 deg with "time averaged trim C_T for the upper and lower rotors of around
0.0073 and 0.0065" (§6.6). At a prescribed rotor angle of attack the rotors
carry the weight and the vertical share of the drag, so their thrust does not
depend on how the propeller makes its thrust; the propeller model changes the
pitch the propeller trims to and the power it draws.
"""
from __future__ import annotations

import math

import pandas as pd

__all__ = ["DISSERTATION_CT_200KT", "propeller_models_at_200kt"]

#: the dissertation's 200 kt trim thrust coefficients (upper, lower), §6.6
DISSERTATION_CT_200KT = (0.0073, 0.0065)


def propeller_models_at_200kt(inflows=None, speed=200.0 * 0.514444, rotor_aoa=math.radians(2.0)):
    """Trim the coaxial compound at 200 kt with each propeller model.

    Parameters
    ----------
    inflows : dict, optional
        ``{name: inflow factory}``; default Isolated Rotors and Dynamic Climb.
    speed : float
        Flight speed [m/s] (200 kt).
    rotor_aoa : float
        Rotor angle of attack of the trim [rad].

    Returns
    -------
    pandas.DataFrame
        One row per inflow and propeller model: ``inflow, propeller_model,
        CT_U, CT_L, CT_sum, CT_U_dissertation, CT_L_dissertation, theta_prop``
        [deg], ``prop_thrust`` [kN], ``prop_power`` [kW], ``max_residual``.
    """
    from aircraft import coaxial_compound
    from aircraft.helicopter import Helicopter, HelicopterSettings, TrimCondition, trim
    from aircraft.helicopter.airframe import PROPELLER_MODELS, propeller_loads
    from aircraft.inflow import DynamicClimb, IsolatedRotors
    if inflows is None:
        inflows = {"Isolated Rotors": IsolatedRotors, "Dynamic Climb": DynamicClimb}
    if not inflows:
        raise ValueError("inflows is empty: give at least one {name: inflow factory}")
    rows = []
    for name, factory in inflows.items():
        for model in PROPELLER_MODELS:
            heli = Helicopter(coaxial_compound(cruise=True), factory(), HelicopterSettings(propeller_model=model))
            tr = trim(heli, TrimCondition(speed=speed, rotor_aoa=rotor_aoa))
            cfg = heli.config
            thrust, torque = propeller_loads(cfg.propeller, tr.u[6], tr.x[0], cfg.rho, model=model)
            rows.append({"inflow": name, "propeller_model": model, "CT_U": tr.loads["CT_U"],
                         "CT_L": tr.loads["CT_L"], "CT_sum": tr.loads["CT_U"] + tr.loads["CT_L"],
                         "CT_U_dissertation": DISSERTATION_CT_200KT[0],
                         "CT_L_dissertation": DISSERTATION_CT_200KT[1],
                         "theta_prop": math.degrees(tr.u[6]), "prop_thrust": thrust / 1e3,
                         "prop_power": torque * cfg.propeller.omega / 1e3, "max_residual": tr.max_residual})
    return pd.DataFrame(rows)
