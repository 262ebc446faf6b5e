"""Design loads of EN 13001-2 (issue 17): the standard's dynamic factors as data and
formulas (`standard`) and the exact single-degree-of-freedom references that explain
them and test the simulations (`sdof`). docs/loads.md gives every clause and derivation.
"""
