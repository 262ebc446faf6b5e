"""What each result field is called in an archive (format 2), its units and meaning.

`FIELDS[class name][field] = (dataset name, units, description)`; units None for text,
flags and counts-free entries (strings, booleans, dicts whose entries carry units by
their key, see `key_units`). `DERIVED[class name]` are datasets computed from the fields
for readers of the file (frequency in Hz, period): written, not read back. The table in
docs/archive.md lists the same names and units; tests/test_archive_h5py.py checks that
doc and file agree.

Units are UDUNITS-style strings: "1" is dimensionless, "mixed" marks generalised
coordinates whose units differ by coordinate (m for translations, rad for rotations and
drums; see the group's `labels`).
"""

_COMMON = {
    "model_name": ("model_name", None, "name of the model"),
    "scene": ("scene", None, "name of the scene ('' for a model file)"),
    "effects": ("effects", None, "effects the analysis included (rope_mass, sway, ...)"),
    "timings": ("timings", "s", "wall time of each stage"),
    "warnings": ("warnings", None, "warnings of the analysis"),
    "status": ("status", None, "0: ok, else failed"),
    "message": ("message", None, "'ok' or why the analysis failed"),
    "quasi_cyclic": ("quasi_cyclic", None, "quasi-cyclic (condensed) coordinates"),
}

