"""Kill test for cranefe/analysis/loads/sdof.py (tools/mutation.py sdof; docs/testing.md,
"Mutation testing"): `beta3_equivalent` was reached by no test."""

import math

from cranefe.analysis.loads.sdof import beta3_equivalent


def test_beta3_equivalent_is_the_ramp_amplitude():
    """A linear release over t_r of a system at w' swings with A = |sin(w' t_r/2)| /
    (w' t_r/2): w' = 2 rad/s, t_r = pi/2 s gives w' t_r/2 = pi/2 and A = 2/pi; a
    sudden release (t_r = 0) gives 1 (tests/test_loads_standard.py derives A)."""
    assert math.isclose(beta3_equivalent(2.0, math.pi / 2), 2.0 / math.pi, rel_tol=1e-14)
    assert beta3_equivalent(2.0, 0.0) == 1.0
