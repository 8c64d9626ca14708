"""generated/<family>.py: a built-in family's module, printed from its derivation's
FamilyModule (derive/families/engine.py): the tables, the paper's general forms and the end
forms in closed form in n."""

from __future__ import annotations

from ..families.engine import FamilyModule, GeneralForm
from . import printing as _emit


def _general_form(form: GeneralForm) -> str:
    body = "return (\n" + "".join(f"    {_emit.expression(v)},\n" for v in form.values) + ")"
    return _emit.function(form.name, list(form.args), form.doc, body)


def render(data: FamilyModule) -> str:
    return _emit.family_module(
        script=data.script,
        doc=data.doc,
        definition=data.definition,
        **data.tables,
        general_forms=[_general_form(form) for form in data.general_forms],
        endpoint=data.endpoint,
    )
