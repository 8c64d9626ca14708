from __future__ import annotations

import sys
from functools import cache
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).parent))

from reference import FAMILIES, Family  # noqa: E402

import lambda_bezier as lb  # noqa: E402


@pytest.fixture(autouse=True)
def _mpmath_precision_restored():
    """Each test leaves mpmath's global precision as it found it: a test that sets mp.dps in
    its body would otherwise change the references of whichever test pytest-xdist runs next
    in the same worker (a comparison with mp.pi failed that way on CI only)."""
    import mpmath

    dps = mpmath.mp.dps
    yield
    mpmath.mp.dps = dps


# The default run is reproducible: the same examples on every run and every machine (CI
# included), so a red run is a bug to fix, not a draw. `pytest --hypothesis-profile=fuzz`
# draws new random examples on every run (run it when changing an algorithm).
settings.register_profile(
    "default",
    max_examples=60,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
    derandomize=True,
)
settings.register_profile(
    "fuzz",
    settings.get_profile("default"),
    derandomize=False,
)
settings.load_profile("default")

ROOT = Path(__file__).resolve().parents[1]


def family_file(name: str, suffix: str = ".toml") -> Path:
    """A family definition (or its `.derived.json`) by name: the test fixtures in
    tests/data/families, or the examples shipped with the package (c_bezier_cubic)."""
    fixture = Path(__file__).parent / "data" / "families" / f"{name}{suffix}"
    if fixture.exists():
        return fixture
    from lambda_bezier import examples

    return examples.path(f"{name}{suffix}")


def examples_per_profile(default: int, fuzz: int) -> int:
    """max_examples for a property whose examples cost seconds each (an mpmath reference):
    `default` in the reproducible run (CI's), `fuzz` under --hypothesis-profile=fuzz. Read when
    the test module is collected, after pytest has loaded the profile the command line names;
    every failure found is pinned with @example, so the default run keeps each of them."""
    return fuzz if settings.get_current_profile_name() == "fuzz" else default


