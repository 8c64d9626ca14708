"""The energy coefficients of a batch of nets as straight-line vector code: LLVM IR emitted from
one energy's weights (hazmat.surface_weights' BatchWeights) and compiled by llvmlite (numba's
own code generator, so present wherever the `fast` extra is).

Why not a numba loop: the generic kernel (surface_batch_compiled._coefficients_chunk) reads
the weights as data, so its accumulators and Gram products live in memory and every update
is a load and a store (measured: those bound it, about 1.0-1.4 ms for 10,000 bicubic nets).
Here the weights are constants of the code: per block of LANES nets the net's coordinates,
the Gram products and the nine accumulators are vector values, each weight a multiply-add
on registers, and the only memory traffic is reading the nets once and writing the nine
coefficients (measured 0.28 ms for the same nets, with the transposition and the check of the
coordinates in it). The same code through numba (generated Python source) runs as fast, but
numba's front end takes 5-8 s to compile it against about 0.4 s for llvmlite on the IR.

The arithmetic is the generic kernel's, in another order: the change of basis, then
g_p = Σ_c z_ic z_jc and e_t = Σ_p W[p, t] g_p in pair order; multiplies and adds carry LLVM's
`contract` flag only (they may fuse into one rounding where the CPU has FMA; no reassociation,
no other fast-math assumption), as the generic kernel's fastmath={"contract"}. So the results
agree with it to rounding (a few units in the last place of the largest term), not bit for bit.

The function emitted, for nets flat (k, R) (R = points x d coordinates, row-major) and
nblocks >= 1 blocks of LANES nets from the first:
    i64 coefficients(double* flat, i64 nblocks, double* out, i64 ostride, double limit)
writes net k's coefficient t (of λ_u^a λ_v^b, t = 3a + b) at out[t * ostride + k] and returns
1 if every coordinate read is finite and at most `limit` in magnitude, else 0.
"""

from __future__ import annotations

import ctypes
import struct
import threading
from collections.abc import Callable
from typing import Any

import numpy as np

LANES = 8  # nets per vector: LLVM splits an 8-wide vector where the CPU's are narrower
# the emitted code and its build time grow with the weights: past this many multiply-adds a
# net the generic kernel runs instead. Measured (thread time, llvmlite 0.50 / LLVM 22): the
# bicubic thin plate of the 000 family, 992 operations, builds in 0.2-0.4 s; degrees (4, 4),
# 2,698 operations, 0.8 s; (5, 5), 5,876, 1.8 s; (6, 6), 11,222, 4.4 s
MAX_OPERATIONS = 3000

_Kernel = Callable[[int, int, int, int, float], int]
_LOCK = threading.Lock()
# the weights' bytes -> (engine, function), or None where this llvmlite could not build it
_KERNELS: dict[bytes, tuple[Any, _Kernel] | None] = {}
_BY_IDENTITY: dict[int, tuple[Any, int, int, _Kernel | None]] = {}  # the last lookups


def operations(w: Any, dim: int) -> int:
    """Multiply-adds a net of the emitted code: change of basis, Gram products, weights."""
    return int(w.mix_target.size + w.pair_i.size * dim + np.count_nonzero(w.weights))


def _hex(c: float) -> str:
    """A double in LLVM's exact hexadecimal notation (decimal would have to be exact)."""
    bits = struct.unpack("<Q", struct.pack("<d", float(c)))[0]
    return f"0x{bits:016X}"


