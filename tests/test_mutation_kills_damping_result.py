"""Kill tests for cranefe/analysis/damping/result.py (issue 20, mutation testing;
tools/mutation.py damping_result): the damping result's properties and its `--json`
document on a result written out by hand (three modes: a rigid one, a weakly coupled
one and one whose coupling and predicted error sit exactly on the limits), every value
derived here, not by the module:

- weak coupling: every coupling coefficient strictly below KAPPA = 0.1 (Hasselman);
  trusted: that and |predicted error| strictly below ERROR_TOL = 0.02;
- viscous log decrement 2 pi zeta / sqrt(1 - zeta^2), infinite when overdamped;
- complex-stiffness (hysteretic) log decrement 2 pi tan(atan(2 zeta) / 2), written here
  by the half-angle identity tan(atan(x) / 2) = x / (1 + sqrt(1 + x^2));
- relative errors (estimate - exact) / exact, 0 where both vanish, unknown (None in the
  document) where the exact value is not computed.
Tolerance: 1e-14 relative (a few roundings of the same closed forms).
"""

import math

import numpy as np
import pytest

from cranefe.analysis.damping.result import DampingResult

TWO_PI = 2 * math.pi
W = np.array([0.0, TWO_PI * 1.5, TWO_PI * 4.0])
ZETA = np.array([0.0, 0.05, 0.2])
EXACT = np.array([np.nan, 0.04, 1.25])          # mode 3 overdamped in the exact solution
HYST = np.array([0.0, 0.06, 0.25])


def _result(**kw):
    args = dict(
        model_name="hand", effects={"damping": "modal"}, method="both", omega=W,
        rigid=np.array([True, False, False]), zeta=ZETA,
        damped_omega=W * np.sqrt(1 - ZETA ** 2),
        log_decrement=np.array([np.nan, 0.3, 1.2]),
        coupling=np.array([0.0, 0.05, 0.1]), coupled_with=np.array([-1, 2, 1]),
        coupling_matrix=np.zeros((3, 3)), predicted_error=np.array([0.0, 0.01, -0.02]),
        D=np.zeros((3, 3)), dominant_element=("", "rope a", "rope b"),
        dominant_share=np.array([0.0, 0.75, 0.5]),
        exact_zeta=EXACT, exact_damped_omega=np.array([np.nan, 9.0, 0.0]),
        hysteretic_zeta=HYST, hysteretic_damped_omega=np.array([0.0, 9.5, 25.0]),
        dofs=3, quasi_cyclic=("drum hoist",), timings={"total": 0.1234567},
        warnings=["w1"])
    args.update(kw)
    return DampingResult(**args)


def _hyst_dec(z):
    x = 2 * z
    return TWO_PI * x / (1 + math.sqrt(1 + x * x))


def test_properties_by_hand():
    r = _result()
    assert np.allclose(r.frequency_hz, [0.0, 1.5, 4.0], rtol=1e-14, atol=0)
    # 0.1 is not below KAPPA = 0.1; -0.02 is not below ERROR_TOL in magnitude
    assert r.criterion_holds.tolist() == [True, True, False]
    assert r.trusted.tolist() == [True, True, False]
    assert _result(predicted_error=np.array([0.0, 0.02, 0.0])).trusted.tolist() == \
        [True, False, False]
    dv = r.exact_log_decrement
    assert dv[2] == np.inf              # overdamped (mode 1: not computed, never read)
    assert dv[1] == pytest.approx(TWO_PI * 0.04 / math.sqrt(1 - 0.04 ** 2), rel=1e-14)
    dh = r.hysteretic_log_decrement
    for k in range(3):
        assert dh[k] == pytest.approx(_hyst_dec(HYST[k]), rel=1e-14, abs=0)
    ev = r.error_viscous
    assert np.isnan(ev[0])               # exact unknown for the rigid mode
    assert ev[1] == pytest.approx((0.05 - 0.04) / 0.04, rel=1e-14)
    assert ev[2] == pytest.approx((0.2 - 1.25) / 1.25, rel=1e-14)
    eh = r.error_hysteretic
    assert eh[0] == 0.0                  # both zero
    assert eh[1] == pytest.approx(-1 / 6, rel=1e-14)
    assert eh[2] == pytest.approx(-0.2, rel=1e-14)
    modal = _result(method="modal", exact_zeta=None, exact_damped_omega=None,
                    hysteretic_zeta=None, hysteretic_damped_omega=None)
    for name in ("exact_log_decrement", "hysteretic_log_decrement", "error_viscous",
                 "error_hysteretic"):
        assert getattr(modal, name) is None


