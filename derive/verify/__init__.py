"""The verify layer: the papers' printed claims (derive/published/*.toml) against derive's own
derivations. From the bottom: the expression model (expr_parse, scalar, values, realiser,
compare), the checkers' registry of claim kinds (checks_core) and families
(claim_families), the context (context), the checkers by group of claim kinds (checks_*),
registry.py (which imports them all, with each built-in family's own checks module), the
records (records), the report (report) and coverage (coverage).

Beside derive.emit at the top of derive: nothing below imports it.
"""
