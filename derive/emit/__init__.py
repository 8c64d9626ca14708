"""The emit layer: printing exact objects as Python source (printing.py), one module per
group of generated/ (bernstein, families, energy, joins, properties; generated.py puts them
together), writing and checking the tree atomically, and the derived family document
(document.py). The top layer of derive beside verify; it never imports verify.
"""
