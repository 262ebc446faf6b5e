"""Model files: reading, checking, and the frozen data they become."""

from .load import build, load, read_raw
from .model import GROUND, Effects, Model

__all__ = ["load", "read_raw", "build", "Model", "Effects", "GROUND"]
