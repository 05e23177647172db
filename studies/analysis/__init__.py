"""Analyses specific to the dissertation's studies (not library code: a user's own rotor does not need them).

::

    six_state_diagnostics   the same 6-state data fitted several ways: why Eq. 5.3 is not trusted
    six_state_scan          the Eq. 5.3 family fitted from every start and judged by the guidelines
    twelve_state_variants   constrained 12-state structures compared on one data set, flown
    coaxial_200kt           the 200 kt model beside Table 6.3; the isolated-rotor check (Figs. 7.7-7.10)
    forward_flight          single-rotor forward-flight models beside Pitt-Peters and Eqs. 4.7-4.8

The studies import them from their modules; their tests live beside them
(``studies/analysis/tests``, collected by ``make test``): research code with tests,
kept out of the library and out of ``tests/``.
"""
