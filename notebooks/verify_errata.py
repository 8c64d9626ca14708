# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # What the papers print, beside what the derivation gives
#
# `lambda-bezier verify` checks every transcribed formula against the derivation. This
# notebook runs it on the records it finds wrong, prints each erratum (printed form,
# corrected form, the verifier's diff) and draws two of them, so the size of each misprint is
# visible. Needs SymPy (the `derive` extra); uses the checkout's derive/ when run inside one.

# %%
import importlib
import os
import sys
from pathlib import Path

try:
    import sympy as sp
except ImportError:
    raise SystemExit(
        "this tutorial re-derives formulas with SymPy: pip install 'lambda-bezier[derive]'"
    ) from None
import matplotlib.pyplot as plt
import numpy as np

import lambda_bezier as lb

# derive/ from the checkout when there is one (the first of the working directory and its
# parents that holds derive/: the notebook runs from notebooks/, and from docs/tutorials/
# when the docs are built), else the copy installed with the package, with its records
CHECKOUT = next(
    (
        p
        for p in (Path.cwd().resolve(), *Path.cwd().resolve().parents)
        if (p / "derive" / "__init__.py").is_file()
    ),
    None,
)
if CHECKOUT is not None:
    sys.path.insert(0, str(CHECKOUT))
    DERIVE = "derive"
else:
    DERIVE = "lambda_bezier._derive"
verify = importlib.import_module(f"{DERIVE}.verify.report")
parse = importlib.import_module(f"{DERIVE}.verify.expr_parse").parse

FIGURES = Path(os.environ.get("LAMBDA_BEZIER_FIGURES", Path.cwd() / "figures"))
FIGURES.mkdir(parents=True, exist_ok=True)

# %% [markdown]
# ## Every mismatch, re-derived now

# %%
records = verify.load_records()
suspects = [r for r in records if r.get("expect") == "mismatch"]
report = verify.verify(suspects, index=records, jobs=1)
for res in report.results:
    print(f"{res.id} ({res.record['location']}): {res.verdict}")
    print("   ", res.record["erratum"]["explanation"])
    print("    corrected form re-checked:", res.erratum.verdict if res.erratum else "-")
    assert res.verdict == "mismatch" and res.erratum is not None
    assert res.erratum.verdict == "match"
print(verify._summary(report))

# %% [markdown]
# ## 000, eq. (7): the printed three-term form is not the basis
#
# The printed coefficients, evaluated for n = 5 and λ = 1/2, against the basis functions of
# eq. (1) (here from `SameDegreeCurve.basis`, i.e. from the generated expansions).

# %%
t = sp.Symbol("t")
eq7 = next(r for r in records if r["id"] == "000.eq7")
bern = sp.Function("B")
n_val, lam_val = 5, sp.Rational(1, 2)
tt = np.linspace(0, 1, 201)
true = lb.SameDegreeCurve(np.eye(6)[:, :2], float(lam_val)).basis(tt)


def as_function(text, i_val):
    expr = parse(text).subs(
        {sp.Symbol("n"): n_val, sp.Symbol("i"): i_val, sp.Symbol("lam"): lam_val}
    )
    expr = expr.replace(
        bern,
        lambda a, nn, x: sp.binomial(nn, a) * x**a * (1 - x) ** (nn - a) if 0 <= a <= nn else 0,
    )
    return sp.lambdify(t, expr.subs(sp.Symbol("t"), t), "numpy")


fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for ax, (label, text) in zip(
    axes,
    (("printed", eq7["equations"][0]["rhs"]), ("corrected", eq7["erratum"]["equations"][0]["rhs"])),
    strict=True,
):
    for i_val in (1, 2, 3):
        values = np.broadcast_to(as_function(text, i_val)(tt), tt.shape)
        ax.plot(tt, values, label=f"{label} i={i_val}")
        ax.plot(tt, true[:, i_val], "k:", linewidth=1)
        if label == "corrected":
            assert np.allclose(values, true[:, i_val])
    ax.set_title(f"eq. (7) {label} (dotted: b_i^5 from eq. (1)), λ = 1/2")
    ax.legend(fontsize=7)
fig.savefig(FIGURES / "verify_000_eq7.png", dpi=80)
plt.show()

# %% [markdown]
# ## 002, the convexity example: y(x) printed with (1 − x²) instead of (1 − x)²

# %%
conv = next(r for r in records if r["id"] == "002.convexity.example")
omega = sp.Rational(1, 8)
x = sp.Symbol("x")
printed_y = sp.lambdify(x, parse(conv["equations"][1]["rhs"]).subs(sp.Symbol("omega"), omega))
curve = lb.BezierCurve([(0, 0), (0.25, 0.25), (0.5, float(omega)), (0.75, 0.25), (1, 0)])
xy = curve.evaluate(tt)
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(xy[:, 0], xy[:, 1], "k", label="the Bézier curve (derived)")
ax.plot(tt, printed_y(tt), "C3--", label="y(x) as printed")
ax.set_title("002 convexity example, ω = 1/8")
ax.legend(fontsize=8)
fig.savefig(FIGURES / "verify_002_convexity.png", dpi=80)
plt.show()
print("largest gap:", float(np.max(np.abs(printed_y(tt) - xy[:, 1]))))

# %% [markdown]
# ## 000, Proposition 5: the basis is not independent on all of (−2, 1]
#
# The verifier decides linear independence exactly for every λ of the stated range: the
# determinant of the Bernstein coefficients, as a polynomial in λ, has roots inside (−2, 1]
# from degree 5 on. Below, from the definition (eq. 1) alone: the smallest singular value of
# the sampled basis against λ, dropping to zero at each `singular_parameters` value; and
# b₂⁵ = b₃⁵ at λ = −3/2.

# %%
tt = np.linspace(0, 1, 201)
lams = np.linspace(-1.999, 1, 1200)
fig, ax = plt.subplots(figsize=(7, 4))
for n in (5, 6, 7, 9):
    sv = []
    for lam in lams:
        basis = lb.SameDegreeCurve(np.eye(n + 1)[:, :2], lam).basis(tt)
        s = np.linalg.svd(basis, compute_uv=False)
        sv.append(s[-1] / s[0])
    ax.semilogy(lams, sv, label=f"n = {n}")
    roots = [float(r) for r in lb.singular_parameters("same_degree", n)]
    print(f"degree {n}: singular at λ ≈ {[round(r, 6) for r in roots]}")
    for r in roots:
        ax.axvline(r, color="grey", linewidth=0.5)
ax.set_xlabel("λ")
ax.set_ylabel("smallest / largest singular value")
ax.set_title("000 Prop. 5: the same-degree basis loses rank inside (−2, 1]")
ax.legend(fontsize=8)
fig.savefig(FIGURES / "verify_000_prop5.png", dpi=80)
plt.close(fig)
b5 = lb.SameDegreeCurve(np.eye(6)[:, :2], -1.5).basis(tt)
print("max |b_2 - b_3| at λ = -3/2, degree 5:", float(np.max(np.abs(b5[:, 2] - b5[:, 3]))))
assert np.max(np.abs(b5[:, 2] - b5[:, 3])) < 1e-12
