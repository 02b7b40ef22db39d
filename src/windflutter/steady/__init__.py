"""The deflected steady state of a rotor under centrifugal and steady BEM aerodynamic loads.

``steady_state(fe, struct, sections, rotor_geometry, V, omega, n_blades=..)`` -> :class:`SteadyState`
(see :mod:`windflutter.steady.state`); layers: uses ``structure``, ``rotor`` and ``aero``, used by
``solve`` and above.
"""

from windflutter.steady.state import SteadyOptions, SteadyState, steady_state

__all__ = ["SteadyOptions", "SteadyState", "steady_state"]
