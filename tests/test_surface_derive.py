"""The surface derivations of derive/ (issue 31): the energy matrices integrated from the
tensor-product basis against the Kronecker form, the patch joins against the runtime's
join_surface, and verify's surface claim kinds on records that match and records that do not."""

from __future__ import annotations

import copy
import importlib
from fractions import Fraction

import pytest
from conftest import ROOT

import lambda_bezier as lb
from lambda_bezier import _derive_runner
from lambda_bezier.surface_joins import join_surface

pytestmark = pytest.mark.skipif(
    not (ROOT / "derive" / "formulas" / "surface_energy.py").is_file(),
    reason="needs the source checkout (derive/)",
)


def _derive(name: str):
    return importlib.import_module(f"{_derive_runner.load_derive(ROOT).__name__}.{name}")


@pytest.fixture(scope="module")
def se():
    return _derive("formulas.surface_energy")


@pytest.fixture(scope="module")
def sj():
    return _derive("formulas.surface_joins")


@pytest.fixture(scope="module")
def report():
    return _derive("verify.report")


# ---------------------------------------------------------------------- energy matrices
@pytest.mark.parametrize(
    "fu, fv, m, n",
    [("same_degree", "bernstein_like", 3, 2), ("bezier", "same_degree", 2, 3)],
)
@pytest.mark.parametrize("energy", ["membrane", "thin_plate"])
def test_direct_integration_equals_kronecker_for_mixed_families(se, fu, fv, m, n, energy):
    direct = se.surface_matrices(fu, fv, m, n, energy)
    assert direct == se.kronecker_matrices(fu, fv, m, n, energy)
    assert (2 if fu != "bezier" else 0, 2) in direct  # quadratic in each shape parameter
    se.check_kronecker(fu, fv, m, n, energy)


@pytest.mark.parametrize(
    "fu, fv, m, n, energy",
    [
        ("same_degree", "bernstein_like", 3, 2, "thin_plate"),
        ("bezier", "same_degree", 1, 3, "membrane"),
    ],
)
def test_moment_form_equals_integrating_each_product(se, fu, fv, m, n, energy):
    # surface_matrices integrates through the moments of the square (issue #29); here each
    # entry is the literal definition instead: the two partials multiplied as polynomials
    # and the product integrated over u, then v, in FLINT
    basis = se.tensor_basis(fu, fv, m, n)
    direct = se.surface_matrices(fu, fv, m, n, energy)
    size = len(basis)
    want: dict = {}
    for ku, kv, weight in se.ENERGIES[energy]:
        parts = [se._partial(b, ku, kv) for b in basis]
        for r in range(size):
            for c in range(size):
                product = parts[r] * parts[c]
                integral = product.integral(0).subs({"u": 1}).integral(1).subs({"v": 1})
                for (_, _, a, b), coef in integral.to_dict().items():
                    mat = want.setdefault((int(a), int(b)), [[0] * size for _ in range(size)])
                    mat[r][c] += weight * coef
    want = {key: mat for key, mat in want.items() if any(any(row) for row in mat)}
    assert sorted(direct) == sorted(want)
    for key, mat in want.items():
        assert [list(row) for row in direct[key]] == mat, key


def test_kronecker_check_rejects_a_changed_entry(se):
    full = dict(se.surface_matrices("same_degree", "same_degree", 3, 3, "thin_plate"))
    key = (1, 1)
    rows = [list(r) for r in full[key]]
    rows[2][5] += 1
    full[key] = tuple(tuple(r) for r in rows)
    with pytest.raises(AssertionError, match="differ"):
        se.check_kronecker("same_degree", "same_degree", 3, 3, "thin_plate", full)


def test_emitted_forms_are_the_derived_ones(se):
    from lambda_bezier._lazy import generated

    table = generated("surface_energy").SURFACE_ENERGY
    assert set(table) == set(se.FAMILIES)
    for fam, entries in table.items():
        for (m, n, energy), forms in entries.items():
            assert forms == se.surface_forms(fam, fam, m, n, energy)


