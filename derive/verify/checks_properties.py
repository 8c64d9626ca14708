"""Checkers of the property claims: statements about a whole basis, for a whole λ interval.

Each kind is decided exactly by derive/formulas/properties.py for every degree of the family's range
(from the record's `min_degree` on) and every λ of the record's `parameter_range` (default: the
family's range), never at sampled λ. A failure names the degree, the exact λ (or an interval
with rational ends isolating an irrational one) and what goes wrong there.

Registered into checks_core.CHECKERS on import (verify/registry.py imports this module).
"""

from __future__ import annotations

from fractions import Fraction

import flint
import sympy as sp

from ..families.registry import REFERENCE
from ..formulas import properties as pr
from .checks_core import (
    LAM,
    Outcome,
    S,
    checker,
    claim_kind,
)
from .checks_equations import (
    check_equations,
)
from .checks_joins import (
    JOIN_CONTINUITY,
    records_by_id_safe,
)
from .context import (
    Context,
)
from .expr_parse import (
    parse,
)

MAX_LINES = 6  # failing degrees listed in full; the rest are counted


def _interval(record: dict) -> pr.Interval | None:
    family = record["family"]
    text = record.get("parameter_range")
    if text is None:
        return pr.FAMILY_RANGES.get(family)
    if family == REFERENCE:
        raise ValueError(f"the {REFERENCE} family has no shape parameter: drop parameter_range")
    return pr.Interval.parse(text)


def _degrees(record: dict, ctx: Context) -> list[int]:
    lo = int(record.get("min_degree", 0))
    if "n" in record:  # a claim about one degree (as `n` fixes it for every other kind)
        n = int(record["n"])
        if n not in ctx.family.degrees or n < lo:
            raise ValueError(
                f"n = {n} is not a degree of the {ctx.family.name} range from min_degree {lo} on"
            )
        return [n]
    degrees = [d for d in ctx.family.degrees if d >= lo]
    if not degrees:
        raise ValueError(f"no degree of the {ctx.family.name} range is >= min_degree {lo}")
    return degrees


def _scope(record: dict, ctx: Context, iv) -> str:
    degrees = _degrees(record, ctx)
    where = f", every λ in {iv} (exact)" if iv is not None else ""
    return f"degrees {degrees[0]}..{degrees[-1]}{where}"


def _outcome(findings: list[pr.Finding], scope: str) -> Outcome:
    lines = [f.text for f in findings[:MAX_LINES]]
    if len(findings) > MAX_LINES:
        lines.append(
            f"(fails in {len(findings)} degrees; also degree "
            + ", ".join(str(f.degree) for f in findings[MAX_LINES:])
            + ")"
        )
    return Outcome("mismatch" if findings else "match", lines, [scope])


def _per_degree(record: dict, ctx: Context, decide) -> Outcome:
    iv = _interval(record)
    family = record["family"]
    findings = [f for n in _degrees(record, ctx) if (f := decide(family, n, iv)) is not None]
    return _outcome(findings, _scope(record, ctx, iv))


@checker("basis_partition_of_unity")
def check_partition_of_unity(record: dict, ctx: Context) -> Outcome:
    return _per_degree(record, ctx, lambda f, n, iv: pr.partition_of_unity(f, n))


@checker("basis_symmetric")
def check_symmetric(record: dict, ctx: Context) -> Outcome:
    return _per_degree(record, ctx, lambda f, n, iv: pr.symmetry(f, n))


@checker("basis_endpoint_interpolation")
def check_endpoint_interpolation(record: dict, ctx: Context) -> Outcome:
    return _per_degree(record, ctx, lambda f, n, iv: pr.endpoint_interpolation(f, n))


@checker("basis_nonnegative")
def check_nonnegative(record: dict, ctx: Context) -> Outcome:
    return _per_degree(record, ctx, pr.nonnegative)


@checker("basis_linearly_independent")
def check_linearly_independent(record: dict, ctx: Context) -> Outcome:
    return _per_degree(record, ctx, pr.linear_independence)


@checker("curve_convex_hull")
def check_convex_hull(record: dict, ctx: Context) -> Outcome:
    """A curve lies in the convex hull of its control points for every choice of them iff its
    basis is non-negative and sums to one: decided as those two."""

    def decide(family, n, iv):
        return pr.nonnegative(family, n, iv) or pr.partition_of_unity(family, n)

    return _per_degree(record, ctx, decide)


@checker("basis_reduces_to_bernstein")
def check_reduces_to_bernstein(record: dict, ctx: Context) -> Outcome:
    value = parse(record.get("shape", "0"))
    if not value.is_Rational:
        raise ValueError(f"shape {record.get('shape')!r} must be an exact number")
    shape = Fraction(int(value.p), int(value.q))
    iv = _interval(record)
    lines = []
    if iv is not None and not iv.contains(shape):
        lines.append(f"λ = {shape} is outside the parameter range {iv}")
    findings = [
        f
        for n in _degrees(record, ctx)
        if (f := pr.reduces_to_bernstein(record["family"], n, shape)) is not None
    ]
    out = _outcome(findings, _scope(record, ctx, None) + f", at λ = {shape}")
    if lines:
        out.diffs = lines + out.diffs
        out.verdict = "mismatch"
    return out


