"""Small shell/plate/tube model builders shared by the structure tests."""

import numpy as np

from windflutter.structure.fem import FEModel, IsotropicMaterial, Ply, ShellProperty


def plate(nx, ny, a, b, prop, matdir=(1.0, 0.0, 0.0)):
    """Flat rectangular plate in the x-y plane, nx x ny quads; returns (fe, node index grid)."""
    xs, ys = np.linspace(0, a, nx + 1), np.linspace(0, b, ny + 1)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    nodes = np.c_[X.ravel(), Y.ravel(), np.zeros(X.size)]
    idx = np.arange(X.size).reshape(nx + 1, ny + 1)
    conn = np.c_[idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()]
    fe = FEModel(nodes=nodes, shell_conn=conn, shell_prop=np.zeros(len(conn), int),
                 shell_matdir=np.tile(matdir, (len(conn), 1)), shell_properties=[prop])
    return fe, idx


def tube(nc, nl, R, L, prop):
    """Circular tube along x, nc nodes around, nl quads along; returns (fe, ring node index array)."""
    th = np.linspace(0, 2 * np.pi, nc, endpoint=False)
    xs = np.linspace(0, L, nl + 1)
    X, TH = np.meshgrid(xs, th, indexing="ij")
    nodes = np.c_[X.ravel(), R * np.cos(TH.ravel()), R * np.sin(TH.ravel())]
    idx = np.arange(X.size).reshape(nl + 1, nc)
    nxt = np.roll(idx, -1, axis=1)
    # counter-clockwise seen from outside: normal outward
    conn = np.c_[idx[:-1].ravel(), idx[1:].ravel(), nxt[1:].ravel(), nxt[:-1].ravel()]
    fe = FEModel(nodes=nodes, shell_conn=conn, shell_prop=np.zeros(len(conn), int),
                 shell_matdir=np.tile([1.0, 0, 0], (len(conn), 1)), shell_properties=[prop])
    return fe, idx


def iso(E, nu, rho, t):
    return ShellProperty(plies=(Ply(IsotropicMaterial(E, nu, rho), t, 0.0),))
