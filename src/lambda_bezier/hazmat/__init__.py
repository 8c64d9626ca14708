"""lambda_bezier.hazmat: pure functions on coefficient and point arrays.

The rule: a module here imports numpy, the standard library and other hazmat modules
(and numba, optionally, in the *_compiled modules), nothing else from lambda_bezier
(import-linter checks it in CI, and tests/test_runtime_layers.py). A kernel that needs a
generated table takes it as an argument. Inputs are not validated here: the curve classes
above check them first, so calling these directly with bad arrays gives numpy's errors, not
ours (the name follows the `bezier` package's `hazmat`).

- `kernels`: de Casteljau, subdivision, blocked Horner, exact matrix products; the chunking
  of batch operations, and the switch to their compiled kernels;
- `kernels_compiled`: the first two levels of the arc-length rule and their decisions,
  compiled (numba, the `fast` extra; imported on use);
- `batch_compiled`: the batch operations compiled (numba, the `fast` extra; imported on use):
  the energy coefficients and optimal λ of many polygons in one pass, and evaluate_many's
  test of the curves' magnitudes;
- `batch_numpy`: the optimal λ of many polygons without numba (the compiled pass's interface
  in numpy, chunk by chunk on threads; the chunks it declines go to the careful path);
- `forms`: classical Bézier hodograph, elevation and blossoming at any degree;
- `arclength`: adaptive Gauss-Lobatto/Kronrod quadrature of the speed;
- `roots`: real roots in [0, 1] of polynomials about t = 1/2 (companion matrix, Newton);
- `extremes`: tight bounding boxes from those roots; closest points (the engine's switch);
- `closest_compiled`: closest points by a certified branch and bound on the Bernstein form of
  the squared distance, compiled with numba (the `fast` extra; imported on use);
- `closest_numpy`: the same branch and bound without numba (breadth first over a batch in
  numpy; depth first on Python floats for a few queries);
- `intersect`: curve/curve intersection; `intersect_self` a curve's self-intersections on
  the same engine; `intersect_shared_ends` the exact end points a pair shares (its
  certificate's corners);
- `intersect_locate`: point location on a curve and the end points of a pair located on each
  other (with the Newton starting points of unresolved pieces and the shared tolerances);
- `intersect_subdivide`: the candidate isolation `intersect` runs on (subdivision on arrays);
- `intersect_compiled`: the same loop compiled with numba (the `fast` extra; imported on use);
- `intersect_contact`: a tangency's pair of pieces confined to a small cell around its point
  of contact (a certificate), instead of halved to the flat pieces; one source, run as plain
  Python by the numpy loop and compiled by intersect_compiled for the kernels;
- `intersect_certify`: the certified fast path for transversal crossings away from the ends
  (numpy, or `certify_compiled`: the whole per-pair pipeline in one numba call);
- `pieces_compiled`: the compiled helpers on one or two pieces those kernels share (boxes,
  fat lines, cones, halving, compensated de Casteljau, local Newton);
- `settle_compiled`, `refine_compiled`: intersect's careful path compiled (end points,
  tangencies, merging) for the pairs the certificate declines (numba; imported on use);
- `coincide`: shared stretches of two rational curves under any parameterisation (exact by
  gcds over Q for exact rows, to rounding for floats);
- `intersect_exact`: exact, certified isolation of planar crossings (resultants, Sturm,
  Krawczyk in rational interval arithmetic); `intersect_self_exact` the same for a curve's
  crossings with itself (its divided differences (p(s) − p(t)) / (s − t));
  `intersect_self_polish` refines a float curve's self-crossing on those divided differences
  in floats (by blossoms of the hodograph), where a small loop puts it out of Newton's reach;
- `exact_flint`: its costly exact steps (resultants, gcds, real-root isolation) on
  python-flint (the `exact` extra; imported on use), `exact_poly` the fallback;
- `intersect_fold`: the self-intersections of a curve on a line that turns back along it
  (the end pairs of the stretches its monotone pieces share); `intersect_refold` the same
  for a curve off a line (P = Q(g), g not monotone), cut at its exact turning points;
- `intersect_kind`: the kind of a meeting where a curve stops (zero speed at an end, a
  cusp): from its first derivative that does not vanish there;
- `intersect_prepared`: a curve as the intersection solvers use it (floats, exact rows);
- `intersect_pairs`: the compiled kernels' entry for one pair (certificate, then the careful
  path compiled, in one call) or many pairs in one call; `intersect_pairs_compiled` its
  kernels (numba, the `fast` extra; imported on use);
- `reduce`: degree reduction, exact or least squares;
- `implicit`: implicitization (imports SymPy when called, never at import);
- `numbers`: the exact-number grammar of the command line and of export files;
- `rational_kernels`: rational Bézier curves on their homogeneous form (evaluation, derivatives
  by the quotient rule, subdivision, Möbius maps);
- `surface_kernels`: tensor-product evaluation, boxes and closest points of control nets;
- `surface_compiled`: grid evaluation and the batch optimum of (λ_u, λ_v), compiled with numba (the
  `fast` extra; imported on use);
- `exact_poly`: exact polynomials over the rationals (Sturm sequences, resultants);
- `box_bernstein`: exact Bernstein bounds of a polynomial in several variables over a box
  (branch and bound: signs, zeros, the certified minimum);
- `box_forms`: exact power to Bernstein conversion and evaluation in several variables;
- `box_convex`: the neighbourhood of a minimum for that branch and bound (a float polish of
  the start, and an exact quadratic floor over a small box about it).
- `box_batch`: the certified minimum of many polynomials over one box at once (local strong
  convexity and a Bernstein clearing of the rest, every polynomial's sub-boxes as rows of
  arrays): batches of surface nets with several parameters a direction.
- `atoms`: curves in a space of atoms 1, t^k, cos/sin, cosh/sinh (trigonometric, hyperbolic
  and mixed families): the atom grammar, exact differentiation, fast evaluation;
- `atom_pieces`: such a curve as a piecewise polynomial with a certified truncation bound
  (numpy), and `atom_pieces_compiled`, its evaluation compiled with numba (the `fast`
  extra; imported on use);
- `atom_bounds`: certified enclosures of such a curve and its derivatives on t-intervals
  (Taylor forms), and the branch and bound of its bounding box and closest point;
- `atom_surface_bounds`: the same for tensor-product surfaces of such bases (mixed families,
  no rational form, across another atom family or a polynomial one): certified bounding box
  and closest points, branch and bound over (u, v);
- `atom_intersect`: certified intersections of such a curve with another, with a polynomial
  or rational Bézier curve, and with itself (branch and bound on parameter pairs, Krawczyk);
- `atom_intersect_parts`: the curves that search sees (enclosures of atom curves and of
  polynomial and rational Bézier curves) and its interval arithmetic;
- `atom_deviation`: a certified bound of the distance between such a curve and a polynomial
  piece approximating it (export within a chosen tolerance);
- `surface_certify`: the fixed-cost certificate of the batch optimum of (λ_u, λ_v) (one
  elementwise source: numpy on arrays, or compiled by `surface_batch_compiled`, numba, the
  `fast` extra; imported on use);
- `surface_fixed_cost`: that certificate and its edge and corner one, run in numpy in the
  compiled kernel's order (the batch optima's numpy engine);
- `surface_weights`: the energy's weights for that kernel, in the basis where each
  direction's λ-part is sparse (exact change of basis);
- `surface_coefficients_ir`: the energy's coefficients of a large batch as vector code
  emitted from those weights (LLVM IR, compiled by llvmlite, numba's code generator; the
  `fast` extra, imported on use);
- `constants`: exact numbers in ℚ(π) and ℚ(e^W) (`ConstantFraction`), signs decided exactly.

The submodules are imported on use: ``from lambda_bezier.hazmat import kernels``.
"""

