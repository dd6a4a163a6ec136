"""Studies: the models against references and each other (convergence, speed against
accuracy, stability, Eq. 21 over lambda, friction variants).

Each module's ``run`` computes and returns a small frozen dataclass; nothing here writes a
file or draws. :func:`webfem.io.studies.write` writes a study's CSV, chart and markdown, and
``webfem study KIND CASE --out DIR`` does both.
"""
