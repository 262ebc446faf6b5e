"""Mutation testing of one cranefe formula module at a time (issue 20).

Runs mutmut 3 (``pip install -e .[mutation]``) over ONE module with the fast tests that
cover it, in a scratch copy of the worktree (mutmut writes a ``mutants/`` tree and its
config must name the module, so nothing in the checkout is touched), then prints the
counts, the score and the diff of every surviving mutant.

    python tools/mutation.py ropes            # a preset below
    python tools/mutation.py cranefe/condense.py tests/test_condense.py --timeout 30
    python tools/mutation.py ropes --keep /tmp/mut-ropes   # keep the scratch copy
    python tools/mutation.py beams --before    # without the kill tests of issue 20

score = killed / (killed + survived + timed out); "timeout" is a mutant whose tests ran
longer than the per-mutant limit (mutmut: 15 x the clean run time + ``--timeout`` s),
usually a loop made endless, and counts as not killed here to stay conservative.
Runs one worker at a time by default (the machine has 2 cores shared with others).
"""

from __future__ import annotations

import argparse
import ast
import os
import re
import signal
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# module -> the fast tests that exercise it (seconds each, no slow marker)
PRESETS = {
    "ropes": ("cranefe/elements/ropes.py",
              ["tests/test_kernels.py", "tests/test_closed_forms.py",
               "tests/test_exact_potential.py", "tests/test_mutation_kills_ropes.py"]),
    "bodies": ("cranefe/elements/bodies.py",
               ["tests/test_kernels.py", "tests/test_closed_forms.py",
                "tests/test_mutation_kills_bodies.py"]),
    "damping_element": ("cranefe/analysis/damping/element.py",
                        ["tests/test_values.py", "tests/test_damping.py",
                         "tests/test_mutation_kills_damping.py"]),
    "damping_modal": ("cranefe/analysis/damping/modal.py",
                      ["tests/test_values.py", "tests/test_damping.py",
                       "tests/test_mutation_kills_modal.py",
                       "tests/test_mutation_kills_modal_mixed.py"]),
    "condense": ("cranefe/condense.py",
                 ["tests/test_closed_forms.py", "tests/test_audit_numerics.py",
                  "tests/test_mutation_kills_condense.py",
                  "tests/test_mutation_kills_condense_weak.py",
                  "tests/test_mutation_kills_condense_massless_map.py",
                  "tests/test_mutation_kills_condense_free.py"]),
    "sdof": ("cranefe/analysis/loads/sdof.py",
             ["tests/test_loads_standard.py", "tests/test_mutation_kills_loads.py"]),
    # beams: the three slowest structure tests (8-15 s each) are left out; every kernel
    # is still reached by the others
    "beams": ("cranefe/elements/beams.py",
              ["tests/test_members.py", "tests/test_structures.py",
               "--deselect=tests/test_structures.py::test_fv2_double_cross_with_pinned_supports",
               "--deselect=tests/test_structures.py::test_fv5_in_3d_with_per_direction_supports",
               "--deselect=tests/test_structures.py::"
               "test_mesh_members_take_sections_and_their_points_take_supports",
               "tests/test_mutation_kills_beams.py"]),
    # system and statics: tension and load stiffness with sway on are compared with a
    # peer only in the Exudyn spreader test (1.7 s; skipped without Exudyn); the beams'
    # geometric stiffness under self-weight only in two structure tests
    "system": ("cranefe/system.py",
               ["tests/test_closed_forms.py", "tests/test_kernels.py",
                "tests/test_mutation_kills_bodies.py", "tests/test_members.py",
                "tests/test_validation_study.py::test_spatial_spreader_with_sway_against_exudyn",
                "tests/test_structures.py::test_column_buckles_under_its_own_weight_at_greenhill",
                "tests/test_structures.py::test_modes_see_the_self_weight_buckling_load",
                "tests/test_mutation_kills_damping.py",
                "tests/test_mutation_kills_system.py"]),
    # statics: every model test solves a static state, so the module tests (the earlier
    # preset, statics_broad) run per mutant for about 1.5 h; the two kill-test files
    # reach every function on small models solved by hand, in seconds
    "statics": ("cranefe/statics.py",
                ["tests/test_mutation_kills_statics.py",
                 "tests/test_mutation_kills_statics_solve.py",
                 "tests/test_mutation_kills_statics_effects.py"]),
    "statics_broad": ("cranefe/statics.py",
                      ["tests/test_closed_forms.py", "tests/test_audit_numerics.py",
                       "tests/test_members.py",
                       "tests/test_validation_study.py::test_spatial_spreader_with_sway_against_exudyn",
                       "tests/test_structures.py::test_member_end_forces_under_self_weight_are_exact",
                       "tests/test_mutation_kills_statics.py"]),
    # newmark: the Stepper on hand-built Equations of 1-2 coordinates (no model, no
    # statics: ~1 s a mutant; a whole run of the 859 in ~16 min) + the Cayley-map case
    "newmark": ("cranefe/analysis/transient/newmark.py",
                ["tests/test_mutation_kills_newmark_stepper.py",
                 "tests/test_mutation_kills_newmark.py"]),
    # luffing: tests/test_luffing.py runs whole analyses (up to 7 s each): the J(alpha)
    # value test and the kill test reach every quantity of energy.py in a few seconds
    "luffing_energy": ("cranefe/analysis/luffing/energy.py",
                       ["tests/test_values.py::test_portal_crane_reduced_inertia_from_an_independent_linkage",
                        "tests/test_mutation_kills_luffing.py",
                        "tests/test_mutation_kills_luffing_own_axis.py",
                        "tests/test_mutation_kills_luffing_drive.py",
                        "tests/test_mutation_kills_luffing_proxy.py"]),
    # kinematics: the Linkage alone against the hand linkage (hand values computed once
    # per session); + a parallelogram with a redundant link (pseudo-inverse branch)
    "luffing_kinematics": ("cranefe/analysis/luffing/kinematics.py",
                           ["tests/test_mutation_kills_luffing_kinematics.py",
                            "tests/test_mutation_kills_luffing_configs.py::"
                            "test_a_redundant_joint_is_solved_by_the_pseudo_inverse"]),
    # luffing laws and sway: the laws by hand and in mpmath; the sway against a hand
    # integration of the pendulums and a 30-digit quadrature of the residual
    "luffing_laws": ("cranefe/analysis/luffing/laws.py",
                     ["tests/test_mutation_kills_luffing_laws.py"]),
    "luffing_sway": ("cranefe/analysis/luffing/sway.py",
                     ["tests/test_mutation_kills_luffing_sway.py"]),
    "motion": ("cranefe/elements/motion.py",
               ["tests/test_mutation_kills_motion.py"]),
    # loads/standard.py: the EN 13001-2 factors, pure functions
    "standard": ("cranefe/analysis/loads/standard.py",
                 ["tests/test_loads_standard.py", "tests/test_mutation_kills_loads.py",
                  "tests/test_mutation_kills_standard.py"]),
    # shaping: the impulse trains (pure) and the varying-frequency shaper; the engine's
    # tests (tests/test_shaping_engine.py, 30 s) are left out
    "shapers": ("cranefe/analysis/shaping/shapers.py",
                ["tests/test_shaping.py", "tests/test_mutation_kills_shapers.py"]),
    "varying": ("cranefe/analysis/shaping/varying.py",
                ["tests/test_shaping_varying.py", "tests/test_mutation_kills_varying.py"]),
    # operation engine: the drive profiles and the joint inertia, by value (the engine's
    # own tests, tests/test_operation.py, take about 70 s)
    "profiles": ("cranefe/analysis/operation/profiles.py",
                 ["tests/test_mutation_kills_profiles.py",
                  "tests/test_mutation_kills_properties.py::"
                  "test_motion_end_is_the_last_boundary_only_when_it_rests"]),
    # assembly/: every file of the package (a glob), with the fast model-building tests;
    # _springs: every field of the spring rows, the pattern, null space, COO step, Reuse;
    # _local: beam_local_matrices by hand; _more: rigid rod oblique to a 3D hinge, a
    # rope's extra length, a light welded body (whole run ~20 min at load 4-5)
    "assembly": ("cranefe/assembly/*",
                 ["tests/test_closed_forms.py", "tests/test_kernels.py",
                  "tests/test_members.py", "tests/test_mutation_kills_system.py",
                  "tests/test_mutation_kills_statics.py",
                  "tests/test_mutation_kills_assembly.py",
                  "tests/test_mutation_kills_assembly_beams.py",
                  "tests/test_timoshenko_geometric.py",
                  "tests/test_mutation_kills_assembly_springs.py",
                  "tests/test_mutation_kills_assembly_local.py",
                  "tests/test_mutation_kills_assembly_more.py"]),
    # shaping/motion.py: the acceleration/jerk-step profiles, their shaping and the
    # residual sway in closed form; test_shaping.py (1.5 s) and the kill tests (~6 s)
    "shaping_motion": ("cranefe/analysis/shaping/motion.py",
                       ["tests/test_shaping.py",
                        "tests/test_mutation_kills_shaping_motion.py"]),
    # shaping/swingfree.py: the minimum-time swing-free trapezoid and the energy-optimal
    # move; test_shaping.py (1.5 s) and the kill tests (~6-10 s: a 25-digit Gram system)
    "swingfree": ("cranefe/analysis/shaping/swingfree.py",
                  ["tests/test_shaping.py", "tests/test_mutation_kills_swingfree.py"]),
    # operation/shaped.py: shaped moves of scenes, frequency: auto from the crane's
    # modes; the kill tests parse scenes only (~10 s); tests/test_shaping_engine.py runs
    # the engine (30 s idle) and is left out
    "shaped": ("cranefe/analysis/operation/shaped.py",
               ["tests/test_mutation_kills_shaped.py"]),
    # shaping/engine.py: the scene edits, the summary and compare's document; the engine
    # itself is replaced by a stand-in in the kill tests (tests/test_shaping_engine.py,
    # which runs it, takes about 30 s idle and is left out)
    "shaping_engine": ("cranefe/analysis/shaping/engine.py",
                       ["tests/test_mutation_kills_shaping_engine.py"]),
    # joints: the rewritten module (JointChain, Taylor jets); tests/test_operation_joint_chain.py
    # (~60 s) is too slow per mutant: the chain's kill tests check it against a hand
    # Lagrangian and Cauchy-formula derivatives of the composed closed-form maps
    "joints": ("cranefe/analysis/operation/joints.py",
               ["tests/test_mutation_kills_joints.py",
                "tests/test_mutation_kills_joints_chain.py"]),
    # linkage: luffing by a linear drive in the operation engine; its engine tests
    # (tests/test_operation_dyn.py, test_operation_fixes.py) are too slow per mutant:
    # a four-bar luffed by a cylinder on its coupler against hand geometry; poses asked
    # far from the last one (the continuation table, times in any order); a Newton step
    # past the linkage's range after a reached pose (halved back toward it)
    "linkage": ("cranefe/analysis/operation/linkage.py",
                ["tests/test_mutation_kills_linkage.py",
                 "tests/test_mutation_kills_linkage_configs.py",
                 "tests/test_mutation_kills_linkage_overshoot.py"]),
    # operation engine: the equations at a state (forces, tangents, kinematics, statics,
    # energies, powers) by hand on small scenes, no integration; the setup's refusals; the
    # configurations the first two files did not build (a joint's point on no body, bodies
    # two levels below a joint coordinate, springs between bodies, a joint coordinate
    # before a drum coordinate, a linear drive, ranges, an elastic structure's poses,
    # three prescribed joints in a chain); the flexible kill tests reach the elastic
    # structure's calls (evaluate, energy, powers); _rare: two drum coordinates, an
    # elastic jib with a damped rope, an elastic structure beside a joint coordinate,
    # three joint coordinates, sway off with a load no coordinate guides
    "mechanism": ("cranefe/analysis/operation/mechanism.py",
                  ["tests/test_mutation_kills_mechanism.py",
                   "tests/test_mutation_kills_mechanism_setup.py",
                   "tests/test_mutation_kills_mechanism_configs.py",
                   "tests/test_mutation_kills_mechanism_rare.py",
                   "tests/test_mutation_kills_flexible.py"]),
    # damping_exact: fast kill tests only (the analyses of test_values/test_damping ran
    # minutes per mutant; that set is damping_exact_broad): a 3-DOF chain against mpmath,
    # repeated/overdamped/massless cases and the eigen-search's parts by closed forms
    "damping_exact": ("cranefe/analysis/damping/exact.py",
                      ["tests/test_mutation_kills_exact.py",
                       "tests/test_mutation_kills_exact_search.py"]),
    "damping_exact_broad": ("cranefe/analysis/damping/exact.py",
                            ["tests/test_values.py", "tests/test_damping.py",
                             "tests/test_mutation_kills_exact.py"]),
    # operation/constraints.py: the inextensible ropes' stepper and the massless blocks'
    # helpers; hand states (pendulum, V, sling, trolley, two drums, block) and a 2 s
    # pendulum run in the kill tests, plus the fast inextensible runs (< 1 s each)
    "constraints": ("cranefe/analysis/operation/constraints.py",
                    ["tests/test_mutation_kills_constraints.py",
                     "tests/test_mutation_kills_constraints_refresh.py",
                     "tests/test_operation_inextensible.py::test_load_thrown_up_goes_slack_and_is_jerked_taut",
                     "tests/test_operation_inextensible.py::test_torque_drum_hoists_with_the_drums_inertia",
                     "tests/test_operation_inextensible.py::test_hoisting_at_constant_speed_without_sway_is_m_g",
                     "tests/test_operation_inextensible.py::test_what_constraints_do_not_cover_is_refused"]),
    # transient/modal.py: modal superposition with the static correction, against the
    # trapezoidal rule of the modal equations written out by hand (1-3 s)
    "transient_modal": ("cranefe/analysis/transient/modal.py",
                        ["tests/test_mutation_kills_transient_modal.py"]),
    # analysis/buckling.py: critical gravity factor k/(m g l) of bars above hinges,
    # never-buckling cases, the Greenhill column (~12 s)
    "buckling": ("cranefe/analysis/buckling.py",
                 ["tests/test_mutation_kills_modal_paths.py",
                  "tests/test_structures.py::test_column_buckles_under_its_own_weight_at_greenhill"]),
    # transient equations: the Equations/Factor objects alone, on a hand-built two-mass
    # hoist (no model, no stepping: ~0.3 s of test work per mutant)
    "transient_equations": ("cranefe/analysis/transient/equations.py",
                            ["tests/test_mutation_kills_transient_equations.py"]),
    # transient problem: the equations Problem builds for the two-mass hoist (and a
    # sheave block, a spring chain) against hand-written ones; no time stepping
    "transient_problem": ("cranefe/analysis/transient/problem.py",
                          ["tests/test_mutation_kills_transient_problem.py"]),
    # coordinates/: the rope mesh, the constraint transform T_c, the kinematic map and
    # the member mesh, by hand on small models (every closed-form test reaches them, but
    # runs whole analyses: minutes per mutant); ~1-3 s per file
    "coords_ropes": ("cranefe/coordinates/ropes.py",
                     ["tests/test_mutation_kills_coordinates_ropes.py"]),
    "coords_constraints": ("cranefe/coordinates/constraints.py",
                           ["tests/test_mutation_kills_coordinates_constraints.py"]),
    # dofmap: build_dofs is reached by all four files (rope meshes, constraints, members);
    # _more: a body welded to the ground by a joint listing the ground second
    "coords_dofmap": ("cranefe/coordinates/dofmap.py",
                      ["tests/test_mutation_kills_coordinates_dofmap.py",
                       "tests/test_mutation_kills_coordinates_dofmap_more.py",
                       "tests/test_mutation_kills_coordinates_ropes.py",
                       "tests/test_mutation_kills_coordinates_constraints.py",
                       "tests/test_mutation_kills_coordinates_members.py"]),
    "coords_members": ("cranefe/coordinates/members.py",
                       ["tests/test_mutation_kills_coordinates_members.py"]),
    # sections: every shape's A, I, J, shear areas and moduli composed by hand from
    # rectangles and quarter discs (not the module's spandrel integrals); named profiles
    "sections": ("cranefe/model/sections.py",
                 ["tests/test_mutation_kills_sections.py",
                  "tests/test_sections_profiles.py::test_fillets_and_radii_are_exact_spandrels"]),
    # luffing optimum: every solver of eq. 16 against the closed-form optima of
    # J = exp(2 k alpha) and J = (c + alpha)^2 (tests/test_luffing.py builds a crane: slow)
    "luffing_optimum": ("cranefe/analysis/luffing/optimum.py",
                        ["tests/test_mutation_kills_luffing_optimum.py"]),
    # member forces: a 3D L-frame with self-weight in both bending planes and torsion and
    # a tripod against hand statics, on the module's functions (the CLI tests: slow)
    "member_forces": ("cranefe/outputs/member_forces.py",
                      ["tests/test_mutation_kills_member_forces.py"]),
    # loads/scene.py: the loads scene's keys, defaults and errors (parse only, ~10 s)
    "loads_scene": ("cranefe/analysis/loads/scene.py",
                    ["tests/test_mutation_kills_loads_scene.py",
                     "tests/test_mutation_kills_loads_scene_more.py"]),
    # loads/runs.py: every run behind the factors on one- and two-mass models against
    # closed forms (operation engine without numba: its compilation costs a minute)
    "loads_runs": ("cranefe/analysis/loads/runs.py",
                   ["tests/test_mutation_kills_loads_runs.py"]),
    # the numpy stepper (fast=False): one trapezoidal step and its error estimate by
    # hand, the step controller, events at free-fall times, runs against scipy; the
    # main loop's exact step sequences (free fall, constant acceleration), injected
    # Newton/error failures, a pendulum on a moving trolley (joint coordinate, kinks);
    # the event step's drive work (closed-form taut event), the right limits at a kink
    # with a joint and a damped rope, two drums, a massless block, the hand-over to the
    # compiled loop/step (numba, its cache: the first run compiles for minutes); an
    # elastic structure's run (steps ending at kinks from the left, _FlexOps' force-error
    # rows) and inextensible ropes' runs (a given state projected, a jerk with the drum's
    # work) (53 tests)
    "integrate": ("cranefe/analysis/operation/integrate.py",
                  ["tests/test_mutation_kills_integrate.py",
                   "tests/test_mutation_kills_integrate_loop.py",
                   "tests/test_mutation_kills_integrate_events.py",
                   "tests/test_mutation_kills_integrate_flexible.py",
                   "tests/test_mutation_kills_integrate_inextensible.py"]),
    # damping/analysis.py: the damping analysis's switch (modal / exact / both / auto by
    # Hasselman's coupling and the predicted error), its report, warnings and partner
    # modes, on 1-40-coordinate models by hand (state space, closed forms; ~2 s)
    "damping_analysis": ("cranefe/analysis/damping/analysis.py",
                         ["tests/test_mutation_kills_damping_analysis.py"]),
    # damping/result.py: the damping result's properties (the weak-coupling criterion,
    # trust, the log decrements, the errors against the exact solutions) and its document
    # on a result written by hand, and through the damping analysis' kill tests
    "damping_result": ("cranefe/analysis/damping/result.py",
                       ["tests/test_mutation_kills_damping_result.py",
                        "tests/test_mutation_kills_damping_analysis.py"]),
    # transient/scene.py: the transient scene's keys, defaults, drives, motors, time
    # functions and grounded loads, and every error's file/entry/message (parse only, ~1 s)
    "transient_scene": ("cranefe/analysis/transient/scene.py",
                        ["tests/test_mutation_kills_transient_scene.py",
                         "tests/test_mutation_kills_properties.py::"
                         "test_transient_breakpoints_strictly_inside_the_run"]),
    # luffing/analysis.py: a parallelogram linkage written out by hand (J, Jp, dV, the
    # rack, the tip); the swing-free law and, in analyse, the pendulums and reports are
    # stand-ins (each has its own kill tests); ~20 s, so run with OPENBLAS_NUM_THREADS=1;
    # + a four-bar whose coupler turns (tip on a coupler curve): the load-mass law
    "luffing_analysis": ("cranefe/analysis/luffing/analysis.py",
                         ["tests/test_mutation_kills_luffing_analysis.py",
                          "tests/test_mutation_kills_luffing_configs.py"]),
    # analysis/modal.py: dense, sparse (massless node condensed in the operator), rigid
    # and unstable modes, graded paths and the Cholesky fallback (coupled inertia, mass
    # contrast), the choices modes() makes and reports, drive_reduction (~15 s)
    "modal": ("cranefe/analysis/modal.py",
              ["tests/test_mutation_kills_modal_paths.py",
               "tests/test_mutation_kills_modal_graded.py",
               "tests/test_mutation_kills_modal_choices.py",
               "tests/test_graded.py::test_negative_load_stiffness_merged_locally",
               "tests/test_mutation_kills_condense_massless_map.py",
               "tests/test_mutation_kills_properties.py::"
               "test_modal_frequency_and_period_by_hand"]),
    # analysis/graded.py: element factor, energy, merged negative parts, massless rows,
    # Jacobi SVD; graded models against mpmath, factor contracts by hand (~20 s)
    "graded": ("cranefe/analysis/graded.py",
               ["tests/test_mutation_kills_modal_paths.py",
                "tests/test_mutation_kills_modal_graded.py", "tests/test_graded.py",
                "tests/test_mutation_kills_condense_massless_map.py",
                "tests/test_mutation_kills_graded_factor.py"]),
    # operation/flexible.py: the elastic structure riding on the mechanism; one-element
    # members, moving and chained frames, a linkage body and the setup's refusals written
    # out by hand in the kill tests, plus the fast tests of tests/test_operation_flexible.py
    # (its runs take minutes: left out); two ropes going slack in one step below an
    # elastic tip (the event search's power terms on a motions-cache miss)
    "flexible": ("cranefe/analysis/operation/flexible.py",
                 ["tests/test_mutation_kills_flexible.py",
                  "tests/test_mutation_kills_flexible_frames.py",
                  "tests/test_mutation_kills_flexible_chain.py",
                  "tests/test_mutation_kills_flexible_setup.py",
                  "tests/test_mutation_kills_flexible_events.py",
                  "tests/test_operation_flexible.py::test_spinning_cantilever_stiffens_southwell",
                  "tests/test_operation_flexible.py::test_linearisation_equals_the_linear_core",
                  "tests/test_operation_flexible.py::test_truss_and_spring_structure_equals_the_linear_core",
                  "tests/test_operation_flexible.py::test_static_tip_deflection_under_gravity",
                  "tests/test_operation_flexible.py::test_refused_cases_exit_2",
                  "tests/test_operation_flexible.py::test_lean_does_not_claim_an_elastic_structure"]),
    # loads/analysis.py: the EN 13001-2 load table of a single mass on an elastic rope
    # by hand, a hook block with the load on a sling (two ropes) against DOP853, phi1 of
    # an elastic arm, phi5 of a slider move (+ ZV shaper); the configurations file:
    # only=[phi5] with a move, every run's warnings, a tag line beside a 0.49 N rope,
    # light and massless parts in phi1, phi5 of an inclined luffing jib and of a 60 deg
    # slew about axes away from the origin (pendulum references by DOP853); the ties
    # file: phi1's worst mass on a balanced arm, the suspension node's rule by hand
    "loads_analysis": ("cranefe/analysis/loads/analysis.py",
                       ["tests/test_mutation_kills_loads_analysis.py",
                        "tests/test_mutation_kills_loads_configs.py",
                        "tests/test_mutation_kills_loads_ties.py",
                        "tests/test_loads.py::test_phi5_of_a_luffing_hinge"]),
    # operation/lean.py: Lean (the integrator's view of a mechanism) by hand and against
    # Mechanism on 14 small scenes x sway/damping (every branch), Generic (~5 s CPU)
    # operation/results.py: the Recorder (energy terms, Hermite peaks and samples between
    # steps) through the numpy loop's runs: the loop configurations step for step against
    # the numpy loop, the integrator's hand values, and drive torques sampled inside
    # steps (a torque table, a geared motor) by hand
    "results": ("cranefe/analysis/operation/results.py",
                ["tests/test_mutation_kills_loop_configs.py",
                 "tests/test_mutation_kills_integrate.py",
                 "tests/test_mutation_kills_results.py"]),
    "lean": ("cranefe/analysis/operation/lean.py",
             ["tests/test_mutation_kills_lean.py"]),
    # operation/fast.py (numba step; this tool runs it with numba's JIT off and the kernels
    # undecorated, see JIT_MODULES and undecorate below); a step by hand,
    # LU against numpy, _forces and the step against Lean and the numpy Stepper (~2 s);
    # a step whose Newton matrix needs a row swap
    "fast_step": ("cranefe/analysis/operation/fast.py",
                  ["tests/test_mutation_kills_lean_fast.py::test_forces_equal_lean[trolley-{damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_forces_equal_lean[winch and sling-{sway: false, damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_forces_equal_lean[v sling-{damping: none}]",
                   "tests/test_mutation_kills_lean_fast.py::test_forces_equal_lean[tag line-{sway: false, damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_forces_equal_lean[soft rope-{damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_forces_equal_lean[running sheave-{damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_step_equals_the_numpy_step[trolley-{damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_step_equals_the_numpy_step[winch on a trolley-{damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_step_equals_the_numpy_step[v sling-{damping: none}]",
                   "tests/test_mutation_kills_lean_fast.py::test_step_equals_the_numpy_step[soft rope-{damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_step_equals_the_numpy_step[tag line-{sway: false, damping: exact}]",
                   "tests/test_mutation_kills_lean_fast.py::test_available_says_whether_numba_is_installed",
                   "tests/test_mutation_kills_lean_fast.py::test_lu_with_pivoting_solves_as_numpy",
                   "tests/test_mutation_kills_lean_fast.py::test_lu_refuses_singular_and_non_finite_matrices",
                   "tests/test_mutation_kills_lean_fast.py::test_one_step_of_a_load_on_its_rope_by_hand",
                   "tests/test_mutation_kills_lean_fast.py::test_failures_of_the_step",
                   "tests/test_mutation_kills_lean_fast_pivot.py"]),
    # operation/loop.py (numba loop): NUMBA_DISABLE_JIT=1 and undecorated as fast_step;
    # profiles by hand, the kinematics/powers/energy against Lean, runs against scipy
    # and the numpy loop step for step (16 ids of the lean loop's file), and the
    # configurations of test_mutation_kills_loop_configs.py (two ropes taut in one step,
    # kinks before 1 s, a stretched tag line without sway, failures inside the event
    # search and after some steps, three profile drums, two guided loads, a rope below
    # 1 N, a winch paying out faster than free fall, the energy error's scales).
    # 2192 mutants: ~3 h idle with the whole list; see docs/mutation.md for the
    # assembled run (narrow subsets first, survivors with the whole list)
    "loop": ("cranefe/analysis/operation/loop.py",
             ["tests/test_mutation_kills_lean_loop.py::test_kinematics_powers_and_energy_equal_lean",
              "tests/test_mutation_kills_lean_loop.py::test_runs_equal_the_numpy_loop[trolley]",
              "tests/test_mutation_kills_lean_loop.py::test_runs_equal_the_numpy_loop[winch on a trolley]",
              "tests/test_mutation_kills_lean_loop.py::test_runs_equal_the_numpy_loop[tag line, sway off]",
              "tests/test_mutation_kills_lean_loop.py::test_runs_equal_the_numpy_loop[trolley on a held jib]",
              "tests/test_mutation_kills_lean_loop.py::test_motion_table_by_hand",
              "tests/test_mutation_kills_lean_loop.py::test_sign",
              "tests/test_mutation_kills_lean_loop.py::test_trolley_pendulum_against_scipy",
              "tests/test_mutation_kills_lean_loop.py::test_two_loads_thrown_up_against_scipy",
              "tests/test_mutation_kills_lean_loop.py::test_snatch_with_sway_and_damping",
              "tests/test_mutation_kills_lean_loop.py::test_progress_runs_in_chunks_with_the_same_steps",
              "tests/test_mutation_kills_lean_loop.py::test_failures_as_the_numpy_loop",
              "tests/test_mutation_kills_lean_loop.py::test_what_the_loop_does_not_cover",
              "tests/test_mutation_kills_loop_configs.py"]),
}

