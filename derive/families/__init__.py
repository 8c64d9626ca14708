"""The families layer: the definition files (*.toml), reading and validating a definition
(definition.py), the engine that turns one into a derivation (engine.py), the registry of
built-in families (registry.py) and each built-in family's paper-specific closed forms
(same_degree.py, bernstein_like.py). Imports only derive.algebra and derive.grammar.
"""
