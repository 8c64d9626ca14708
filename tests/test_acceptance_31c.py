"""Third acceptance pass of issue #31 (surfaces): what tests/test_acceptance_31.py and
tests/test_acceptance_31b.py do not cover, each against a computation that does not use the
code under test (mpmath at 50 digits on the exact Bézier form or on a closed form, exact
Fractions, dense sampling)."""

from __future__ import annotations

from fractions import Fraction as F

import mpmath as mp
import numpy as np
import pytest

import lambda_bezier as lb

# ------------------------------------------------ curvatures near a degenerate point
# The graph z = (x² + y²) / 2 over x = u + v, y = eps v: a biquadratic Bézier surface whose
# partials S_u = (1, 0, x) and S_v = (1, eps, x + eps² v) are nearly parallel for a small eps,
# while its curvatures are those of the paraboloid, K = 1 / w², H = (1 + w) / (2 w^(3/2)),
# w = 1 + x² + y² (sign: the normal S_u x S_v points up).
_T, _T2 = (F(0), F(1, 2), F(1)), (F(0), F(0), F(1))  # Bernstein coefficients of t, t²


def _sheared_paraboloid(eps: F) -> lb.BezierSurface:
    return lb.BezierSurface(
        [
            [
                (
                    _T[i] + _T[j],
                    eps * _T[j],
                    (_T2[i] + 2 * _T[i] * _T[j] + (1 + eps**2) * _T2[j]) / 2,
                )
                for j in range(3)
            ]
            for i in range(3)
        ]
    )


def _paraboloid_curvatures(eps: F, u: float, v: float) -> tuple[float, float]:
    with mp.workdps(50):
        x = mp.mpf(u) + mp.mpf(v)
        y = mp.mpf(eps.numerator) / eps.denominator * mp.mpf(v)
        w = 1 + x * x + y * y
        return float(1 / w**2), float((1 + w) / (2 * w ** mp.mpf(1.5)))


@pytest.mark.parametrize("k", [1, 2, 3, 4])
def test_curvatures_where_the_partials_are_nearly_parallel(k):
    """Where the curvatures are returned they are the paraboloid's, to 1e-7 (before: K was
    computed with EG - F², which cancels; it was wrong by 4e-4 at eps = 1e-6)."""
    eps = F(1, 10**k)
    K, H = _sheared_paraboloid(eps).curvatures(0.3, 0.4)
    K_ref, H_ref = _paraboloid_curvatures(eps, 0.3, 0.4)
    assert pytest.approx(K_ref, rel=1e-7) == K
    assert pytest.approx(H_ref, rel=1e-7) == H


@pytest.mark.parametrize("k", [6, 7, 8])
def test_curvatures_decided_by_rounding_are_refused(k):
    """Before: eps = 1e-7 gave K = 0.4098 (the true 0.4504, 9% off) without a word, eps = 1e-8
    a ValueError calling the curvature beyond the float range (EG - F² came out 0) and a
    divide-by-zero RuntimeWarning. Now a ValueError naming the point, as for the normal."""
    surf = _sheared_paraboloid(F(1, 10**k))
    surf.normal(0.3, 0.4)  # the normal itself is still defined within rounding
    with pytest.raises(
        ValueError, match=r"curvature is undefined within rounding at \(u, v\) = \(0.3, 0.4\)"
    ):
        surf.curvatures(0.3, 0.4)
    with pytest.raises(ValueError, match="undefined within rounding"):
        surf.curvatures(np.array([0.1, 0.3]), np.array([0.1, 0.4]))


def _bezier_curvatures(surf: lb.Surface, u: float, v: float) -> tuple[mp.mpf, mp.mpf]:
    """K and H of the exact Bézier form, at 50 digits (Bernstein derivatives by mpmath)."""
    net = surf.to_bezier().control_net()
    m, n = len(net) - 1, len(net[0]) - 1
    with mp.workdps(50):
        uu, vv = mp.mpf(u), mp.mpf(v)

        def bern(k: int, deg: int, t: mp.mpf, order: int) -> mp.mpf:
            return mp.diff(lambda x: mp.binomial(deg, k) * x**k * (1 - x) ** (deg - k), t, order)

        bu = {(i, a): bern(i, m, uu, a) for i in range(m + 1) for a in range(3)}
        bv = {(j, b): bern(j, n, vv, b) for j in range(n + 1) for b in range(3)}

        def part(a: int, b: int) -> list[mp.mpf]:
            return [
                mp.fsum(
                    mp.mpf(net[i][j][c].numerator) / net[i][j][c].denominator * bu[i, a] * bv[j, b]
                    for i in range(m + 1)
                    for j in range(n + 1)
                )
                for c in range(3)
            ]

        su, sv, suu, suv, svv = part(1, 0), part(0, 1), part(2, 0), part(1, 1), part(0, 2)
        dot = lambda x, y: mp.fsum(p * q for p, q in zip(x, y, strict=True))  # noqa: E731
        cross = [
            su[1] * sv[2] - su[2] * sv[1],
            su[2] * sv[0] - su[0] * sv[2],
            su[0] * sv[1] - su[1] * sv[0],
        ]
        nrm = [x / mp.sqrt(dot(cross, cross)) for x in cross]
        e, f, g = dot(su, su), dot(su, sv), dot(sv, sv)
        l_, m_, n_ = dot(suu, nrm), dot(suv, nrm), dot(svv, nrm)
        det = e * g - f * f
        return (l_ * n_ - m_ * m_) / det, (e * n_ - 2 * f * m_ + g * l_) / (2 * det)


