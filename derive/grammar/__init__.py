"""The formula grammar: text to expression (derive/grammar/formula.py), with no evaluator,
and the interval text of parameter ranges (derive/grammar/interval.py).

A bottom layer of derive: it imports nothing else of derive.
"""

from .formula import (
    BUILTINS as BUILTINS,
)
from .formula import (
    ELEMENTARY as ELEMENTARY,
)
from .formula import (
    FUNCTION_NAMES as FUNCTION_NAMES,
)
from .formula import (
    FUNCTIONS as FUNCTIONS,
)
from .formula import (
    MAX_ARGS as MAX_ARGS,
)
from .formula import (
    MAX_CONSTANT_BITS as MAX_CONSTANT_BITS,
)
from .formula import (
    MAX_DEPTH as MAX_DEPTH,
)
from .formula import (
    MAX_DIGITS as MAX_DIGITS,
)
from .formula import (
    MAX_EXPONENT as MAX_EXPONENT,
)
from .formula import (
    MAX_FACTORIAL as MAX_FACTORIAL,
)
from .formula import (
    MAX_FREQUENCY as MAX_FREQUENCY,
)
from .formula import (
    MAX_OPERATOR_NESTING as MAX_OPERATOR_NESTING,
)
from .formula import (
    MAX_TEXT as MAX_TEXT,
)
from .formula import (
    OPERATORS as OPERATORS,
)
from .formula import (
    SYMBOL_NAMES as SYMBOL_NAMES,
)
from .formula import (
    SYMBOLS as SYMBOLS,
)
from .formula import (
    ParseError as ParseError,
)
from .formula import (
    Token as Token,
)
from .formula import (
    paper_binomial_expr as paper_binomial_expr,
)
from .formula import (
    parse_formula as parse_formula,
)
from .formula import (
    tokenize as tokenize,
)
from .interval import Interval as Interval