@checker("basis_degree")
def check_degree(record: dict, ctx: Context) -> Outcome:
    """Every basis function is a polynomial in t of degree at most the claimed one (for every
    λ), and some function reaches it (for all but finitely many λ)."""
    claimed = parse(record["claimed_degree"])
    if not claimed.free_symbols <= {S["n"]}:
        raise ValueError(f"claimed_degree {record['claimed_degree']!r} may use n only")
    findings = []
    for n in _degrees(record, ctx):
        want = int(claimed.subs(S["n"], n))
        got = pr.degree_in_t(record["family"], n)
        if got != want:
            findings.append(
                pr.Finding(n, f"degree {n}: the basis functions have degree {got}, not {want}", {})
            )
    return _outcome(findings, _scope(record, ctx, None) + " (degree in t)")


# --------------------------------------------------------------------------- proofs and words

# A proof's intermediate equalities (chains a = b = c as consecutive entries) are equations of
# the family's models, checked like any printed formula: for every degree and index.
checker("proof_step")(check_equations)


@checker("count")
def check_count(record: dict, ctx: Context) -> Outcome:
    """A count stated in words ("n - 1 vectors") against the number of items of the index
    range the same sentence defines (`counted = "lo..hi"`, inclusive): hi - lo + 1."""
    lo_text, hi_text = record["counted"].split("..", 1)
    lo, hi = parse(lo_text), parse(hi_text)
    printed = parse(record["count"])
    derived = sp.expand(hi - lo + 1)
    if sp.expand(printed - derived) == 0:
        return Outcome("match", [], [f"count of {record['counted']}: {derived}"])
    return Outcome(
        "mismatch",
        [f"count: printed {printed}, but {record['counted']} has {derived} items"],
        [f"count of {record['counted']}"],
    )


CONTINUITY_OF_KIND = JOIN_CONTINUITY


@checker("condition_name")
def check_condition_name(record: dict, ctx: Context) -> Outcome:
    """The name a statement gives its condition (`continuity`: C1, C2, G1, G2) against the
    condition its formulas are verified to be: the join record it states (`uses`), whose own
    verdict compares those formulas with the derivation of that continuity."""
    printed = record["continuity"]
    diffs, checked = [], []
    for rid in record["uses"]:
        used = records_by_id_safe(rid)
        kind = claim_kind(used["claim"])
        derived = CONTINUITY_OF_KIND.get(kind)
        if derived is None:
            raise ValueError(f"{rid} is not a join record (claim {used['claim']})")
        checked.append(f"{rid}: {kind} ({derived})")
        if printed != derived:
            diffs.append(
                f"the condition is called {printed}, but its formulas ({rid}) are the {derived} "
                "conditions"
            )
    return Outcome("mismatch" if diffs else "match", diffs, checked)


def _sign_findings(record: dict, ctx: Context, want: str) -> tuple[list[pr.Finding], str]:
    """Where `expression` (in the degree symbol n or m and lam) is not `want` (positive or
    nonzero) for a degree of the range and a λ of the interval: decided exactly per degree."""
    expr = parse(record["expression"])
    extra = expr.free_symbols - {S["n"], S["m"], LAM}
    if extra:
        names = ", ".join(sorted(map(str, extra)))
        raise ValueError(f"expression may use n or m and lam only, not {names}")
    iv = _interval(record)
    deg_syms = [s for s in (S["n"], S["m"]) if s in expr.free_symbols]

    def where(deg: int) -> str:
        return ", ".join(f"{s} = {deg}" for s in deg_syms) or f"degree {deg}"

    findings = []
    for deg in _degrees(record, ctx):
        e = expr.subs({s: deg for s in deg_syms})
        poly = sp.Poly(e, LAM)
        p = flint.fmpq_poly([_fmpq_of(c) for c in reversed(poly.all_coeffs())])
        if p.is_zero() and want != "nonnegative":
            findings.append(pr.Finding(deg, f"{where(deg)}: {expr} is identically 0", {}))
            continue
        if p.is_zero():
            continue
        bad = pr.negative_point(p, iv) if want in ("positive", "nonnegative") else None
        if bad is not None:
            value = e.subs(LAM, sp.Rational(bad.numerator, bad.denominator))
            findings.append(
                pr.Finding(deg, f"{where(deg)}, λ = {bad}: {expr} = {value} < 0", {"lam": bad})
            )
            continue
        zeros = pr.real_roots(p, iv) if p.degree() > 0 and want != "nonnegative" else []
        if zeros:
            at = ", ".join(str(z) for z in zeros)
            findings.append(
                pr.Finding(deg, f"{where(deg)}: {sp.factor(e)} = 0 at λ = {at}", {"lam": zeros[0]})
            )
    return findings, _scope(record, ctx, iv)


def _fmpq_of(c) -> flint.fmpq:
    c = sp.Rational(c)
    return flint.fmpq(int(c.p), int(c.q))


@checker("sign_on_range")
def check_sign_on_range(record: dict, ctx: Context) -> Outcome:
    """A sign a statement relies on (`sign`: positive, nonnegative or nonzero) for every degree
    of the range and every λ of the interval, decided exactly."""
    findings, scope = _sign_findings(record, ctx, record.get("sign", "positive"))
    return _outcome(findings, scope)


@checker("formula_domain")
def check_formula_domain(record: dict, ctx: Context) -> Outcome:
    """A printed formula divides by `expression`: it is defined on the whole stated range
    (`match`) or it is not, and the statement holds only with that exception (`caveat`,
    with the exact degree and λ where the denominator vanishes)."""
    findings, scope = _sign_findings(record, ctx, "nonzero")
    out = _outcome(findings, scope)
    if findings:
        out.verdict = "caveat"
        out.diffs = [
            f"the formula divides by {record['expression']}, which vanishes inside the stated "
            "range:"
        ] + out.diffs
    return out
