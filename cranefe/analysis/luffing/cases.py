"""Exact-answer linkages for the luffing kinematics (shared by tests and studies).

`paper_linkage` is the linkage for which Loveikin et al. (2013) eq. 12-15 hold exactly:
a boom of length L hinged at the origin O, a jib of length l whose tip D is held on the
horizontal line z = H by a slider (eq. 12-13 assume the tip moves on that line), and a
rack between a stand point A (length a from O, inclined Theta above the horizontal,
behind O) and a boom point C (length b from O, opening angle mu from the boom line).
"""

import numpy as np


def paper_linkage(L=24.0, l=14.0, H=12.0, a=6.0, theta_deg=20.0, b=7.0, mu_deg=10.0,
                  alpha_deg=60.0, R=0.25, i=140.0, rotor=2.5):
    """YAML text of the exact linkage in its position alpha_deg, and the closed forms.

    Returns (text, exact) with exact functions of alpha (rad):
    ``jib``: (dphi3/dalpha, d2phi3/dalpha2) of eq. 12-13 (phi3 measured clockwise: the
    jib's counter-clockwise angle has the opposite sign); ``motor``: (dphi5/dalpha,
    d2phi5/dalpha2) of eq. 14-15, phi5 = i (s - s0) / R."""
    al = np.radians(alpha_deg)
    th, mu = np.radians(theta_deg), np.radians(mu_deg)
    B = L * np.array([np.cos(al), np.sin(al)])
    dz = B[1] - H
    if not 0 < dz < l:
        raise ValueError("the jib cannot reach the line z = H from this boom position")
    D = B + np.array([np.sqrt(l**2 - dz**2), -dz])
    A = a * np.array([-np.cos(th), np.sin(th)])
    C = b * np.array([np.cos(al + mu), np.sin(al + mu)])

    def xz(p):
        return f"[{float(p[0])!r}, 0, {float(p[1])!r}]"

    text = f"""cranefe: 1
name: Loveikin et al. (2013) eq. 12-15 linkage
plane: xz
nodes:
  O: [0, 0, 0]
  B: {xz(B)}
  D: {xz(D)}
  A: {xz(A)}
  C: {xz(C)}
ground: [O, A]
bodies:
  boom: {{mass: 12000, com: {xz(B / 2)}, inertia: {float(12000 * L**2 / 12)!r}, nodes: [O, B, C]}}
  jib: {{mass: 6000, com: {xz((B + D) / 2)}, inertia: {float(6000 * l**2 / 12)!r}, nodes: [B, D]}}
  block: {{mass: 0, nodes: [D]}}
joints:
  - {{type: hinge, bodies: [ground, boom], at: O}}
  - {{type: hinge, bodies: [boom, jib], at: B}}
  - {{type: hinge, bodies: [jib, block], at: D}}
  - {{type: slider, bodies: [ground, block], at: D, axis: [1, 0, 0]}}
linear_drives:
  rack: {{nodes: [A, C], pinion_radius: {float(R)!r}, gear_ratio: {float(i)!r},
         rotor_inertia: {float(rotor)!r}}}
"""

    def jib(alpha):
        # Loveikin et al. (2013) eq. 12 and eq. 13
        q = l**2 - (L * np.sin(alpha) - H) ** 2
        d1 = L * np.cos(alpha) / np.sqrt(q)
        d2 = L * ((L**2 + H**2 - l**2) * np.sin(alpha)
                  - H * L * (1 + np.sin(alpha) ** 2)) / q**1.5
        return d1, d2

    def motor(alpha):
        # Loveikin et al. (2013) eq. 14 and eq. 15
        c = th + mu + alpha
        s2 = a**2 + b**2 + 2 * a * b * np.cos(c)
        d1 = -i * a * b * np.sin(c) / (R * np.sqrt(s2))
        d2 = -(a * b * i / R) * ((a**2 + b**2) * np.cos(c)
                                 + a * b * (1 + np.cos(c) ** 2)) / s2**1.5
        return d1, d2

    return text, {"jib": jib, "motor": motor, "H": H, "alpha_ref": al}
