"""Our own deprecated calls and invalid escapes are test failures (pyproject.toml, issue 29): a
DeprecationWarning or SyntaxWarning issued from a windflutter module is raised as an error under
pytest, another package's stays a warning."""

import warnings

import pytest


@pytest.mark.parametrize("category", [DeprecationWarning, SyntaxWarning])
def test_our_warnings_of_these_kinds_are_errors(category):
    with pytest.raises(category):
        warnings.warn_explicit("an old call", category, "api.py", 1, module="windflutter.api")


def test_other_packages_deprecations_stay_warnings():
    with pytest.warns(DeprecationWarning):
        warnings.warn_explicit("an old call", DeprecationWarning, "x.py", 1, module="somepackage.x")
