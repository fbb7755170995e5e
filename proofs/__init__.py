"""The catalogue: one proof package per paper (installed as ``lkverify.proofs``), one module per item.

Each module reads like its paper: the same symbols, equation numbers in
comments.  It declares systems, functionals, hypotheses and claims; lkverify
derives, checks and reports.
"""