def pytest_configure(config):
    """Under pytest-xdist, the controller fills numba's on-disk cache first, in one process per
    worker (tests/numba_warmup.py says why), so that the workers load the kernels instead of
    each compiling them. Not in the workers, not without numba or with it switched off; a
    failing warm-up only warns: the tests themselves run every path and report its errors."""
    import os
    import subprocess
    from importlib.util import find_spec

    workers = getattr(config.option, "numprocesses", None)
    if (
        hasattr(config, "workerinput")
        or not isinstance(workers, int)
        or workers < 2
        or find_spec("numba") is None
        or os.environ.get("LAMBDA_BEZIER_NO_NUMBA")
    ):
        return
    script = Path(__file__).with_name("numba_warmup.py")
    runs = [
        subprocess.Popen(
            [sys.executable, str(script), str(k), str(workers)],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        for k in range(workers)
    ]
    for run in runs:
        _, err = run.communicate()
        if run.returncode:
            message = f"the numba warm-up failed (the tests compile instead): {err[-2000:]}"
            config.issue_config_time_warning(pytest.PytestWarning(message), stacklevel=2)


@pytest.fixture(params=list(FAMILIES), ids=list(FAMILIES))
def family(request) -> Family:
    return FAMILIES[request.param]


def make_curve(fam: Family, points, lam):
    cls = lb.FAMILIES[fam.name]
    return cls(points) if fam.name == "bezier" else cls(points, lam)


@st.composite
def curves(draw, fam: Family, dims=(2, 3), max_degree: int | None = None):
    """A random curve of family `fam`: (curve, points, lam)."""
    hi = fam.degrees[-1] if max_degree is None else min(max_degree, fam.degrees[-1])
    n = draw(st.integers(fam.degrees[0], hi))
    d = draw(st.sampled_from(dims))
    coord = st.floats(-10, 10, allow_nan=False, allow_infinity=False)
    pts = draw(st.lists(st.lists(coord, min_size=d, max_size=d), min_size=n + 1, max_size=n + 1))
    lam = None if fam.name == "bezier" else draw(st.floats(*fam.lam_range))
    return make_curve(fam, pts, lam), pts, lam


@pytest.fixture(scope="module", params=["numpy", "numba"])
def intersect_engine(request):
    """Runs a module's tests on each path of the intersection subdivision: the numpy loop and
    the numba-compiled one (the `fast` extra, which the test extra installs). Module-scoped,
    so that hypothesis tests run under it too; the flag is restored afterwards."""
    from importlib.util import find_spec

    from lambda_bezier.hazmat import intersect_subdivide

    if request.param == "numba" and find_spec("numba") is None:
        pytest.skip("numba is not installed (pip install '.[fast]'): the compiled path")
    before = intersect_subdivide.USE_COMPILED
    intersect_subdivide.USE_COMPILED = request.param == "numba"
    yield request.param
    intersect_subdivide.USE_COMPILED = before


def on_both_subdivision_paths(call):
    """(numpy answer, numba answer) of `call()`, run once with intersect_subdivide's numpy loop
    and once with its compiled twin; the flag is restored afterwards."""
    from lambda_bezier.hazmat import intersect_subdivide

    saved = intersect_subdivide.USE_COMPILED
    try:
        intersect_subdivide.USE_COMPILED = False
        slow = call()
        intersect_subdivide.USE_COMPILED = True
        fast = call()
    finally:
        intersect_subdivide.USE_COMPILED = saved
    return slow, fast


def assert_same_isolated(slow, fast) -> None:
    """Two `intersect_subdivide.Isolated` agree: the same root pairs (parameters to rounding,
    since sums run in another order) and the same unresolved pieces, bit for bit."""
    import numpy as np

    assert np.array_equal(slow.root_pair, fast.root_pair)
    assert slow.root_s == pytest.approx(fast.root_s, abs=1e-12)
    assert slow.root_t == pytest.approx(fast.root_t, abs=1e-12)
    for name in ("left_pair", "left_s0", "left_t0", "left_width"):
        assert np.array_equal(getattr(slow, name), getattr(fast, name)), name


# derive's definition reader and document writer, loaded once (from the source checkout:
# the tests that use it skip without one): derive_beside(path) writes the derived document
# of the [family] table in `path` beside it, as `lambda-bezier derive --family` does
@pytest.fixture(scope="session")
def derive_beside():
    import importlib

    from lambda_bezier import _derive_runner

    derive = _derive_runner.load_derive(ROOT)
    definition = importlib.import_module(f"{derive.__name__}.families.definition")
    document = importlib.import_module(f"{derive.__name__}.emit.document")

    def write(path):
        defn = definition.read_definition(path)
        document.derived_path(path, defn.name).write_text(document.render(defn), encoding="utf-8")
        return defn

    return write


# the two mixed-family test families (tests/data/families/at_cubic.toml, at_pi_cubic.toml),
# loaded once per module: the certified geometry, intersection and export tests use both
@pytest.fixture(scope="module")
def at_family():
    return lb.load_family(ROOT / "tests" / "data" / "families" / "at_cubic.toml")


@pytest.fixture(scope="module")
def at_pi_family():
    return lb.load_family(ROOT / "tests" / "data" / "families" / "at_pi_cubic.toml")


@cache
def surface_families():
    """(TRIG, TWO, QB, HYP, MIXED): han_trig_cubic and two_shape_cubic (the examples),
    q_bezier, hyp_two_shape_cubic and at_pi_cubic (tests/data/families), the families of the
    surface tests; loaded once per process, since parametrize needs them at collection."""
    from lambda_bezier import examples

    data = ROOT / "tests" / "data" / "families"
    return (
        lb.load_family(examples.path("han_trig_cubic.toml")),
        lb.load_family(examples.path("two_shape_cubic.toml")),
        lb.load_family(data / "q_bezier.toml"),
        lb.load_family(data / "hyp_two_shape_cubic.toml"),
        lb.load_family(data / "at_pi_cubic.toml"),
    )


def occt_surface(path):
    """The first face's Geom surface of the STEP file `path`, read back by OCCT (OCP); the
    read must succeed. Skips where OCP is not installed."""
    pytest.importorskip("OCP")
    from OCP.BRep import BRep_Tool
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_ReturnStatus.IFSelect_RetDone
    reader.TransferRoots()
    face = TopoDS.Face(TopExp_Explorer(reader.OneShape(), TopAbs_FACE).Current())
    return BRep_Tool.Surface_s(face)


@pytest.fixture
def no_contact_cells(monkeypatch):
    """A switch for intersect_contact's cells: on, or off (pairs of pieces halved to the flat
    pieces, the subdivision as it was before round 19; the numpy loop reads it per call)."""
    from lambda_bezier.hazmat import intersect_contact

    def switch(on: bool) -> None:
        monkeypatch.setattr(intersect_contact, "CONTACT_LEVEL", 2 if on else 99)

    return switch


def careful_path(a, b) -> list:
    """intersect's careful path alone, in Python (no certificate, no compiled careful path),
    on two curves or two arrays of control points: the reference the fast paths are held to."""
    from lambda_bezier.hazmat import intersect as engine

    p, q = (x._prepared if hasattr(x, "_prepared") else lb.BezierCurve(x)._prepared for x in (a, b))
    engine._check_pair(p, q)
    results: list[list[engine.Intersection]] = [[]]
    engine._careful_pairs([(p, q)], [0], results)
    return results[0]