FIELDS = {
    "ModalResult": dict(_COMMON, **{
        "labels": ("labels", None, "generalised coordinates (n,)"),
        "omega": ("omega_rad_s", "rad/s", "natural circular frequency of each mode (mode,)"),
        "shapes": ("generalised_shape", "mixed",
                   "mass-normalised mode shapes in the generalised coordinates "
                   "(coordinate, mode): shape^T M shape = I"),
        "node_shapes": ("mode_shape", "kg^-1/2",
                        "node translations x, y, z of each mass-normalised mode "
                        "(mode, node, 3); nodes as in node_names"),
        "rigid": ("rigid", None, "zero-frequency (quasi-cyclic) motion (mode,)"),
        "massless": ("massless", None, "massless coordinates condensed statically"),
        "solver": ("solver", None, "eigensolver used (dense | sparse)"),
        "drive_reduction": ("drive_reduction", None,
                            "with drive: reduced, coupled vs reduced frequencies"),
        "graded": ("graded", None, "how a graded problem was solved, else ''"),
    }),
    "DampingResult": dict(_COMMON, **{
        "method": ("method", None, "modal | exact | both | auto"),
        "omega": ("omega_rad_s", "rad/s", "undamped circular frequency (mode,)"),
        "rigid": ("rigid", None, "zero-frequency (quasi-cyclic) motion (mode,)"),
        "zeta": ("damping_ratio", "1", "decoupled (Hasselman) damping ratio (mode,)"),
        "damped_omega": ("damped_omega_rad_s", "rad/s",
                         "decoupled damped circular frequency (mode,)"),
        "log_decrement": ("log_decrement", "1", "logarithmic decrement (mode,)"),
        "coupling": ("coupling", "1", "largest coupling coefficient eps_ij (mode,)"),
        "coupled_with": ("coupled_with", None,
                         "0-based index of that partner mode, -1 if none (mode,)"),
        "coupling_matrix": ("coupling_matrix", "1", "coupling coefficients (mode, mode)"),
        "predicted_error": ("predicted_error", "1",
                            "estimated relative error of damping_ratio (mode,)"),
        "D": ("modal_damping_matrix", "1/s", "V^T B V, V mass-normalised (mode, mode)"),
        "dominant_element": ("dominant_element", None,
                             "element absorbing most energy in each mode (mode,)"),
        "dominant_share": ("dominant_share", "1", "its share of the absorption (mode,)"),
        "exact_zeta": ("exact_damping_ratio", "1",
                       "damping ratio of the exact viscous eigenproblem (mode,)"),
        "exact_damped_omega": ("exact_damped_omega_rad_s", "rad/s",
                               "exact viscous damped circular frequency (mode,)"),
        "hysteretic_zeta": ("hysteretic_damping_ratio", "1",
                            "damping ratio with complex stiffness (mode,)"),
        "hysteretic_damped_omega": ("hysteretic_damped_omega_rad_s", "rad/s",
                                    "damped circular frequency with complex stiffness "
                                    "(mode,)"),
        "dofs": ("dofs", None, "number of generalised coordinates"),
    }),
    "TransientResult": dict(_COMMON, **{
        "method": ("method", None, "direct | modal"),
        "initial": ("initial", None, "static | grounded"),
        "dofs": ("dofs", None, "number of generalised coordinates"),
        "labels": ("labels", None, "generalised coordinates (n,)"),
        "duration": ("duration", "s", "simulated time"),
        "time_step": ("time_step", "s", "integration time step"),
        "steps": ("steps", None, "number of steps"),
        "modes": ("modes", None, "elastic modes retained (modal), else 0"),
        "highest_frequency_hz": ("highest_frequency_hz", "Hz",
                                 "highest frequency the step resolves"),
        "times": ("t_s", "s", "output times (time,)"),
        "q": ("q", "mixed", "displacements from the reference state (time, coordinate)"),
        "v": ("v", "mixed/s", "velocities (time, coordinate)"),
        "rope_names": ("rope_names", None, "ropes (rope,)"),
        "rope_force": ("rope_force", "N", "largest force along each rope (time, rope)"),
        "rope_force_static": ("rope_force_static", "N", "force with the load at rest (rope,)"),
        "rope_force_max": ("rope_force_max", "N", "peak force over the run (rope,)"),
        "rope_force_max_time": ("rope_force_max_time", "s", "time of the peak (rope,)"),
        "dynamic_factor": ("dynamic_factor", "1", "peak / static force, phi2 (rope,)"),
        "drum_names": ("drum_names", None, "drums with a rotation coordinate (drum,)"),
        "drum_drive": ("drum_drive", None, "speed | torque | motor | held (drum,)"),
        "drum_angle": ("drum_angle", "rad", "drum rotation (time, drum)"),
        "drum_speed": ("drum_speed", "rad/s", "drum speed (time, drum)"),
        "drum_torque": ("drum_torque", "N m", "torque at the drum (time, drum)"),
        "load_names": ("load_names", None, "nodes with a point mass (load,)"),
        "load_displacement": ("load_displacement", "m",
                              "displacement x, y, z of each point mass (time, load, 3)"),
        "ground_names": ("ground_names", None, "loads resting on the ground at the start"),
        "ground_force": ("ground_force", "N", "the ground's push on each (time, ground)"),
        "lift_off_times": ("lift_off_times", "s", "lift-off of each, nan if never"),
        "lift_off_time": ("lift_off_time", "s", "first lift-off, nan if none"),
        "energy_error": ("energy_error", "1", "energy balance error / largest term"),
        "energy": ("energy", "J", "energy balance terms"),
        "events": ("events", None, "events ('0.18 s: lift-off HOOK', ...)"),
    }),
    "LuffingResult": {
        "status": _COMMON["status"], "message": _COMMON["message"],
        "model_name": _COMMON["model_name"], "scene": _COMMON["scene"],
        "alpha0": ("alpha0", "rad", "boom angle at the start"),
        "alphak": ("alphak", "rad", "boom angle at the end"),
        "t_k": ("t_k", "s", "duration of the luffing motion"),
        "reach0": ("reach0", "m", "reach (x of the jib tip) at the start"),
        "reachk": ("reachk", "m", "reach at the end"),
        "load_mass": ("load_mass", "kg", "mass of the load"),
        "rope_length": ("rope_length", "m", "length of the load's pendulum"),
        "inertia": ("inertia", None, "the inertia the optimum minimises: complete | paper"),
        "jib_tip_deviation": ("jib_tip_deviation", "m",
                              "max - min height of the jib tip over the range"),
        "imbalance_moment": ("imbalance_moment", "N m", "largest |dV/dalpha| of the links"),
        "imbalance_motor_torque": ("imbalance_motor_torque", "N m", "the same at the motor"),
        "optimum": ("optimum", None, "figures of the optimum (units by key suffix)"),
        "table": ("table", None, "figures of each law (units by key suffix)"),
        "law_names": ("law_names", None, "motion laws compared (law,)"),
        "t": ("t_s", "s", "time (time,)"),
        "alpha": ("alpha", "rad", "boom angle (law, time)"),
        "speed": ("speed", "rad/s", "boom angular speed (law, time)"),
        "motor_torque": ("motor_torque", "N m", "motor torque (law, time)"),
        "kinetic_energy": ("kinetic_energy", "J", "kinetic energy, complete (law, time)"),
        "sway": ("sway", "rad", "load sway, nonlinear with gravity (law, time)"),
        "sway_linear": ("sway_linear", "rad", "load sway, linearised (law, time)"),
        "alpha_grid": ("alpha_grid", "rad", "boom angles over the luffing range (grid,)"),
        "tip_x": ("tip_x", "m", "jib tip x over alpha_grid (grid,)"),
        "tip_z": ("tip_z", "m", "jib tip z over alpha_grid (grid,)"),
        "J": ("J", "kg m^2", "complete reduced inertia at the boom (grid,)"),
        "J_paper": ("J_paper", "kg m^2", "reduced inertia of the paper's eq. 3 (grid,)"),
        "imbalance": ("imbalance", "N m", "dV/dalpha (grid,)"),
        "motor_ratio": ("motor_ratio", "1", "d(motor angle)/d(alpha) (grid,)"),
        "collocation": ("collocation", None, "collocation solution of the optimum"),
        "sensitivity": ("sensitivity", None, "sensitivity of the optimum"),
        "kinematics": ("kinematics", None, "kinematic checks of the linkage"),
        "timings": _COMMON["timings"], "warnings": _COMMON["warnings"],
    },
    "OperationResult": dict(_COMMON, **{
        "coordinates": ("coordinates", None, "generalised coordinates (n,)"),
        "duration": ("duration", "s", "simulated time"),
        "steps": ("steps", None, "accepted steps"),
        "rejected": ("rejected", None, "rejected steps"),
        "newton_iterations": ("newton_iterations", None, "Newton iterations"),
        "times": ("t_s", "s", "output times (time,)"),
        "mass_names": ("mass_names", None, "nodes with a point mass (mass,)"),
        "mass_position": ("mass_position", "m",
                          "position x, y, z of each point mass, global frame "
                          "(time, mass, 3)"),
        "rope_names": ("rope_names", None, "every rope of the model (rope,)"),
        "rope_force": ("rope_force", "N",
                       "rope force, elastic + dashpot; nan: not computed (time, rope)"),
        "rope_force_static": ("rope_force_static", "N", "static force at the start (rope,)"),
        "rope_force_max": ("rope_force_max", "N", "peak force over the run (rope,)"),
        "rope_force_max_time": ("rope_force_max_time", "s", "time of the peak (rope,)"),
        "drive_names": ("drive_names", None, "drives (drive,)"),
        "drive_units": ("drive_units", None,
                        "units of position and speed of each drive (drive, 2)"),
        "drive_kind": ("drive_kind", None,
                       "profile | torque | motor | free (drive,); torque: also a "
                       "slider's force"),
        "drive_position": ("drive_position", "mixed",
                           "drive position, units in drive_units (time, drive)"),
        "drive_speed": ("drive_speed", "mixed/s",
                        "drive speed, units in drive_units (time, drive)"),
        "drive_torque": ("drive_torque", "mixed",
                         "torque of a drum or hinge drive (N m), force of a slider drive "
                         "(N); nan for prescribed joints (time, drive)"),
        "holding": ("holding", "mixed", "torque (N m, hinge) or force (N, slider) that "
                    "holds each torque- or motor-driven joint at rest at t = 0"),
        "sway_names": ("sway_names", None, "point masses hanging on ropes (sway,)"),
        "sway_deg": ("sway_deg", "deg",
                     "angle of the span above from the vertical (time, sway)"),
        "sway_max_deg": ("sway_max_deg", "deg", "largest sway (sway,)"),
        "sway_residual_deg": ("sway_residual_deg", "deg",
                              "largest sway after the drives stop, nan if none (sway,)"),
        "motion_end": ("motion_end", "s", "when the last prescribed drive stops; inf "
                       "with a torque, force or motor drive (it acts to the end)"),
        "energy": ("energy", "J", "energy balance terms"),
        "energy_error": ("energy_error", "1", "energy balance error / largest term"),
        "events": ("events", "s", "events: column_0 the time, column_1 what happened"),
    }),
    "MemberForces": {
        "kind": ("kind", None, "what the states are: static | modes | times | envelope "
                 "(state 0 the minimum, state 1 the maximum over the output times)"),
        "forces": ("section_forces", "mixed",
                   "section forces in the element's axes at both ends: N, Vy, Vz in N, "
                   "T, My, Mz in N m (state, element, end, component); see the "
                   "attribute components, and the derived datasets in N and N m"),
        "stress": ("extreme_fibre_stress", "Pa",
                   "sigma_max, sigma_min at both ends: N/A +- |My|/Wy +- |Mz|/Wz; nan "
                   "for a beam without Wy (Wz) (state, element, end, 2)"),
        "pieces": ("pieces", None,
                   "node-to-node pieces of the members: column_0 member, column_1 type, "
                   "column_2 from node, column_3 to node, column_4 first element, "
                   "column_5 last element (0-based, piece)"),
        "scale": ("scale", None, "how modes are scaled: normalisation, amplitude_m (m)"),
        "element_member": ("element_member", None, "member of each element (element,)"),
    },
}