# modules of numba kernels: mutated with numba's JIT off (fast.available() stays True, so
# the tests still take the compiled path, as plain Python)
JIT_MODULES = {"cranefe/analysis/operation/fast.py", "cranefe/analysis/operation/loop.py"}


def undecorate(path: Path) -> None:
    """`@dec` + `def f` -> `def f` ... `f = dec(f)`, the same code, in the scratch copy:
    mutmut 3 leaves every function with a decorator other than staticmethod/classmethod
    unmutated (properties, cached properties, the section shapes' registry, the numba
    kernels), so without this their formulas would get no mutant. Module-level functions
    and methods with one decorator; the assignment follows the function at its indent."""
    src = path.read_text()
    lines = src.split("\n")
    edits = []
    for parent in ast.walk(ast.parse(src)):
        if not isinstance(parent, (ast.Module, ast.ClassDef)):
            continue
        for node in parent.body:
            if not isinstance(node, ast.FunctionDef) or len(node.decorator_list) != 1:
                continue
            dec = node.decorator_list[0]
            if isinstance(dec, ast.Name) and dec.id in ("staticmethod", "classmethod"):
                continue
            edits.append((dec.lineno, dec.end_lineno, node.end_lineno, node.col_offset,
                          node.name, ast.get_source_segment(src, dec)))
    for first, last, end, col, name, dec in sorted(edits, reverse=True):
        lines.insert(end, " " * col + f"{name} = ({dec})({name})")
        del lines[first - 1:last]
    path.write_text("\n".join(lines))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("module", help="a preset name or a path such as cranefe/condense.py")
    ap.add_argument("tests", nargs="*", help="test files (default: the preset's)")
    ap.add_argument("--timeout", type=float, default=20.0,
                    help="seconds added to 15 x the clean run time per mutant")
    ap.add_argument("--multiplier", type=float, default=15.0,
                    help="x the clean run time in the per-mutant limit (mutmut: CPU seconds "
                         "2 x multiplier x (clean time + --timeout))")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--minutes", type=float,
                    help="stop the run after this long and report the mutants checked so far")
    ap.add_argument("--before", action="store_true",
                    help="leave out the preset's tests/test_mutation_kills_*.py (the score before them)")
    ap.add_argument("--keep", type=Path, help="scratch directory to keep (default: a temp dir)")
    args = ap.parse_args(argv)

    if args.module in PRESETS:
        module, tests = PRESETS[args.module]
        tests = args.tests or tests
    else:
        module, tests = args.module, args.tests
    if args.before:
        tests = [t for t in tests if "test_mutation_kills_" not in t]
    # a preset's kill-test file that does not exist yet (a "before" run) is left out
    missing = [t for t in tests if not t.startswith("-") and not (ROOT / t.split("::")[0]).exists()]
    if missing:
        print("not found, left out:", " ".join(missing))
    tests = [t for t in tests if t not in missing]
    if not [t for t in tests if not t.startswith("-")]:
        ap.error("name the test files that cover the module")

    work = args.keep or Path(tempfile.mkdtemp(prefix="cranefe-mut-"))
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    shutil.copytree(ROOT / "cranefe", work / "cranefe",
                    ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(ROOT / "tests", work / "tests",
                    ignore=shutil.ignore_patterns("__pycache__"))
    for extra in ("examples", "models", "results", "docs", "README.md"):
        src = ROOT / extra
        if src.is_dir():
            shutil.copytree(src, work / extra, ignore=shutil.ignore_patterns("__pycache__"))
        elif src.is_file():
            shutil.copy(src, work / extra)
    for path in sorted(work.glob(module)):
        undecorate(path)
    # a pyproject without [tool.mutmut] would shadow setup.cfg only if it had one; keep the
    # pytest settings (markers) by copying it and adding the mutmut section to setup.cfg
    shutil.copy(ROOT / "pyproject.toml", work / "pyproject.toml")
    copies = "\n    ".join(["tests", "examples", "models", "results", "docs"])
    (work / "setup.cfg").write_text(
        "[mutmut]\n"
        f"only_mutate = {module}\n"
        "source_paths = cranefe\n"
        f"pytest_add_cli_args_test_selection =\n    " + "\n    ".join(tests) + "\n"
        f"also_copy =\n    {copies}\n"
        f"timeout_constant = {args.timeout}\n"
        f"timeout_multiplier = {args.multiplier}\n"
        "use_git_change_detection = false\n")

    # the numba kernels run as plain Python (their mutants are reached; nothing compiled)
    env = dict(os.environ, NUMBA_DISABLE_JIT="1") if module in JIT_MODULES else None
    run = subprocess.Popen([sys.executable, "-m", "mutmut", "run",
                            "--max-children", str(args.workers)], cwd=work,
                           start_new_session=True, env=env)
    try:
        run.wait(timeout=args.minutes * 60 if args.minutes else None)
    except subprocess.TimeoutExpired:
        # mutmut saves each mutant's result as it comes: stop its process group and
        # report what was checked ("not checked" counts the rest)
        os.killpg(run.pid, signal.SIGTERM)
        run.wait()
        print(f"\nstopped after {args.minutes} min", flush=True)
    res = subprocess.run([sys.executable, "-m", "mutmut", "results", "--all", "true"],
                         cwd=work, capture_output=True, text=True)
    counts: dict[str, list[str]] = {}
    for line in res.stdout.splitlines():
        m = re.match(r"\s*(\S+): (.+)$", line)
        if m:
            counts.setdefault(m.group(2).strip(), []).append(m.group(1))
    total = sum(len(v) for v in counts.values())
    killed = len(counts.get("killed", []))
    surv = counts.get("survived", [])
    tout = counts.get("timeout", [])
    print(f"\n== {module} with {' '.join(tests)}", flush=True)
    print("mutants:", total, {k: len(v) for k, v in counts.items()})
    if "not checked" in counts:
        print(f"(partial run: {len(counts['not checked'])} not checked; the score is of "
              "the checked ones, which mutmut runs fastest-first)")
    denom = killed + len(surv) + len(tout)
    if denom:
        print(f"score: {killed}/{denom} = {killed / denom:.1%}")
    for name in surv + tout:
        show = subprocess.run([sys.executable, "-m", "mutmut", "show", name],
                              cwd=work, capture_output=True, text=True)
        diff = [ln for ln in show.stdout.splitlines()
                if ln.startswith(("+", "-")) and not ln.startswith(("+++", "---"))]
        print(f"-- {name}")
        print("\n".join("   " + ln for ln in diff))
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    return run.returncode


if __name__ == "__main__":
    sys.exit(main())
