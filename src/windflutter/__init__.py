"""windflutter: frequency-domain aeroelastic stability (flutter, divergence) of wind turbines.

The package folders mirror the analysis pipeline:
model -> mesh -> structure -> rotor -> aero -> solve -> steady -> system -> overspeed -> post
(the import layers are in ``docs/architecture.md``).

Importing windflutter applies its BLAS-thread policy to the process (one thread unless the
environment variable ``WINDFLUTTER_BLAS_THREADS`` says otherwise; see :mod:`windflutter.threads`).

The Python API (:mod:`windflutter.api`, loaded on first use so that ``import windflutter`` stays
light) ::

    import windflutter

    turbine = windflutter.load_turbine("nrel5mw")        # windIO, OpenFAST .fst, HAWC2 .htc, bundled name
    windflutter.modes(turbine, part="blade", n=4)         # natural frequencies (beam model)
    windflutter.campbell(turbine, [6.0, 11.0, 18.0])      # frequency and damping of every mode
    windflutter.stability(turbine, [11.0])                # flutter / divergence onset per wind speed
    windflutter.run(turbine, "analysis.yaml")             # the whole analysis -> out/nrel5mw/
    windflutter.analysis_config(aero="potential")         # a validated analysis config
"""

from windflutter.version import __version__  # noqa: E402

from windflutter import threads as _threads  # noqa: E402  (after __version__: cheap, no NumPy)

_threads.apply_policy()

#: the API functions re-exported here (from :mod:`windflutter.api`)
# (simulate is windflutter.api's only: the sub-package windflutter.simulate holds that name)
_API = ("load_turbine", "modes", "campbell", "stability", "run", "analysis_config", "confirm_onset")


def __getattr__(name: str):
    if name in _API:
        from windflutter import api  # noqa: PLC0415

        return getattr(api, name)
    raise AttributeError(f"module 'windflutter' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_API))


__all__ = ["__version__", *_API]
