"""windflutter.simulate: nonlinear time-domain simulation, a second implementation beside the
eigen-solvers (it shares the model data and the element and strip-force definitions, never a
linearized matrix), and the identification of frequency and damping from its response."""