def test_membrane_energy_of_a_bilinear_patch_by_hand(se):
    # S = P00 (1-u)(1-v) + P01 (1-u)v + P10 u(1-v) + P11 uv; for the scalar net P00 = 1 (others
    # 0): S_u = -(1-v), S_v = -(1-u), ∫∫ S_u² + S_v² = 1/3 + 1/3.
    full = se.surface_matrices("bezier", "bezier", 1, 1, "membrane")[(0, 0)]
    assert Fraction(int(full[0][0].p), int(full[0][0].q)) == Fraction(2, 3)


# ---------------------------------------------------------------------- joins
def test_columnwise_reduction_holds_for_every_pair(sj):
    sj.check_all()


def test_columnwise_check_rejects_a_wrong_weight(sj, monkeypatch):
    real = dict(sj._curve_joins())
    key = ("bezier", "bezier", "C1")
    changed = dict(real[key])
    changed[(1, "first", 1)] = changed[(1, "first", 1)] + 1
    monkeypatch.setattr(sj, "_curve_joins", lambda: {**real, key: changed})
    with pytest.raises(AssertionError, match="do not match"):
        sj.check_columnwise.__wrapped__("bezier", "bezier", "C1")


def _lam(fam: str, value: Fraction) -> Fraction | None:
    return None if fam == "bezier" else value


@pytest.mark.parametrize(
    "first, second, continuity",
    [
        ("same_degree", "bernstein_like", "G1"),
        ("bezier", "same_degree", "C2"),
        ("bernstein_like", "bernstein_like", "C1"),
        ("same_degree", "same_degree", "C2"),
    ],
)
def test_derived_conditions_give_the_runtime_join(sj, first, second, continuity):
    n, m, along = 3, 4, 2
    lam1, lam2, alpha = Fraction(1, 3), Fraction(-2, 5), Fraction(3, 2)
    if continuity != "G1":
        alpha = Fraction(1)
    net = [[(i + j, i * j - 1, (i - j) ** 2) for j in range(along + 1)] for i in range(n + 1)]
    patch = lb.Surface(net, _lam(first, lam1), None, family=(first, "bezier"))
    order = sj.ORDER[continuity]
    rest = [[(9 + r, j, r * j) for j in range(along + 1)] for r in range(order + 1, m + 1)]
    got = join_surface(
        patch,
        "u",
        continuity,
        m,
        _lam(second, lam2),
        rest=rest,
        alpha=alpha,
        family=second,
    ).control_net()
    values = {
        "lam1": lam1 if first != "bezier" else 0,
        "lam2": lam2 if second != "bezier" else 0,
        "alpha": alpha,
    }
    given = {order + 1 + k: row for k, row in enumerate(rest)}
    for coord in range(3):
        scalar = [[Fraction(p[coord]) for p in row] for row in net]
        given_c = {r: [Fraction(p[coord]) for p in row] for r, row in given.items()}
        head = sj.apply(first, second, continuity, scalar, n, m, values, given_c)
        for r, row in enumerate(head):
            assert [got[r][j][coord] for j in range(along + 1)] == row, (r, coord)


