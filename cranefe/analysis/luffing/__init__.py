"""Energy-optimal luffing of a level-luffing articulated jib (Loveikin, Palamarchuk,
Khodnevych 2013; docs/luffing.md).

kinematics  planar linkage from the model: loop closure by Newton, transfer functions by
            implicit differentiation
energy      reduced inertia J(alpha) (complete and the paper's eq. 3), potential, drive
optimum     eq. 16 exactly (quadrature), the paper's 3-point collocation (eq. 17-25, as
            printed and corrected), n-point collocation by Newton, solve_bvp
laws        standard laws and the practical rest-to-rest law
sway        the paper's eq. 9, linear and nonlinear sway with gravity, swing-free law
analysis    the scene's analysis -> LuffingResult; report, plots: presentation
"""
