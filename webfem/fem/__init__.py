"""Finite-element building blocks: meshes, weak forms, nonlinear solvers. No files, no plots."""