from __future__ import annotations

__all__ = [
    "arclength",
    "atom_bounds",
    "atom_deviation",
    "atom_intersect",
    "atom_intersect_parts",
    "atom_pieces",
    "atom_pieces_compiled",
    "atom_surface_bounds",
    "atoms",
    "batch_compiled",
    "batch_numpy",
    "box_batch",
    "box_bernstein",
    "box_convex",
    "box_forms",
    "certify_compiled",
    "closest_compiled",
    "closest_numpy",
    "coincide",
    "constants",
    "exact_flint",
    "exact_poly",
    "extremes",
    "forms",
    "implicit",
    "intersect",
    "intersect_certify",
    "intersect_compiled",
    "intersect_contact",
    "intersect_exact",
    "intersect_fold",
    "intersect_kind",
    "intersect_locate",
    "intersect_pairs",
    "intersect_pairs_compiled",
    "intersect_prepared",
    "intersect_refold",
    "intersect_self",
    "intersect_shared_ends",
    "intersect_self_exact",
    "intersect_self_polish",
    "intersect_subdivide",
    "kernels",
    "kernels_compiled",
    "pieces_compiled",
    "numbers",
    "rational_kernels",
    "reduce",
    "refine_compiled",
    "roots",
    "settle_compiled",
    "surface_batch_compiled",
    "surface_certify",
    "surface_coefficients_ir",
    "surface_compiled",
    "surface_fixed_cost",
    "surface_kernels",
    "surface_weights",
]
