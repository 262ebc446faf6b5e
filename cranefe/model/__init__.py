"""Model files: reading, checking, and the frozen data they become."""

from .load import load
from .model import GROUND, Effects, Model

__all__ = ["load", "Model", "Effects", "GROUND"]
