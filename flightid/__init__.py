"""flightid: frequency-domain system identification (CIFER-class), generic.

Nothing here knows about rotors: the same code identifies a free-vortex wake,
a flight-test record or a wind-tunnel record.
"""
__all__: list = []
