"""`lambda-bezier verify`: every published record compared with the derivation.

Records come from derive/published/*.toml (the printed formulas, misprints kept). Each record
is checked by the checker registered for its `claim` (derive/verify/) and gets a
verdict:

* ``match``     — the printed form agrees with our derivation (symbolically where derive has a
                  general-n closed form, and always for every degree of the family's range);
* ``mismatch``  — it does not; the diff names the equation / case / entry / coefficient and the
                  first degree and index where it fails, with printed and derived values;
* ``caveat``    — the printed result agrees with the derivation, but not with the range the
                  paper states for it (a value outside the stated parameter range, an optimum
                  that does not exist on it, a formula whose denominator vanishes inside it);
                  the reason is printed and ERRATA.md lists it;
* ``pending``   — the derivation it needs does not exist yet (the reason says which).

Expectations and errata live next to each record in the TOML files:

* ``expect = "match" | "mismatch" | "caveat" | "pending"`` — the verdict a reviewer confirmed. A run
  fails when any verdict differs from its expectation, so a new discrepancy, a misprint that
  now matches, or a derivation that has landed is never silent. Setting ``expect`` is a
  review step: run the verifier, read every mismatch, confirm it independently.
* ``[record.erratum]`` — required for ``expect = "mismatch"``: ``explanation`` (one line),
  ``origin`` ("paper" or "transcription") and corrected values for the record's fields
  (``equations``, ``cases``, ``matrix``, ...). The corrected record is checked too and must
  match: an erratum is itself verified. ERRATA.md (repository root) is generated from them.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import re
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path

from ..families.registry import REFERENCE, builtin_families
from ..grammar.messages import clip
from . import index as record_index
from .index import records_by_id as records_by_id  # the run's records, for cross-references
from .records import RecordsError, load_paths, renamed_record
from .registry import FAMILIES, Outcome, run_checker

__all__ = ["RecordsError", "load_records", "verify"]

PUBLISHED = Path(__file__).resolve().parents[1] / "published"
VERDICTS = ("match", "mismatch", "caveat", "pending")
ERRATUM_META = ("explanation", "origin")
ERRATA_FILE = "ERRATA.md"
ERRATA_COMMAND = "lambda-bezier verify --errata"


# --------------------------------------------------------------------------- records


def load_records(paths: Iterable[Path] | None = None) -> list[dict]:
    """The records of `paths` (default: every built-in file), validated (records.py)."""
    if paths is None:
        paths = sorted(PUBLISHED.glob("*.toml"))
    return load_paths(paths)


record_index.set_loader(lambda: load_records())


def corrected(record: dict) -> dict:
    """The record with its erratum's corrected fields in place of the printed ones."""
    fix = record.get("erratum")
    if not fix:
        raise ValueError(f"{record['id']} has no erratum")
    out = {k: v for k, v in record.items() if k != "erratum"}
    for key, value in fix.items():
        if key not in ERRATUM_META:
            out[key] = value
    return out


# --------------------------------------------------------------------------- results


@dataclass
class Result:
    record: dict
    outcome: Outcome
    erratum: Outcome | None = None
    error: str | None = None
    seconds: float = 0.0

    @property
    def id(self) -> str:
        return self.record["id"]

    @property
    def source(self) -> str:
        return self.record["source"]

    @property
    def verdict(self) -> str:
        return "error" if self.error else self.outcome.verdict

    @property
    def expect(self) -> str | None:
        return self.record.get("expect")

    def problems(self) -> list[str]:
        """Why this record fails the run (empty when it agrees with its expectation)."""
        out = []
        exp, got = self.expect, self.verdict
        if self.error:
            out.append(f"checker error: {self.error}")
        elif exp not in VERDICTS:
            out.append(f"no valid expectation recorded (expect = {exp!r}); verdict is {got}")
        elif got != exp:
            if exp == "match" and got == "caveat":
                out.append("NEW CAVEAT: expected match, the claim holds only as qualified above")
            elif exp == "match":
                out.append("NEW DISCREPANCY: expected match, the derivation disagrees")
            elif exp == "mismatch" and got == "match":
                out.append("a recorded misprint now MATCHES: review and drop the erratum")
            elif exp == "pending":
                out.append(
                    f"the derivation now exists and the verdict is {got}: review it and record "
                    "the expectation"
                )
            else:
                out.append(f"expected {exp}, got {got}")
        fix = self.record.get("erratum")
        if exp == "mismatch" and not fix:
            out.append("a confirmed mismatch needs an erratum")
        if fix and exp == "match":
            out.append("an erratum on a record expected to match")
        if fix and not fix.get("explanation"):
            out.append("erratum without an explanation")
        if self.erratum is not None and self.erratum.verdict not in ("match", "pending"):
            out.append("the erratum's corrected form does NOT match the derivation")
        if self.erratum is not None and self.erratum.verdict == "pending" and got != "pending":
            out.append("the erratum could not be verified")
        return out


