"""Value and boundary tests of the EN 13001-2 factors (cranefe/analysis/loads/standard.py;
issue 20, mutation testing). Each number below is the formula of the clause its function
cites, evaluated by hand:

- phi1 = 1 +/- a for 0 <= a <= 0.1 (4.2.2.1), both ends of the range allowed;
- v_h of Table 3 = f v_h,max (HD1 A1: f = 1, HD4 A1: 0.5, HD5 C1: 0.5), or the creep speed;
- phi3 = 1 - (dm/m)(1 + beta3) (4.2.2.3), dm/m in [0, 1] both ends allowed;
- phi7 = 1.25 for xi <= 0.5, 1.25 + 0.7 (xi - 0.5) above (4.2.4.3);
- xi = work / (F_max * stroke): 1/2 for a linear spring, on a stroke not starting at 0;
- behaves_like: "within" is the lowest class whose line is AT or above every point.

Tolerances: 1e-15 relative or exact: a few floating operations on O(1) numbers.
"""

import numpy as np
import pytest

from cranefe.analysis.loads import standard as st
from cranefe.errors import ModelError


def test_phi1_range_ends():
    assert st.phi1(0.0) == (1.0, 1.0)
    assert st.phi1(0.1) == (1.1, 0.9)
    for a in (-1e-9, 0.1 + 1e-9):
        with pytest.raises(ModelError, match=r"phi1 = 1 \+/- a needs 0 <= a <= 0.1"):
            st.phi1(a)


def test_unknown_classes_name_the_known_ones():
    with pytest.raises(ModelError, match=r"^unknown hoisting class 'HC9': use one of "
                                         r"HC1, HC2, HC3, HC4$"):
        st.phi2("HC9", 1.0)
    with pytest.raises(ModelError, match=r"^unknown hoist drive class 'HD9': use one of "
                                         r"HD1, HD2, HD3, HD4, HD5$"):
        st.characteristic_speed("HD9", 1.0)
    with pytest.raises(ModelError, match=r"^unknown load combination 'D7': use A1, B1 "
                                         r"or C1$"):
        st.characteristic_speed("HD1", 1.0, combination="D7")
    with pytest.raises(ModelError, match=r"^test must be 'dynamic' or 'static' "
                                         r"\(got 'bogus'\)$"):
        st.phi6(1.2, test="bogus")


def test_characteristic_speed_of_table_3_by_hand():
    vmax, vcs = 2.0, 0.25
    assert st.characteristic_speed("HD1", vmax) == 2.0
    assert st.characteristic_speed("HD4", vmax, combination="A1") == 1.0
    assert st.characteristic_speed("HD4", vmax, combination="C1") == 2.0
    assert st.characteristic_speed("HD5", vmax, combination="B1") == 0.0
    assert st.characteristic_speed("HD5", vmax, combination="C1") == 1.0
    assert st.characteristic_speed("HD2", vmax, vcs) == 0.25
    assert st.characteristic_speed("HD1", vmax, combination="C1") is None
    assert st.characteristic_speed("HD3", vmax, combination="C1") is None
    # phi2 at those speeds: phi2,min + beta2 v_h (HC3: 1.15 + 0.51 v_h)
    assert st.phi2("HC3", 1.0) == pytest.approx(1.66, rel=1e-15)
    assert np.allclose(st.phi2("HC1", [0, 2]), [1.05, 1.05 + 0.34], rtol=1e-15)


def test_phi3_with_a_number_and_at_the_range_ends():
    assert st.phi3(0.2, 0.7) == pytest.approx(1 - 0.2 * 1.7, rel=1e-15)
    assert st.phi3(0.2, "slow") == pytest.approx(1 - 0.2 * 1.5, rel=1e-15)
    assert st.phi3(0.0) == 1.0
    assert st.phi3(1.0) == -1.0                     # the whole load released fast
    for x in (-1e-9, 1 + 1e-9):
        with pytest.raises(ModelError, match="must lie in"):
            st.phi3(x)


def test_phi5_guidance_rows():
    assert st.phi5_guidance(centrifugal=True, backlash=True) == (1.0, 1.0,
                                                                 "centrifugal forces")
    assert st.phi5_guidance(backlash=True)[:2] == (3.0, 3.0)
    assert st.phi5_guidance(sudden=True)[:2] == (1.5, 2.0)
    assert st.phi5_guidance()[:2] == (1.0, 1.5)


def test_phi7_both_branches_and_range_ends():
    assert st.phi7(0.0) == 1.25
    assert st.phi7(0.2) == 1.25
    assert st.phi7(0.5) == 1.25
    assert st.phi7(0.8) == pytest.approx(1.25 + 0.7 * 0.3, rel=1e-15)
    assert st.phi7(1.0) == pytest.approx(1.6, rel=1e-15)
    for x in (-1e-9, 1 + 1e-9):
        with pytest.raises(ModelError, match="buffer characteristic xi must lie in"):
            st.phi7(x)


def test_buffer_characteristic_on_a_stroke_not_from_zero():
    """A linear spring F = k (u - u0) from u0 = 0.1 to 0.6: work k 0.5^2 / 2, peak
    force k 0.5, xi = 1/2 (the trapezoidal rule is exact for a linear F); a constant
    force gives 1."""
    u = np.linspace(0.1, 0.6, 6)
    assert st.buffer_characteristic(u, 3.0 * (u - 0.1)) == pytest.approx(0.5, rel=1e-14)
    assert st.buffer_characteristic(u, np.full(6, 7.0)) == pytest.approx(1.0, rel=1e-14)


def test_behaves_like_a_class_exactly_on_its_line():
    """Points exactly on HC2's line are covered by HC2 (excess 0, 'at or above')."""
    v = np.array([0.2, 0.5, 1.0])
    p = st.phi2("HC2", v)
    r = st.behaves_like(v, p)
    assert r["within"] == "HC2" and r["closest"] == "HC2"
    assert r["excess"]["HC2"] == 0.0
    # HC1's line is 0.05 + 0.17 v below: excess 0.05 + 0.17 * 1.0, rms by hand
    assert r["excess"]["HC1"] == pytest.approx(0.05 + 0.17, rel=1e-13)
    d = 0.05 + 0.17 * v
    assert r["rms"]["HC1"] == pytest.approx(np.sqrt(np.mean(d**2)), rel=1e-13)
    d = -(0.05 + 0.17 * v)                                   # HC3 above by as much
    assert r["rms"]["HC3"] == pytest.approx(np.sqrt(np.mean(d**2)), rel=1e-13)
    assert r["excess"]["HC3"] == pytest.approx(-(0.05 + 0.17 * 0.2), rel=1e-13)
    assert st.behaves_like(v, p + 1.0)["within"] is None
