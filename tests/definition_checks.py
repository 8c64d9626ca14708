"""The refused-definition check shared by the family-definition tests
(tests/test_acceptance_30.py, tests/test_acceptance_30b_definitions.py,
tests/test_trig_refusals.py): a definition table, changed in one key, is refused with a
DefinitionError whose message says each of the needles (the key and the term)."""

from __future__ import annotations

from collections.abc import Iterable

import pytest

from derive.emit.document import derive as derive_document
from derive.families.definition import DefinitionError, definition_from_table

# a two-parameter trigonometric quadratic on [0, pi/2] (a partition of unity for every lam,
# mu): the table the definition tests change one key of
TWO_PARAMETER_TRIG = {
    "name": "user_fam",
    "parameters": ["lam", "mu"],
    "range": {"lam": "[-1, 1]", "mu": "[-1, 1]"},
    "domain": "[0, pi/2]",
    "degrees": "2",
    "functions": [
        "(1 - sin(t))*(1 - lam*sin(t))",
        "1 - (1 - sin(t))*(1 - lam*sin(t)) - (1 - cos(t))*(1 - mu*cos(t))",
        "(1 - cos(t))*(1 - mu*cos(t))",
    ],
}


def assert_refused(table: dict, needles: Iterable[str], *, derive: bool = True) -> None:
    """`table` (read as the file fam.toml, then derived unless `derive` is False: some
    refusals belong to reading alone) raises DefinitionError naming every needle."""
    with pytest.raises(DefinitionError) as info:
        definition = definition_from_table(table, "fam.toml")
        if derive:
            derive_document(definition)
    for needle in needles:
        assert needle in str(info.value), str(info.value)