@dataclass
class Report:
    results: list[Result]
    seconds: float
    extra_problems: list[str] = field(default_factory=list)

    def counts(self) -> dict[str, int]:
        out = dict.fromkeys((*VERDICTS, "error"), 0)
        for r in self.results:
            out[r.verdict] += 1
        return out

    def problems(self) -> list[tuple[str, str]]:
        out = [(r.id, p) for r in self.results for p in r.problems()]
        return out + [("", p) for p in self.extra_problems]

    def failed(self, strict: bool = False) -> bool:
        if self.problems():
            return True
        return strict and any(r.verdict != "match" for r in self.results)


def _in_own_names(outcome: Outcome | None, parameter: str) -> Outcome | None:
    """The checker's texts in the family's own parameter name (the checkers say lam or λ)."""
    if outcome is None or parameter == "lam":
        return outcome
    return Outcome(
        outcome.verdict,
        [own_names(d, parameter) for d in outcome.diffs],
        [own_names(c, parameter) for c in outcome.checked],
    )


def own_names(text: str, parameter: str) -> str:
    if parameter == "lam":
        return text
    return re.sub(r"\blam\b|λ", parameter, text)


def check_record(record: dict) -> Result:
    start = time.perf_counter()
    fam = FAMILIES.get(record.get("family", ""))
    parameter = getattr(fam, "parameter", "lam")
    inner = renamed_record(record, parameter)  # the checkers read the parameter as lam
    try:
        outcome = _in_own_names(run_checker(inner), parameter)
        fixed = (
            _in_own_names(run_checker(corrected(inner)), parameter)
            if record.get("erratum")
            else None
        )
        res = Result(record, outcome, fixed)
    except Exception as exc:  # noqa: BLE001 - a checker failure is reported, never a verdict
        error = own_names(f"{type(exc).__name__}: {exc}", parameter)
        res = Result(record, Outcome("mismatch"), error=error)
    res.seconds = time.perf_counter() - start
    return res


def default_jobs() -> int:
    """Worker processes: one per CPU where fork is available, else 1."""
    if "fork" not in multiprocessing.get_all_start_methods():
        return 1
    return max(1, min(os.cpu_count() or 1, 8))


# The order in which records are laid out for the workers: the first worker takes records from
# the front and the second from the back, so the first family's records go to one worker and
# the last family's to the other, each deriving (and caching) only its own family's bases and
# closed forms; they meet in the reference (Bézier) records, which need neither.
def _family_order() -> dict[str, int]:
    """The built-in families in order with the reference basis in the middle (for two
    families: the first, the reference, the second)."""
    names = [b.name for b in builtin_families()]
    half = (len(names) + 1) // 2
    return {name: pos for pos, name in enumerate([*names[:half], REFERENCE, *names[half:]])}


FAMILY_ORDER = _family_order()


def _parallel(records: list[dict], jobs: int, done: Callable[[int, Result], None]) -> None:
    """check_record for every record in `jobs` forked workers; done(index, result) in the
    parent as each result arrives."""
    ctx = multiprocessing.get_context("fork")
    order = sorted(range(len(records)), key=lambda i: FAMILY_ORDER.get(records[i]["family"], 1))
    lock = ctx.Lock()
    front = ctx.Value("i", 0, lock=False)
    back = ctx.Value("i", len(order), lock=False)
    results = ctx.SimpleQueue()

    def work(from_front: bool) -> None:
        while True:
            with lock:
                if front.value >= back.value:
                    break
                if from_front:
                    pos = front.value
                    front.value += 1
                else:
                    back.value -= 1
                    pos = back.value
            results.put((order[pos], None))  # started: named if this worker dies
            results.put((order[pos], check_record(records[order[pos]])))

    workers = [ctx.Process(target=work, args=(w % 2 == 0,), daemon=True) for w in range(jobs)]
    for w in workers:
        w.start()
    started: set[int] = set()
    try:
        finished = 0
        while finished < len(records):
            while results.empty():
                if not any(w.is_alive() for w in workers) and results.empty():
                    codes = [w.exitcode for w in workers]
                    busy = ", ".join(records[i]["id"] for i in sorted(started)) or "none"
                    raise RuntimeError(
                        f"verify workers exited early (exit codes {codes}) while checking: {busy}"
                    )
                time.sleep(0.005)
            idx, res = results.get()
            if res is None:
                started.add(idx)
                continue
            started.discard(idx)
            finished += 1
            done(idx, res)
    finally:
        for w in workers:
            if w.is_alive():
                w.terminate()
            w.join()


