"""The formulas layer: what is derived for any family, generic over its derivation (end
forms via the families layer, energies, joins, basis properties and singular parameters).
Imports only the layers below (families, algebra, grammar); derive/emit prints the results.
"""