def emit(w: Any, dim: int, rows: int) -> str:
    """The IR of the coefficients function for BatchWeights `w` and nets of `rows` values
    (points x dim)."""
    vt = f"<{LANES} x double>"
    mask_t = f"<{LANES} x i1>"
    all_true = "<" + ", ".join("i1 true" for _ in range(LANES)) + ">"

    def splat(c: float) -> str:
        return "<" + ", ".join(f"double {_hex(c)}" for _ in range(LANES)) + ">"

    out: list[str] = []
    e = out.append
    e(
        "define i64 @coefficients(ptr noalias nocapture readonly %flat, i64 %nblocks, "
        "ptr noalias nocapture writeonly %out, i64 %ostride, double %limit) {"
    )
    e("entry:")
    e(f"  %lim0 = insertelement {vt} poison, double %limit, i64 0")
    e(f"  %lim = shufflevector {vt} %lim0, {vt} poison, <{LANES} x i32> zeroinitializer")
    e("  br label %block")
    e("block:")
    e("  %b = phi i64 [0, %entry], [%bnext, %block]")
    e(f"  %okin = phi {mask_t} [{all_true}, %entry], [%okout, %block]")
    e(f"  %base = mul i64 %b, {LANES}")
    for lane in range(LANES):  # the first value of each net of the block
        e(f"  %net{lane} = add i64 %base, {lane}")
        e(f"  %row{lane} = mul i64 %net{lane}, {rows}")
    name: dict[int, str] = {}
    tiled = rows - rows % LANES if LANES == 8 else 0
    for q in range(0, tiled, LANES):  # whole tiles: LANES loads, then a shuffle transposition
        vs = []
        for lane in range(LANES):
            e(f"  %to{q}_{lane} = add i64 %row{lane}, {q}")
            e(f"  %tp{q}_{lane} = getelementptr double, ptr %flat, i64 %to{q}_{lane}")
            e(f"  %tl{q}_{lane} = load {vt}, ptr %tp{q}_{lane}, align 8")
            vs.append(f"%tl{q}_{lane}")
        for stage, (width, tag) in enumerate(((1, "a"), (2, "b"), (4, "c"))):
            nxt = []
            for k in range(0, LANES, 2):
                lo, hi = _interleave(width)
                x, y = vs[k], vs[k + 1]
                e(f"  %t{tag}{q}_{k} = shufflevector {vt} {x}, {vt} {y}, <{LANES} x i32> {lo}")
                e(f"  %t{tag}{q}_{k + 1} = shufflevector {vt} {x}, {vt} {y}, <{LANES} x i32> {hi}")
                nxt += [f"%t{tag}{q}_{k}", f"%t{tag}{q}_{k + 1}"]
            vs = _regroup(nxt, stage)
        for j in range(LANES):
            name[q + j] = vs[j]
    ok = "%okin"
    for r in range(rows):
        if r < tiled:
            prev = name[r]
            e(f"  %abs{r} = call {vt} @llvm.fabs.v{LANES}f64({vt} {prev})")
            e(f"  %le{r} = fcmp ole {vt} %abs{r}, %lim")  # false for NaN too
            e(f"  %ok{r} = and {mask_t} {ok}, %le{r}")
            ok = f"%ok{r}"
            continue
        prev = "poison"
        for lane in range(LANES):
            e(f"  %o{r}_{lane} = add i64 %row{lane}, {r}")
            e(f"  %p{r}_{lane} = getelementptr double, ptr %flat, i64 %o{r}_{lane}")
            e(f"  %s{r}_{lane} = load double, ptr %p{r}_{lane}, align 8")
            e(f"  %v{r}_{lane} = insertelement {vt} {prev}, double %s{r}_{lane}, i64 {lane}")
            prev = f"%v{r}_{lane}"
        name[r] = prev
        e(f"  %abs{r} = call {vt} @llvm.fabs.v{LANES}f64({vt} {prev})")
        e(f"  %le{r} = fcmp ole {vt} %abs{r}, %lim")  # false for NaN too
        e(f"  %ok{r} = and {mask_t} {ok}, %le{r}")
        ok = f"%ok{r}"
    mix = zip(w.mix_target.tolist(), w.mix_source.tolist(), w.mix_weight.tolist(), strict=True)
    for i, (t, s, c) in enumerate(mix):  # the change of basis, in order
        e(f"  %mm{i} = fmul contract {vt} {splat(c)}, {name[s]}")
        e(f"  %m{i} = fadd contract {vt} {name[t]}, %mm{i}")
        name[t] = f"%m{i}"
    acc: dict[int, str] = {}
    n = 0
    for p, (i, j) in enumerate(zip(w.pair_i.tolist(), w.pair_j.tolist(), strict=True)):
        a, b = i * dim, j * dim
        g = f"%gm{p}_0"
        e(f"  {g} = fmul contract {vt} {name[a]}, {name[b]}")
        for c in range(1, dim):
            e(f"  %gm{p}_{c} = fmul contract {vt} {name[a + c]}, {name[b + c]}")
            e(f"  %ga{p}_{c} = fadd contract {vt} {g}, %gm{p}_{c}")
            g = f"%ga{p}_{c}"
        for t in np.flatnonzero(w.weights[p]).tolist():
            e(f"  %wm{n} = fmul contract {vt} {splat(w.weights[p, t])}, {g}")
            if t in acc:
                e(f"  %wa{n} = fadd contract {vt} {acc[t]}, %wm{n}")
                acc[t] = f"%wa{n}"
            else:
                acc[t] = f"%wm{n}"
            n += 1
    for t in range(9):
        e(f"  %ro{t} = mul i64 %ostride, {t}")
        e(f"  %rb{t} = add i64 %ro{t}, %base")
        e(f"  %q{t} = getelementptr double, ptr %out, i64 %rb{t}")
        e(f"  store {vt} {acc.get(t, 'zeroinitializer')}, ptr %q{t}, align 8")
    e(f"  %okout = and {mask_t} {ok}, {all_true}")
    e("  %bnext = add i64 %b, 1")
    e("  %done = icmp sge i64 %bnext, %nblocks")
    e("  br i1 %done, label %exit, label %block")
    e("exit:")
    e(f"  %all = call i1 @llvm.vector.reduce.and.v{LANES}i1({mask_t} %okout)")
    e("  %res = zext i1 %all to i64")
    e("  ret i64 %res")
    e("}")
    e(f"declare {vt} @llvm.fabs.v{LANES}f64({vt})")
    e(f"declare i1 @llvm.vector.reduce.and.v{LANES}i1({mask_t})")
    return "\n".join(out) + "\n"