# ---------------------------------------------------------------------- verify
def _records(se) -> list[dict]:
    s, upper = se.surface_forms("same_degree", "same_degree", 3, 3, "membrane")[(0, 1)]
    base = {"source": "test", "family": "same_degree"}
    return [
        {
            **base,
            "id": "s.basis",
            "claim": "same_degree.surface_basis",
            "degrees": [3, 3],
            "lam_u": "1/2",
            "lam_v": "-1",
            "uv": ["1/3", "1/4"],
            "values": [[str(x) for x in row] for row in _values(se, 3, 3)],
        },
        {**base, "id": "s.unity", "claim": "same_degree.surface_basis", "sums_to_one": True},
        {
            **base,
            "id": "s.bnd",
            "claim": "same_degree.surface_boundary",
            "degrees": [3, 4],
            "side": "v=1",
            "line": "column n",
        },
        {
            **base,
            "id": "s.corner",
            "claim": "same_degree.surface_corners",
            "degrees": [3, 4],
            "corners": [[0, 0, 0, 0], [1, 1, 3, 4], [1, 0, 3, 0]],
        },
        {
            **base,
            "id": "s.join",
            "claim": "same_degree.surface_continuity",
            "continuity": "C1",
            "second_family": "bezier",
            "weights": [
                {"row": 0, "source": "first", "k": 0, "weight": "1"},
                {"row": 1, "source": "first", "k": 0, "weight": "(m + n - 1 + lam1)/m"},
                {"row": 1, "source": "first", "k": 1, "weight": "-(n - 1 + lam1)/m"},
            ],
        },
        {
            **base,
            "id": "s.energy",
            "claim": "same_degree.surface_energy_matrix",
            "degrees": [3, 3],
            "energy": "membrane",
            "term": [0, 1],
            "scale": str(s),
            "matrix": [list(row) for row in upper],
        },
    ]


def _values(se, m, n):
    import flint

    basis = se.tensor_basis("same_degree", "same_degree", m, n)
    at = {
        "u": flint.fmpq(1, 3),
        "v": flint.fmpq(1, 4),
        "lam_u": flint.fmpq(1, 2),
        "lam_v": flint.fmpq(-1),
    }
    vals = [basis[k].subs(at).to_dict().get((0, 0, 0, 0), flint.fmpq(0)) for k in range(len(basis))]
    return [
        [Fraction(int(x.p), int(x.q)) for x in vals[i * (n + 1) : (i + 1) * (n + 1)]]
        for i in range(m + 1)
    ]


def _broken(record: dict) -> dict:
    rec = copy.deepcopy(record)
    kind = rec["claim"].split(".", 1)[1]
    if kind == "surface_basis":
        rec["values"][1][2] = str(Fraction(rec["values"][1][2]) + 1)
    elif kind == "surface_boundary":
        rec["line"] = "column 0"
    elif kind == "surface_corners":
        rec["corners"][1] = [1, 1, 3, 3]
    elif kind == "surface_continuity":
        rec["weights"][2]["weight"] = "-(n + lam1)/m"
    else:
        rec["matrix"][0][1] += 1
    return rec


def test_surface_records_match_and_a_changed_one_does_not(se, report):
    records = _records(se)
    for rec in records:
        res = report.check_record(rec)
        assert res.error is None, (rec["id"], res.error)
        assert res.verdict == "match", (rec["id"], res.outcome.diffs)
        if rec["id"] == "s.unity":
            continue
        bad = report.check_record(_broken(rec))
        assert bad.error is None and bad.verdict == "mismatch", rec["id"]
        assert bad.outcome.diffs


def test_unity_check_fails_on_a_basis_that_does_not_sum_to_one(se, report, monkeypatch):
    # the records first: they are built from the derivation, which (unless an earlier test in
    # this worker cached it) integrates the basis and would meet the broken one below
    rec = _records(se)[1]
    real = se.tensor_basis

    def scaled(*args):
        basis = real(*args)
        return (basis[0] * 2, *basis[1:])

    monkeypatch.setattr(se, "tensor_basis", scaled)
    res = report.check_record(rec)
    assert res.verdict == "mismatch" and "sums to" in res.outcome.diffs[0]


def test_surface_records_validate_their_keys(report, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(
        'schema_version = 2\nsource = "x"\nfamily = "bezier"\n'
        '[[record]]\nid = "a"\nclaim = "surface_boundary"\ndegrees = [3, 3]\n'
        'side = "u=2"\nline = "row 0"\n'
    )
    with pytest.raises(ValueError, match="side"):
        report.load_records([path])
