"""controllers.hq: a CONDUIT-class handling-qualities spec library with ADS-33E-PRF boundaries.

One module per spec family; every spec is an :class:`HQSpec` (a
:class:`controllers.specs.Spec`) carrying its metric, its Level boundaries as
data (polygons for 2-D charts), its source, its axis and where it applies::

    boundaries      LevelRegions (polygons), point-in-region, normalised margin
    bandwidth       attitude bandwidth / phase delay (hover charts, forward flight)
    quickness       attitude quickness from a pulse response
    large_amplitude achievable rates
    coupling        pitch-roll coupling, yaw due to collective
    heave           first-order fit of hdot/collective (T, tau)
    forward_flight  dutch roll, spiral, phugoid
    generic         CONDUIT generic specs (Table 7.3), OLOP with actuator limits, ModFoG2
    selector        specs_for(axis, mte=..., uce=..., attention=..., speed=..., agility=...)
    table           spec_table(): every spec, its source, boundaries and test
    charts          spec_chart / family_window: Level regions and a design's point

Boundaries that were not found printed are marked ``status="not found"``;
evaluating such a spec raises :class:`BoundaryNotPublishedError`.  A user who
holds the values (their copy of ADS-33E-PRF, a programme requirement) supplies
them by name, ``specs_for(..., boundaries={name: {...}})``, or per spec with
:meth:`HQSpec.with_boundaries`; the spec then grades and steers the DMO, its
status reading ``"supplied"`` and its source quoting theirs.
"""
from .base import AXES, HQSpec, MTE_CLASSES, RegionSpec
from .boundaries import BoundaryNotPublishedError, LevelRegions
from .charts import family_window, spec_chart
from .generic import ActuatorLimits
from .selector import all_specs, flight_regime, specs_for
from .table import spec_table

__all__ = ["HQSpec", "RegionSpec", "LevelRegions", "BoundaryNotPublishedError", "ActuatorLimits",
           "specs_for", "flight_regime", "all_specs", "spec_table", "spec_chart", "family_window", "AXES", "MTE_CLASSES"]