# row 0 is one point: the edge u = 0 collapses and the curvatures grow like 1/u towards it
_COLLAPSED = [[(0, 0, 0)] * 4] + [[(i, j, (i * j) % 3) for j in range(4)] for i in range(1, 4)]


@pytest.mark.parametrize(
    "surf",
    [
        lb.SameDegreeSurface(_COLLAPSED, F(1, 2), F(-1, 3)),
        lb.BernsteinLikeSurface(_COLLAPSED, F(1, 3), F(1, 5)),
    ],
    ids=["same_degree", "bernstein_like"],
)
def test_curvatures_towards_a_collapsed_edge(surf):
    """Every curvature returned on the way to the collapsed edge is the exact form's to 1e-6;
    at u = 1e-12 the point is refused (the normal, or the curvature, undefined within
    rounding), never a wild float."""
    for k in (2, 4, 6, 8):
        K, H = surf.curvatures(10.0**-k, 0.4)
        K_ref, H_ref = _bezier_curvatures(surf, 10.0**-k, 0.4)
        assert pytest.approx(float(K_ref), rel=1e-6) == K
        assert pytest.approx(float(H_ref), rel=1e-6) == H
    with pytest.raises(ValueError, match="undefined"):
        surf.curvatures(1e-12, 0.4)


# ---------------------------------------------------------------- JSON, untrusted text
@pytest.mark.parametrize("depth", [100_000, 5_000])
def test_deeply_nested_json_is_a_value_error(depth):
    """Before: surface_from_json (and the curves' loader) let the decoder's RecursionError
    through, a deep traceback from untrusted text."""
    from lambda_bezier._json_io import _load_document
    from lambda_bezier.surface_export import surface_from_json

    text = "[" * depth + "]" * depth
    for load in (surface_from_json, _load_document):
        with pytest.raises(ValueError, match="nested too deeply"):
            load(text)
    inside = '{"lambda_bezier": 1, "kind": "surface", "net": ' + text + "}"
    with pytest.raises(ValueError, match="nested too deeply"):
        surface_from_json(inside)


def test_deeply_nested_family_files_are_named_errors(tmp_path):
    """A family definition (TOML) or derived document (JSON) nested past the recursion limit:
    before, RecursionError from the decoder; now the FamilyFileError (a ValueError) naming
    the file."""
    deep = tmp_path / "deep.toml"
    deep.write_text("a = " + "[" * 100_000 + "]" * 100_000 + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match="deep.toml: not valid TOML: nested too deeply"):
        lb.load_family(deep)
    from lambda_bezier import examples

    src = examples.path("nouri_saeidian.toml")
    (tmp_path / "nouri_saeidian.toml").write_text(src.read_text(encoding="utf-8"), "utf-8")
    (tmp_path / "nouri_saeidian.derived.json").write_text("[" * 100_000 + "]" * 100_000)
    with pytest.raises(ValueError, match="not a derived family document"):
        lb.load_family(tmp_path / "nouri_saeidian.toml")


def test_deeply_nested_records_file_is_named(tmp_path):
    """`lambda-bezier verify` on a records file nested past the recursion limit: before, a
    RecursionError traceback; now exit 2 with the file named."""
    import subprocess
    import sys

    deep = tmp_path / "deep.records.toml"
    deep.write_text("a = " + "[" * 20_000 + "]" * 20_000 + "\n", encoding="utf-8")
    run = subprocess.run(
        [sys.executable, "-m", "lambda_bezier", "verify", str(deep)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert "Traceback" not in run.stderr
    assert "deep.records.toml: not valid TOML: nested too deeply" in run.stderr
    assert run.returncode != 0