def verify(
    records: list[dict] | None = None,
    progress: Callable[[int, int, str], None] | None = None,
    index: list[dict] | None = None,
    jobs: int | None = None,
) -> Report:
    """Check `records` (default: all published ones); `index` is the full set they may refer
    to (default: `records`); `jobs` worker processes (default: default_jobs()); progress(done,
    total, id of the last record checked) as results arrive."""
    records = load_records() if records is None else records
    record_index.replace(records if index is None else index)
    start = time.perf_counter()
    jobs = default_jobs() if jobs is None else jobs
    total = len(records)
    if progress:
        progress(0, total, "")
    if jobs > 1 and total > 4:
        slots: list[Result | None] = [None] * total
        count = 0

        def done(idx: int, res: Result) -> None:
            nonlocal count
            slots[idx] = res
            count += 1
            if progress and count < total:
                progress(count, total, res.id)

        _parallel(records, jobs, done)
        results = [r for r in slots if r is not None]
    else:
        results = []
        for rec in records:
            results.append(check_record(rec))
            if progress and len(results) < total:
                progress(len(results), total, rec["id"])
    if progress:
        progress(total, total, "")
    return Report(results, time.perf_counter() - start)


# --------------------------------------------------------------------------- rendering


def _summary(report: Report) -> str:
    c = report.counts()
    parts = [f"{c[v]} {v}" for v in (*VERDICTS, "error") if c[v] or v != "error"]
    return f"{len(report.results)} records: " + ", ".join(parts) + f" ({report.seconds:.1f} s)"


def render_text(report: Report) -> str:
    width = max((len(r.id) for r in report.results), default=10)
    swidth = max((len(r.source) for r in report.results), default=10)
    lines = []
    for r in report.results:
        lines.append(f"{r.id:<{width}}  {r.source:<{swidth}}  {r.verdict}")
        if r.verdict != "match":
            detail = [r.error] if r.error else r.outcome.diffs
            # A difference of a large claim can be pages long: the text report quotes a
            # readable stretch of each (the JSON report keeps them whole).
            lines += [f"    {clip(d)}" for d in detail]
        if r.erratum is not None:
            lines.append(
                f"    erratum ({r.record['erratum'].get('origin', '?')}): corrected form "
                f"{r.erratum.verdict}"
                + (": " + "; ".join(r.erratum.diffs) if r.erratum.verdict != "match" else "")
            )
    lines.append(_summary(report))
    for rid, p in report.problems():
        lines.append(clip(f"FAIL {rid}: {p}" if rid else f"FAIL: {p}"))
    return "\n".join(lines) + "\n"


def render_json(report: Report) -> str:
    data = {
        "summary": {
            "records": len(report.results),
            **report.counts(),
            "seconds": round(report.seconds, 3),
            "ok": not report.problems(),
        },
        "records": [
            {
                "id": r.id,
                "source": r.source,
                "location": r.record.get("location"),
                "claim": r.record["claim"],
                "verdict": r.verdict,
                "expect": r.expect,
                "diff": [r.error] if r.error else r.outcome.diffs,
                "checked": r.outcome.checked,
                "erratum": None
                if r.erratum is None
                else {
                    "verdict": r.erratum.verdict,
                    "diff": r.erratum.diffs,
                    "explanation": r.record["erratum"].get("explanation"),
                    "origin": r.record["erratum"].get("origin"),
                },
                "problems": r.problems(),
            }
            for r in report.results
        ],
        # each names its record, as the text report's FAIL lines do
        "problems": [f"{rid}: {p}" if rid else p for rid, p in report.problems()],
    }
    return json.dumps(data, indent=2, ensure_ascii=False) + "\n"


