"""The ``campbell`` command's table ends with one line on the structure: a blade structure unstable on
its own (family ``buckling`` modes) is said once, not in a line of its own beside the ValidityWarning
that explains it (the IEA 15 MW shell printed both), and "every mode damped" is not said flatly then."""

from __future__ import annotations

from types import SimpleNamespace

from windflutter.cli.campbell import _print_table


def _result(families):
    modes = [SimpleNamespace(name=f"mode {k}", frequency_hz=1.0 + k, damping_ratio=0.01, family=f)
             for k, f in enumerate(families)]
    point = SimpleNamespace(wind_speed=8.0, rotor_speed_rpm=5.68, pitch_deg=0.0, modes=modes)
    return SimpleNamespace(
        turbine="T", part="turbine", frame="ground-fixed", assumptions={}, points=[point],
        least_damped=lambda: (point, modes[0]), unstable=lambda: [],
        structure_unstable=lambda: [(point, m) for m in modes if m.family == "buckling"])


def test_a_structure_unstable_on_its_own_is_one_line(capsys):
    _print_table(_result(["edge", "buckling"]))
    out = capsys.readouterr().out.splitlines()
    assert sum("statically unstable" in line for line in out) == 1
    assert out[-1].startswith("every oscillating mode damped in operation, but the blade's FE structure alone is "
                              "statically unstable at 8 m/s")


def test_every_mode_damped_without_it(capsys):
    _print_table(_result(["edge", "flap"]))
    assert capsys.readouterr().out.splitlines()[-1] == "every mode damped in operation"
