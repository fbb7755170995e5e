"""The catalogue: one proof module per paper (installed as ``lkverify.proofs``).

Each module reads like its paper: the same symbols, equation numbers in
comments.  It declares systems, functionals, hypotheses and claims; lkverify
derives, checks and reports.
"""
