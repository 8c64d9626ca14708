"""Join weights of one-parameter families defined by data, read from their derived documents
(the ``surface_joins`` table: the column-wise curve joins in closed form in n and m, as
polynomial data) by `_derived_joins.lookup`, against the numeric per-degree solve
(`_join_engine.weights`), which stays the fallback where a document has no pair (C2, G2)."""

from __future__ import annotations

import json
from fractions import Fraction as F
from pathlib import Path

import pytest

import lambda_bezier as lb
from lambda_bezier import _atom_joins, _join_engine, examples
from lambda_bezier.curves import family_class

ROOT = Path(__file__).resolve().parents[1]


def _one_parameter_documents() -> list[Path]:
    """Every shipped or test definition whose derived document is of a one-parameter
    family with surface joins (format 3, no ``parameters`` table)."""
    found = []
    for doc in sorted(
        [*Path(examples.path("nouri_saeidian.toml")).parent.glob("*.derived.json")]
        + [*(ROOT / "tests" / "data" / "families").glob("*.derived.json")]
    ):
        data = json.loads(doc.read_text())
        joins = data.get("surface_joins")
        if "parameters" not in data and isinstance(joins, dict) and "pairs" in joins:
            found.append(doc.with_name(doc.name.replace(".derived.json", ".toml")))
    return found


DOCUMENTS = _one_parameter_documents()
BUILTINS = ("bezier", "same_degree", "bernstein_like")


def test_there_is_a_one_parameter_document_to_check():
    assert any(p.name == "nouri_saeidian.toml" for p in DOCUMENTS)


def _params(cls):
    return [None] if not cls._has_lambda else [F(1, 3), F(-1, 2)]


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: p.stem)
@pytest.mark.parametrize("continuity", ["C1", "G1"])
def test_document_weights_are_the_per_degree_solve_on_every_builtin_pair(path, continuity):
    fam = lb.load_family(path)
    lo, hi = fam.data.LAMBDA_RANGE
    own_values = [F(lo) + (F(hi) - F(lo)) * k / 4 for k in (1, 2, 3)]
    alpha = F(3, 2) if continuity == "G1" else F(1)
    checked = 0
    for other in (*BUILTINS, fam):
        cls = family_class(other)
        degrees = (3, 5) if cls._any_degree else tuple(cls._data.DEGREES)[:2]
        for n in fam.degrees[:2]:
            for m in degrees:
                for lam1 in own_values[:2]:
                    for lam2 in _params(cls) if cls is not fam.curve_class else own_values[1:]:
                        pts = [(k, (k * k) % 5) for k in range(n + 1)]
                        # the family first, `other` second; then `other` first, the family second
                        for first, second, deg2, value2 in (
                            (fam.curve(pts, lam1), cls, m, lam2),
                            (
                                cls([(k, k % 3) for k in range(m + 1)], lam2)
                                if cls._has_lambda
                                else cls([(k, k % 3) for k in range(m + 1)]),
                                fam.curve_class,
                                n,
                                lam1,
                            ),
                        ):
                            a = _atom_joins.join_side(first, 1, first.degree)
                            b = _atom_joins.join_side(second, 2, deg2, value2)
                            derived = _atom_joins.derived_weights(a, b, continuity, alpha, F(0))
                            if first.family in BUILTINS and second.family in BUILTINS:
                                continue
                            assert derived is not None, (first.family, second.family)
                            solved = _join_engine.weights(
                                first, 1, alpha, F(0), second, deg2, value2, continuity
                            )
                            assert derived == solved  # exact Fractions, term by term
                            checked += 1
    assert checked >= 16


def test_join_reads_the_document_and_solves_only_where_it_has_no_pair(monkeypatch):
    """With the per-degree solve disabled, C1 and G1 still join (the document's weights);
    C2, which the document does not hold, needs the solve."""
    fam = lb.load_family(examples.path("nouri_saeidian.toml"))
    curve = fam.curve([(0, 0), (1, 2), (3, 3), (4, 0)], F(1, 2))
    rest = {"C1": [(5, 1), (6, 0), (7, 2)], "G1": [(5, 1), (6, 0), (7, 2)], "C2": [(6, 0), (7, 2)]}

    def joined(c):
        return lb.join(
            curve, c, 4, F(1, 3), alpha=F(2) if c == "G1" else 1, rest=rest[c], family="same_degree"
        )

    want = {c: joined(c) for c in ("C1", "G1", "C2")}

    def no_solve(*args, **kwargs):
        raise AssertionError("the per-degree solve was called")

    monkeypatch.setattr(_join_engine, "weights", no_solve)
    for c in ("C1", "G1"):
        assert joined(c).control_points() == want[c].control_points()
    with pytest.raises(AssertionError, match="per-degree solve"):
        joined("C2")


def test_surface_join_derived_uses_the_same_lookup():
    fam = lb.load_family(examples.path("nouri_saeidian.toml"))
    net = [[(i, j, (i * j) % 3) for j in range(4)] for i in range(4)]
    s = fam.surface(net, F(1, 2), F(1, 4))
    rest = [[(4 + k, j, 0) for j in range(4)] for k in range(2)]
    solved = lb.join_surface(s, "u", "C1", 3, F(1, 3), rest=rest, family="same_degree")
    derived = lb.join_surface(
        s, "u", "C1", 3, F(1, 3), rest=rest, family="same_degree", conditions="derived"
    )
    assert derived.control_net() == solved.control_net()
