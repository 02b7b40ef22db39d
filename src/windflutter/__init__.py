"""windflutter: frequency-domain aeroelastic stability (flutter, divergence) of wind turbines.

The package folders mirror the analysis pipeline:
model -> mesh -> structure -> rotor -> aero -> solve -> stability -> post.
"""

__version__ = "0.1.0"
