"""The formula grammar: text to expression (derive/grammar/formula.py), with no evaluator,
and the interval text of parameter ranges (derive/grammar/interval.py).

A bottom layer of derive: it imports nothing else of derive.
"""

from .formula import (
    BUILTINS as BUILTINS,
    FUNCTIONS as FUNCTIONS,
    FUNCTION_NAMES as FUNCTION_NAMES,
    MAX_ARGS as MAX_ARGS,
    MAX_CONSTANT_BITS as MAX_CONSTANT_BITS,
    MAX_DEPTH as MAX_DEPTH,
    MAX_DIGITS as MAX_DIGITS,
    MAX_EXPONENT as MAX_EXPONENT,
    MAX_FACTORIAL as MAX_FACTORIAL,
    MAX_TEXT as MAX_TEXT,
    ParseError as ParseError,
    SYMBOLS as SYMBOLS,
    SYMBOL_NAMES as SYMBOL_NAMES,
    Token as Token,
    paper_binomial_expr as paper_binomial_expr,
    parse_formula as parse_formula,
    tokenize as tokenize,
)
from .interval import Interval as Interval