def test_the_document_by_hand():
    d = _result().to_dict()
    assert d["model"] == "hand" and d["effects"] == {"damping": "modal"}
    assert d["dofs"] == 3 and d["quasi_cyclic"] == ["drum hoist"]
    assert d["method"] == "both"
    assert d["criterion"] == {"coupling_limit": 0.1, "error_limit": 0.02, "holds": False}
    assert d["timings_s"] == {"total": 0.123457} and d["warnings"] == ["w1"]
    m0, m1, m2 = d["modes"]
    _same(m0, {"index": 1, "frequency_hz": 0.0, "omega_rad_s": 0.0, "period_s": None,
                  "rigid": True, "damping_ratio": 0.0, "damped_frequency_hz": 0.0,
                  "log_decrement": None, "coupling": 0.0, "coupled_with": None,
                  "weak_coupling": True, "predicted_error": 0.0,
                  "absorbed_most_by": None})    # exact NaN: no exact/hysteretic objects
    w1 = TWO_PI * 1.5
    expect1 = {"index": 2, "frequency_hz": 1.5, "omega_rad_s": w1, "period_s": 1 / 1.5,
               "rigid": False, "damping_ratio": 0.05,
               "damped_frequency_hz": 1.5 * math.sqrt(1 - 0.05 ** 2),
               "log_decrement": 0.3, "coupling": 0.05, "coupled_with": 3,
               "weak_coupling": True, "predicted_error": 0.01,
               "absorbed_most_by": {"element": "rope a", "share": 0.75},
               "exact": {"damping_ratio": 0.04, "damped_frequency_hz": 9.0 / TWO_PI,
                         "log_decrement": TWO_PI * 0.04 / math.sqrt(1 - 0.04 ** 2),
                         "relative_error": 0.25},
               "hysteretic": {"damping_ratio": 0.06, "damped_frequency_hz": 9.5 / TWO_PI,
                              "log_decrement": _hyst_dec(0.06),
                              "relative_error": -1 / 6}}
    _same(m1, expect1)
    expect2 = {"index": 3, "frequency_hz": 4.0, "omega_rad_s": TWO_PI * 4.0,
               "period_s": 0.25, "rigid": False, "damping_ratio": 0.2,
               "damped_frequency_hz": 4.0 * math.sqrt(1 - 0.04), "log_decrement": 1.2,
               "coupling": 0.1, "coupled_with": 2, "weak_coupling": False,
               "predicted_error": -0.02,
               "absorbed_most_by": {"element": "rope b", "share": 0.5},
               "exact": {"damping_ratio": 1.25, "damped_frequency_hz": 0.0,
                         "log_decrement": None, "relative_error": -0.84},
               "hysteretic": {"damping_ratio": 0.25, "damped_frequency_hz": 25 / TWO_PI,
                              "log_decrement": _hyst_dec(0.25),
                              "relative_error": -0.2}}
    _same(m2, expect2)
    # a rigid mode with exact values reports no log decrements (no period)
    r = _result(exact_zeta=np.array([0.0, 0.04, 1.25]),
                exact_damped_omega=np.array([0.0, 9.0, 0.0]))
    m0 = r.to_dict()["modes"][0]
    assert m0["exact"] == {"damping_ratio": 0.0, "damped_frequency_hz": 0.0,
                           "log_decrement": None, "relative_error": 0.0}
    assert m0["hysteretic"]["log_decrement"] is None
    # without exact solutions: no exact/hysteretic objects at all
    modal = _result(method="modal", exact_zeta=None, exact_damped_omega=None,
                    hysteretic_zeta=None, hysteretic_damped_omega=None).to_dict()
    assert all("exact" not in m and "hysteretic" not in m for m in modal["modes"])
    assert modal["criterion"]["holds"] is False
    ok = _result(coupling=np.array([0.0, 0.05, 0.09]),
                 predicted_error=np.array([0.0, 0.01, 0.019])).to_dict()
    assert ok["criterion"]["holds"] is True


def _same(got, expect):
    """Equal keys in the same order, values equal (floats to 1e-14 relative)."""
    assert list(got) == list(expect)
    for k, v in expect.items():
        if isinstance(v, dict):
            _same(got[k], v)
        elif isinstance(v, float):
            assert got[k] == pytest.approx(v, rel=1e-14, abs=1e-300), k
        else:
            assert got[k] == v and type(got[k]) is type(v), k


def test_errors_of_small_damping_ratios_are_relative():
    """The zero floor is 1e-9 of the largest exact ratio: a steel structure's ratios of
    1e-3 and 5e-7 still get their relative errors (0.1 and 0.2), not 'zero'."""
    r = _result(zeta=np.array([0.0, 1.1e-3, 6e-7]),
                exact_zeta=np.array([np.nan, 1e-3, 5e-7]))
    assert r.error_viscous[1:] == pytest.approx([0.1, 0.2], rel=1e-12)
