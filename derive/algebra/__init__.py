"""The exact core: symbols, polynomials in t and the parameters, FLINT/SymPy conversions,
and the classical Bernstein basis as pure algebra (derive/algebra/bernstein.py).

The lowest layer of derive: it imports nothing else of derive.
"""

from .bernstein import (
    X as X,
)
from .bernstein import (
    bernstein_basis as bernstein_basis,
)
from .bernstein import (
    bernstein_matrices as bernstein_matrices,
)
from .bernstein import (
    bernstein_poly as bernstein_poly,
)
from .bernstein import (
    bernstein_power_matrix as bernstein_power_matrix,
)
from .bernstein import (
    check_endpoint_weights as check_endpoint_weights,
)
from .bernstein import (
    closed_end_forms as closed_end_forms,
)
from .bernstein import (
    elevation_matrix as elevation_matrix,
)
from .bernstein import (
    endpoint_weight as endpoint_weight,
)
from .bernstein import (
    endpoint_weights as endpoint_weights,
)
from .bernstein import (
    expansion_tables as expansion_tables,
)
from .bernstein import (
    hodograph_matrix as hodograph_matrix,
)
from .bernstein import (
    original_basis as original_basis,
)
from .bernstein import (
    original_power_matrix as original_power_matrix,
)
from .bernstein import (
    power_to_bernstein_matrix as power_to_bernstein_matrix,
)
from .core import (
    CENTRE as CENTRE,
)
from .core import (
    LAMBDA_SAMPLES as LAMBDA_SAMPLES,
)
from .core import (
    Matrix as Matrix,
)
from .core import (
    bernstein_terms as bernstein_terms,
)
from .core import (
    centred_matrices as centred_matrices,
)
from .core import (
    centred_row as centred_row,
)
from .core import (
    check_endpoint_closed_forms as check_endpoint_closed_forms,
)
from .core import (
    endpoint_values as endpoint_values,
)
from .core import (
    exact_function as exact_function,
)
from .core import (
    from_flint as from_flint,
)
from .core import (
    i as i,
)
from .core import (
    j as j,
)
from .core import (
    k as k,
)
from .core import (
    lam as lam,
)
from .core import (
    lambda_degree as lambda_degree,
)
from .core import (
    linear_in_lambda as linear_in_lambda,
)
from .core import (
    m as m,
)
from .core import (
    matmul as matmul,
)
from .core import (
    n as n,
)
from .core import (
    poly as poly,
)
from .core import (
    power_matrices as power_matrices,
)
from .core import (
    t as t,
)
from .core import (
    to_flint as to_flint,
)
from .core import (
    to_fraction as to_fraction,
)
from .core import (
    transpose as transpose,
)
