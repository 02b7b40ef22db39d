"""The operating-point service: the one place that composes the operating-point Campbell.

``windflutter campbell`` (:mod:`windflutter.cli.campbell`), :func:`windflutter.api.campbell` and the
Campbell stage of ``windflutter run`` (:func:`windflutter.analysers.operating_campbell`) all call
:func:`operating_campbell`: it owns the model (method p's
:class:`~windflutter.system.operational.OperationalModel`, from the analysis config), the defaults
(the wind speeds of the operating curve within 3-25 m/s; the frequency limit
:meth:`~windflutter.system.reference.StructuralReference.default_max_hz`, 1.25 x the blade's 1st
torsion frequency) and the named, tracked modes (:mod:`windflutter.system.identity`).
"""

from __future__ import annotations

from typing import Any

from windflutter.config import AnalysisConfig
from windflutter.methods import operational_options
from windflutter.system.campbell import campbell
from windflutter.system.operational import OperationalModel, missing_curve_error


def campbell_model(turbine: Any, config: AnalysisConfig):
    """Method p's operating-point model of ``turbine`` for ``config`` (its one aerodynamic variant;
    with several, the first one analysed with method p)."""
    aero = next((a for a, m in config.cases if m == "p"), config.aero[0])
    return OperationalModel(turbine, operational_options(config, aero))


def campbell_max_hz(config: AnalysisConfig, model) -> float:
    """The Campbell's frequency limit (Hz): the config's ``campbell.max_hz``, else the default of
    ``model``'s identities (1.25 x the blade's 1st torsion frequency)."""
    return config.campbell.max_hz if config.campbell.max_hz is not None else model.reference().default_max_hz()


def operating_campbell(turbine: Any, config: AnalysisConfig, wind_speeds=None, *, model=None, progress=None,
                       workers: int | None = 1, prepared: dict | None = None):
    """The operating-point Campbell diagram of ``turbine`` with the analysis ``config``.

    Parameters
    ----------
    turbine : a :class:`~windflutter.model.Turbine`.
    config : the checked analysis config (its ``campbell.max_hz``, model, aerodynamics, solver).
    wind_speeds : m/s; None: the operating curve's within 3-25 m/s.
    model : an operating-point model built for ``config`` to reuse (its parts are cached), e.g. the
        one the run's stability solver built.
    progress : optional ``progress(fraction, text)``.
    workers : processes evaluating the points (:func:`windflutter.system.campbell.campbell_workers`;
        None: the cores for a shell model, 1 for a beam model).
    prepared : ``{wind speed: point}`` already evaluated with ``config``'s model (a run's stability
        map: :func:`windflutter.system.campbell.campbell_point` of each sweep's operating point).

    Returns
    -------
    windflutter.system.campbell.CampbellResult
    """
    if getattr(turbine, "operating_curve", None) is None:
        raise missing_curve_error(turbine)
    om = model if model is not None else campbell_model(turbine, config)
    return campbell(om.turbine, wind_speeds, max_hz=campbell_max_hz(config, om), model=om, progress=progress,
                    workers=workers, prepared=prepared)
