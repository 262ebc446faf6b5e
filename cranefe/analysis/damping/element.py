"""Element level: equivalent viscous coefficients b = psi c / (2 pi w) (Heletiy 2016,
eq. 12-13), the absorption-weighted stiffness K_psi and the frequency of each element."""


import numpy as np
import scipy.sparse as sp




def equivalent_viscous(psi, c, omega, k1=1.0):
    """Equivalent viscous coefficient of elements in harmonic motion at `omega`.

    Heletiy (2016) eq. 12 (k1 = 1; the paper's "p" is pi) and eq. 13 (poly-harmonic
    motion, k1 from `polyharmonic_k1`): ``b = psi c / (2 pi omega k1)``. Broadcasts.
    """
    return np.asarray(psi) * np.asarray(c) / (2 * np.pi * np.asarray(omega) * k1)


def polyharmonic_k1(amplitudes, omegas):
    """k1 of Heletiy (2016) eq. 13, from equal dissipated power (docs/damping.md).

    For an element elongation ``x = sum_j a_j sin(w_j t)`` the absorbing element
    dissipates ``sum_j psi c a_j^2 w_j / (4 pi)`` per second, a dashpot b dissipates
    ``b sum_j a_j^2 w_j^2 / 2``; equal power gives ``b = psi c / (2 pi w_1 k1)`` with
    ``k1 = sum (a_j/a_1)^2 (w_j/w_1)^2 / sum (a_j/a_1)^2 (w_j/w_1)`` (the printed
    formula has numerator and denominator swapped). a_1 cancels, so a_1 = 0 is allowed.

    amplitudes : (..., nh) elongation amplitudes of the harmonics (e.g. per element)
    omegas : (nh,) their frequencies; omegas[0] is the reference w_1
    Returns k1 with the leading shape of `amplitudes`.
    """
    a2 = np.asarray(amplitudes, dtype=float) ** 2
    r = np.asarray(omegas, dtype=float) / omegas[0]
    num, den = (a2 * r**2).sum(axis=-1), (a2 * r).sum(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), 1.0)


def _weighted_stiffness(system, row_weight, beam_weight):
    """T^T (R^T diag(c w) R + sum w_e K_e) T: element stiffnesses weighted per element."""
    s = system.springs
    K = s.R.T @ sp.diags(s.c * row_weight) @ s.R
    if system.beams is not None:
        from ...assembly import Blocks, sum_blocks
        b = system.beams
        w = np.broadcast_to(beam_weight, (len(b.mat),))
        K = K + sum_blocks([Blocks(b.idx, b.mat * w[:, None, None])], K.shape[0])
    T = system.dofs.T
    K = (T.T @ K @ T).tocsr()
    return ((K + K.T) * 0.5).tocsr()


def psi_stiffness(system):
    """K_psi = sum_e psi_e K_e in generalised coordinates, (n, n) CSR: B(w) = K_psi/(2 pi w)."""
    return _weighted_stiffness(system, system.springs.psi,
                               system.beam_psi if system.beams is not None else 0.0)


def damping_matrix(system, omega, k1=1.0, k1_beams=1.0, omega_beams=None):
    """Viscous matrix B = (R T)^T diag(b) (R T) + beams, with b of eq. 12-13 at `omega`.

    omega : scalar or (n_rows,) per spring row; omega_beams : the beams' (default omega).
    k1 : scalar or (n_rows,) per spring row (poly-harmonic weighting, eq. 13).
    """
    s = system.springs
    beam_psi = system.beam_psi if system.beams is not None else 0.0
    omega_beams = omega if omega_beams is None else omega_beams
    return _weighted_stiffness(system, equivalent_viscous(s.psi, 1.0, omega, k1),
                               equivalent_viscous(beam_psi, 1.0, omega_beams, k1_beams))


def element_frequencies(system, V, omega):
    """The frequency each element mostly vibrates at, for eq. 12 in one viscous matrix.

    Per spring row and per beam element: the frequency of the mode (columns of V,
    mass-normalised, generalised coordinates; omega (m,)) that stores the largest share
    of its strain energy, c (r v_j)^2 / w_j^2, in that element. An element no mode
    strains gets the lowest frequency. Returns (rows (n_rows,), beams (n_beams,)).
    """
    T = system.dofs.T
    s = system.springs
    E = np.asarray((s.R @ T) @ V)                          # (ne, m) elongations
    rows = omega[np.argmax(s.c[:, None] * E**2 / omega**2, axis=1)]
    beams = np.zeros(0)
    if system.beams is not None and len(system.beams.mat):
        b = system.beams
        TV = np.asarray(T @ V)[b.idx]                      # (nb, 12, m)
        energy = np.einsum("eam,eab,ebm->em", TV, b.mat, TV)
        beams = omega[np.argmax(energy / omega**2, axis=1)]
    return rows, beams