def _interleave(width: int) -> tuple[str, str]:
    """The two shuffles of one transposition stage: blocks of `width` elements taken in turn
    from x (indices 0..7) and y (8..15)."""
    lo, hi = [], []
    for k in range(0, LANES, 2 * width):
        lo += list(range(k, k + width)) + list(range(LANES + k, LANES + k + width))
        hi += list(range(k + width, k + 2 * width)) + list(
            range(LANES + k + width, LANES + k + 2 * width)
        )
    return (
        "<" + ", ".join(f"i32 {i}" for i in lo) + ">",
        "<" + ", ".join(f"i32 {i}" for i in hi) + ">",
    )


# after each stage, the order in which its outputs pair up for the next (the last: rows 0..7)
_REGROUP = ((0, 2, 1, 3, 4, 6, 5, 7), (0, 4, 2, 6, 1, 5, 3, 7), (0, 2, 4, 6, 1, 3, 5, 7))


def _regroup(vs: list[str], stage: int) -> list[str]:
    return [vs[i] for i in _REGROUP[stage]]


def _key(w: Any, dim: int, rows: int) -> bytes:
    parts = [np.array([dim, rows, LANES], dtype=np.int64).tobytes()]
    parts += [np.ascontiguousarray(a).tobytes() for a in w]
    return b"".join(parts)


def kernel(w: Any, dim: int, rows: int) -> _Kernel | None:
    """The compiled coefficients function for `w` (built on the first call for these
    weights, about 0.3 s for the bicubic thin plate; kept for the process), or None where
    llvmlite cannot build it: the IR needs LLVM's opaque pointers and llvmlite's new pass
    manager (llvmlite 0.44, numba 0.61, onwards); the caller then runs the generic kernel,
    whose answers these equal to rounding. tests/test_surface_coefficients_ir.py asserts a
    function is built in the test environment."""
    known = _BY_IDENTITY.get(id(w))
    if known is not None and known[0] is w and known[1:3] == (dim, rows):
        return known[3]  # (the callers' weights are cached objects: no bytes to hash)
    key = _key(w, dim, rows)
    if key not in _KERNELS:
        with _LOCK:
            if key not in _KERNELS:
                try:
                    _KERNELS[key] = _compile(emit(w, dim, rows))
                except (ImportError, AttributeError, RuntimeError):  # an older llvmlite
                    _KERNELS[key] = None
    found = _KERNELS[key]
    fn = None if found is None else found[1]
    if len(_BY_IDENTITY) >= 64:  # bounded: a caller building new weights each call
        _BY_IDENTITY.clear()
    _BY_IDENTITY[id(w)] = (w, dim, rows, fn)  # w kept alive: its id is not reused meanwhile
    return fn


def _compile(ir: str) -> tuple[Any, _Kernel]:
    import llvmlite.binding as llvm  # numba's dependency: here only with the `fast` extra

    llvm.initialize_native_target()
    llvm.initialize_native_asmprinter()
    machine = llvm.Target.from_default_triple().create_target_machine(
        cpu=llvm.get_host_cpu_name(), features=llvm.get_host_cpu_features().flatten(), opt=3
    )
    module = llvm.parse_assembly(ir)
    module.verify()
    builder = llvm.create_pass_builder(machine, llvm.create_pipeline_tuning_options(speed_level=3))
    builder.getModulePassManager().run(module, builder)
    engine = llvm.create_mcjit_compiler(module, machine)
    engine.finalize_object()
    signature = ctypes.CFUNCTYPE(
        ctypes.c_int64, ctypes.c_void_p, ctypes.c_int64, ctypes.c_void_p, ctypes.c_int64,
        ctypes.c_double,
    )  # fmt: skip
    fn: _Kernel = signature(engine.get_function_address("coefficients"))
    return engine, fn  # the engine owns the code: kept alive with the function


def coefficients(
    fn: _Kernel, flat: np.ndarray, start: int, stop: int, out: np.ndarray, limit: float
) -> bool:
    """out[t, k - start] = coefficient t of net k for start <= k < stop, by `fn` (`kernel`):
    whole blocks of LANES nets in place, the rest through a zero-padded copy. flat is
    C-contiguous float64 (k, R), out (9, >= stop - start) C-contiguous; whether every
    coordinate was finite and <= limit."""
    rows = flat.shape[1]
    n = stop - start
    whole = n // LANES
    valid = True
    if whole:
        address = flat.ctypes.data + start * rows * 8
        valid = bool(fn(address, whole, out.ctypes.data, out.shape[1], limit))
    rest = n - whole * LANES
    if rest:
        pad = np.zeros((LANES, rows))
        pad[:rest] = flat[start + whole * LANES : stop]
        tail = np.empty((9, LANES))
        valid &= bool(fn(pad.ctypes.data, 1, tail.ctypes.data, LANES, limit))
        out[:, whole * LANES : n] = tail[:, :rest]
    return valid
