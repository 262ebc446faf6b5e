"""Transient simulation of scenes: hoist start, lifting off the ground (docs/transient.md)."""