def _md(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def render_markdown(report: Report) -> str:
    lines = ["| id | source | verdict | diff |", "|---|---|---|---|"]
    for r in report.results:
        diff = (
            ""
            if r.verdict == "match"
            else "<br>".join(_md(d) for d in ([r.error] if r.error else r.outcome.diffs))
        )
        lines.append(f"| `{r.id}` | {r.source} | {r.verdict} | {diff} |")
    lines += ["", _summary(report)]
    for rid, p in report.problems():
        lines.append(f"- **FAIL** `{rid}`: {p}" if rid else f"- **FAIL**: {p}")
    return "\n".join(lines) + "\n"


RENDERERS = {"text": render_text, "json": render_json, "markdown": render_markdown}


# --------------------------------------------------------------------------- errata


def _printed_fields(record: dict) -> list[tuple[str, object, object]]:
    fix = record["erratum"]
    return [(k, record.get(k), v) for k, v in fix.items() if k not in ERRATUM_META]


def _show_field(value) -> list[str]:
    if isinstance(value, list) and value and isinstance(value[0], dict):
        out = []
        for item in value:
            if "lhs" in item:
                extra = ""
                if item.get("where"):
                    extra += "  for " + ", ".join(f"{k} = {v}" for k, v in item["where"].items())
                if item.get("given"):
                    extra += "  with " + ", ".join(f"{k} = {v}" for k, v in item["given"].items())
                out.append(f"{item['lhs']} = {item['rhs']}{extra}")
            elif "index" in item:
                out.append(f"index {item['index']}: {item['value']}")
            else:
                out.append(json.dumps(item, ensure_ascii=False))
        return out
    if isinstance(value, list) and value and isinstance(value[0], list):
        return [json.dumps(row) for row in value]
    return [json.dumps(value, ensure_ascii=False) if not isinstance(value, str) else value]


def render_errata(report: Report) -> str:
    """ERRATA.md: every confirmed misprint with the printed and the corrected form."""
    fixed = [r for r in report.results if r.record.get("erratum")]
    lines = [
        "# Errata",
        "",
        f"<!-- Generated by `{ERRATA_COMMAND}` from derive/published/*.toml. DO NOT EDIT. -->",
        "",
        "Misprints and false statements found by `lambda-bezier verify` in the source",
        "documents (or in their text transcriptions), each confirmed by an independent",
        "computation. For every entry the printed form disagrees with the derivation, and the",
        "corrected form is re-checked by the verifier on every run and matches it.",
        "",
        "Binomial convention: C_n^k = 0 unless 0 ≤ k ≤ n (the papers' convention).",
        "",
    ]
    by_source: dict[str, list[Result]] = {}
    for r in fixed:
        by_source.setdefault(r.source, []).append(r)
    for source, results in by_source.items():
        lines += [f"## {source}", ""]
        for r in results:
            fix = r.record["erratum"]
            lines += [
                f"### `{r.id}` — {r.record.get('location', '')}",
                "",
                f"{fix.get('explanation', '')} ({fix.get('origin', 'paper')} misprint)",
                "",
            ]
            for key, printed, corr in _printed_fields(r.record):
                p_lines, c_lines = _show_field(printed), _show_field(corr)
                lines += [f"`{key}`:", "", "```"]
                if len(p_lines) == len(c_lines):
                    for a, b in zip(p_lines, c_lines, strict=True):
                        if a != b:
                            lines += [f"printed:   {a}", f"corrected: {b}"]
                else:
                    lines += [f"printed:   {a}" for a in p_lines]
                    lines += [f"corrected: {b}" for b in c_lines]
                lines += ["```", ""]
            lines.append("Verifier's diff of the printed form:")
            lines.append("")
            lines += [f"- {_md(d)}" for d in r.outcome.diffs]
            lines.append("")
    if not fixed:
        lines += ["No misprints recorded.", ""]
    lines += _render_caveats(report)
    return "\n".join(lines).rstrip("\n") + "\n"


def _render_caveats(report: Report) -> list[str]:
    """Claims that are right as computed but do not hold on the whole range the paper states
    (a value outside it, an optimum that does not exist there, a formula undefined there)."""
    caveats = [r for r in report.results if r.verdict == "caveat"]
    if not caveats:
        return []
    lines = [
        "## Caveats",
        "",
        "Printed results that agree with the derivation but not with the range the paper",
        "states for them; the verifier re-derives each reason on every run.",
        "",
    ]
    for r in caveats:
        lines += [f"### `{r.id}` — {r.source}, {r.record.get('location', '')}", ""]
        if r.record.get("note"):
            lines += [f"Printed: {r.record['note']}", ""]
        lines += [f"- {_md(d)}" for d in r.outcome.diffs]
        lines.append("")
    return lines
