import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))


@pytest.fixture(scope="session")
def nrel5mw_fixed(nrel5mw):
    """NREL 5 MW with a valid nacelle inertia (yaw only, Jonkman 2009 NacYIner = 2,607,890 kg m^2)
    -- the reader currently returns a non-symmetric tensor for the windIO v2 file."""
    import dataclasses

    import numpy as np

    I = np.asarray(nrel5mw.nacelle.inertia)
    if np.allclose(I, I.T) and np.all(np.linalg.eigvalsh(0.5 * (I + I.T)) >= -1e-9 * abs(I).max()):
        return nrel5mw
    return dataclasses.replace(nrel5mw, nacelle=dataclasses.replace(nrel5mw.nacelle, inertia=np.diag([0.0, 0.0, 2607890.0])))
