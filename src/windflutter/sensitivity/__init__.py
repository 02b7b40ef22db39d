"""Design sensitivities: the derivative of every named mode's frequency and damping ratio with
respect to the blade's section properties (element by element) and global parameters, by
first-order eigenvalue perturbation with left and right eigenvectors (docs/sensitivity.md)."""
