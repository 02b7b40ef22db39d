"""The seed 20 MW shell blade's static instability (issue 33, docs/notes/seed_comparison.md section 5).

The seed 20 MW shell rotor "diverges" at 7.96 RPM at 4 and 10 m/s (the beam of its layup at 9.73): the
p-k maps' static instability.  It is not the blade's aeroelastic divergence but a structural one, a
local mode of the fore shear web's free root end (the web starts at 4.5 % span inside the 9 m root
cylinder; 3 elements across its 2.9 m height) that the centrifugal stress stiffness of the frozen-
azimuth model drives to zero frequency: no aerodynamics is needed for it, and the beam has no such
mode.  These checks pin that diagnosis on the blade alone (clamped at the hub, pitch 0, the default
shell mesh), with the structural terms of the p-k model (``rotor_terms``, the seed's physics).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.sparse as sp


@pytest.mark.slow
def test_seed20mw_shell_static_instability_is_the_fore_web_root_buckling_under_the_centrifugal_stress():
    """At rest the mode is at 1.65 Hz with at least 90 % of its kinetic energy in at most 8 of the
    blade's 4421 nodes, all on the fore web within 6 % of the span (measured: 4 nodes, 4.5 % span).
    With the centrifugal stress stiffness it falls to zero between 5.8 and 6.1 RPM (the lowest
    eigenvalue positive at 5.8, negative at 6.1 and that mode the same nodes; measured 5.95 RPM with
    the complete shell initial stress of issue 33, 7.25 RPM with the membrane-only one, whose
    bracket was 7.0-7.5); without it the mode stays within 1 % of its frequency at rest at 8 RPM
    (spin softening alone does not touch it).  The p-k maps' 7.96 RPM (membrane-only) was this
    instability in their projected basis (which stiffens it: 1.29 Hz at 5 RPM against 1.22 here).
    With pyfe3d's one-point transverse shear (``shell_shear: one-point``), as measured.  With MITC4's
    shear (the default since Dec 2026) the mode at rest is at 1.645 Hz in 10 nodes up to 10.6 % span,
    not all on the web, and the stiffness is already indefinite at 5.8 RPM (-55 1/s^2 near the shift,
    in 7 nodes up to 7.5 % span): not understood yet (docs/verification.md, "Not verified", item 18)."""
    from windflutter.mesh.settings import MeshSettings
    from windflutter.mesh.turbine import build_model, rotor_geometry
    from windflutter.model import load_turbine
    from windflutter.rotor.rotating import rotor_terms
    from windflutter.structure.assembly import assemble
    from windflutter.structure.modal import symmetric_eigs
    from windflutter.units import RPM

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the seed files give no damping (warned)
        t = load_turbine("seed20mw")
        fe, _ = build_model(t, MeshSettings(model="shell", part="rotor_blade", pitch=0.0,
                                                shell_shear="one-point"))
    st = assemble(fe)
    terms = rotor_terms(fe, st, rotor_geometry(t), prestress=True, rigid_sections=False)
    T = sp.csr_matrix(st.T)
    K0, M, Kr1, Ks1 = ((T.T @ sp.csr_matrix(A) @ T).tocsc() for A in (st.K, st.M, terms.Kr1, terms.Ksigma1))
    md = np.asarray(st.M.diagonal()).reshape(-1, 6)[:, :3]
    x = np.asarray(fe.nodes, float)
    r = np.linalg.norm(x - np.asarray(t.rotor_apex, float), axis=1)
    blade = fe.node_groups["blade0"]
    span = (r - r[blade].min()) / (r[blade].max() - r[blade].min())
    web = fe.region_names.index("blade0:web:web_fore")
    web_nodes = np.unique(fe.shell_conn[np.asarray(fe.element_regions["shell"]) == web])

    def lowest(rpm, stress=1.0, shift=-50.0):
        W = rpm * RPM
        w2, X = symmetric_eigs(K0 - W**2 * Kr1 + stress * W**2 * Ks1, M, 1, shift=shift)
        u = np.asarray(T @ X[:, 0]).reshape(-1, 6)[:, :3]
        e = (md * u**2).sum(axis=1)
        o = np.argsort(-e)
        return float(w2[0]), o[:int(np.searchsorted(np.cumsum(e[o]) / e.sum(), 0.9)) + 1]

    w0, nodes = lowest(0.0, shift=(2 * np.pi * 1.65) ** 2)
    f0 = np.sqrt(w0) / (2 * np.pi)
    assert f0 == pytest.approx(1.65, abs=0.1)
    assert len(nodes) <= 8 and np.isin(nodes, web_nodes).all() and span[nodes].max() < 0.06, (nodes, span[nodes])
    w7, _ = lowest(5.8)
    w75, nodes75 = lowest(6.1)
    assert w7 > 0 > w75, (w7, w75)
    assert set(nodes75) <= set(nodes) | set(web_nodes[span[web_nodes] < 0.06]), nodes75
    w8, _ = lowest(8.0, stress=0.0, shift=(2 * np.pi * 1.65) ** 2)
    assert np.sqrt(w8) / (2 * np.pi) == pytest.approx(f0, rel=0.01)
