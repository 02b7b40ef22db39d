"""windflutter: frequency-domain aeroelastic stability (flutter, divergence) of wind turbines.

The package folders mirror the analysis pipeline:
model -> mesh -> structure -> rotor -> aero -> solve -> stability -> post
(the import layers are in ``docs/architecture.md``).

Importing windflutter applies its BLAS-thread policy to the process (one thread unless the
environment variable ``WINDFLUTTER_BLAS_THREADS`` says otherwise; see :mod:`windflutter.threads`).
"""

__version__ = "0.1.0"

from windflutter import threads as _threads  # noqa: E402  (after __version__: cheap, no NumPy)

_threads.apply_policy()