# datasets computed from the fields for readers of the file: name -> (units,
# description, function of the result)
DERIVED = {
    "ModalResult": {
        "frequency_hz": ("Hz", "natural frequency (mode,)", lambda r: r.frequency_hz),
        "period_s": ("s", "natural period, inf for a rigid mode (mode,)",
                     lambda r: r.period_s),
    },
    "DampingResult": {
        "frequency_hz": ("Hz", "undamped natural frequency (mode,)",
                         lambda r: r.frequency_hz),
        "damped_frequency_hz": ("Hz", "decoupled damped frequency (mode,)",
                                lambda r: r.damped_omega / (2 * 3.141592653589793)),
    },
    "OperationResult": {
        "dynamic_factor": ("1", "peak / static rope force (rope,)",
                           lambda r: r.dynamic_factor),
    },
    "MemberForces": {
        "axial_force": ("N", "N, tension + (state, element, end)",
                        lambda r: r.forces[..., 0]),
        "shear_force": ("N", "Vy, Vz (state, element, end, 2)",
                        lambda r: r.forces[..., 1:3]),
        "torque": ("N m", "T (state, element, end)", lambda r: r.forces[..., 3]),
        "bending_moment": ("N m", "My, Mz (state, element, end, 2)",
                           lambda r: r.forces[..., 4:6]),
    },
}

# units of dict entries named by their key's suffix (luffing figures, energies, ...)
_SUFFIX = (("_rad_s", "rad/s"), ("_N_m", "N m"), ("_Nms", "N m s"), ("_Nm", "N m"),
           ("_deg", "deg"), ("_rad", "rad"), ("_hz", "Hz"), ("_Hz", "Hz"), ("_J", "J"),
           ("_W", "W"), ("_N", "N"), ("_s", "s"), ("_m", "m"), ("_kg", "kg"))


def key_units(key, default=None):
    """Units of a dict entry from its key ("T_mean_J" -> "J"), else `default`."""
    for suffix, units in _SUFFIX:
        if key.endswith(suffix):
            return units
    return default


def field_info(cls_name, field):
    """(dataset name, units, description) of a field; an unknown field keeps its name."""
    return FIELDS.get(cls_name, {}).get(field, (field, None, f"field {field} of {cls_name}"))
