/*
** afv_config.h -- the constants of afv in one place: the status codes and
** every tolerance of the library, each with what it means geometrically
** and the test that pins it: the test that fails when the value is
** mutated as said (measured: test/run_tests of the suites named, -O1
** -DNDEBUG).  "Not pinned" says the mutation passes the whole suite,
** with what was measured of its effect: a value that only guards
** rounding no fixture reaches, or a fixture still owed.  A numeric
** tolerance written anywhere else in the library is a bug.  Included by
** afv.h, installed beside it.
**
** Lengths are in units of l unless said.  API (kept across versions): the
** status codes, AFV_CONTACT_TOL, AFV_MAX_STEP_DISP, AFV_RUNAWAY_MOVE and
** the relaxation's AFV_RELAX_*; the others are the library's own, listed
** here so that a reader finds every tolerance where it looks first.
**
** Contents
**   1. status codes
**   2. contact                        AFV_CONTACT_TOL
**   3. the cell's shape (geom.c)      AFV_ANGLE_TOL .. AFV_PRUNE_MARGIN
**   4. the neighbour search           AFV_REACH_MARGIN, AFV_CUT_DEPTH,
**                                     AFV_NEAR_IMAGE
**   5. rounding, the parameters' range, the finite-difference check
**   6. dynamics and relaxation        AFV_MAX_STEP_DISP .. AFV_FIRE_*
**   7. pictures (svg.c)               AFV_FULL_CIRCLE_TOL .. AFV_SVG_*
*/
#ifndef AFV_CONFIG_H
#define AFV_CONFIG_H

#include <float.h>

/* ---- 1. status codes ---------------------------------------------------- */
/* Every library function that can fail returns one (afv_strerror). */
#define AFV_OK           0  /* success */
#define AFV_ENOMEM       1  /* an allocation failed */
#define AFV_EINVAL       2  /* a parameter is out of range (l <= 0, NaN, ...) */
#define AFV_EBOX         3  /* periodic box side smaller than 4l */
#define AFV_ENONFINITE   4  /* a position is NaN or infinite */
#define AFV_ECOINCIDENT  5  /* two centres coincide (d = 0): afv_geom_bad_pair */
#define AFV_EIO          6  /* reading or writing a file failed */
#define AFV_EFORMAT      7  /* a file is not in the documented format */
#define AFV_EUNSTABLE    8  /* a force or position not finite, or a runaway
                            ** move (AFV_RUNAWAY_MOVE): afv_sim_bad_cell */

/* ---- 2. contact --------------------------------------------------------- */
/* A straight edge shorter than AFV_CONTACT_TOL l is geometry, not a
** contact: it stays in the boundary (areas and perimeters add up) but is
** not counted in afv_geom_contacts, the clusters or Omega.  (Two cells
** whose bisector meets a third's exactly on the circle share an edge of
** length 0 up to rounding, ~1e-16 l.)  Pinned (0) by test_core.c
** test_tiny_edge_is_no_contact and test_analysis.c omega_degenerate_vertex. */
#define AFV_CONTACT_TOL 1e-9

/* ---- 3. the cell's shape (geom.c) ---------------------------------------- */
/* gap_angle: two kept parts of a cell's boundary that meet on the circle
** may have a computed gap a hair below zero, which wraps around to a full
** turn; a gap within AFV_ANGLE_TOL (radians) of 2 pi between two distinct
** edges is taken as zero (a true gap that large would need every contact
** edge of the cell shorter than about 1e-12 l).  Pinned (0: 110 of 200000
** junctions on the circle gave A = 2 pi l^2) by test_geometry.c
** test_junction_on_the_circle. */
#define AFV_ANGLE_TOL 1e-12

/* clip_pairs and sliver_kept: two bisectors whose directions t_a, u_b have
** |t_a.u_b| below this are nearly parallel (they meet farther than about
** 1e6 |D| away), and are clipped by clip_near_parallel.  Pinned (0) by
** test_geometry.c test_near_pair_in_tissue, test_fuzz_cases and
** test_check_near_kinks. */
#define AFV_NEAR_PARALLEL 1e-6

/* clip_near_parallel: two nearly parallel neighbours whose displacements
** differ by AFV_NEAR_PARALLEL_GAP |D_a| or more have lines that meet 1e6 l
** away or farther: the nearer line hides the other.  Pinned (0: the
** nearer line hid a close one that meets it in the disk) by
** test_geometry.c test_near_parallel_lines_meet.  The other side (0.9,
** 2, 1e6: the e-form for every nearly parallel pair) changed none of
** 300000 random pairs 0.2..1.9 l and 1..1.9 times as far, 1e-6..1e-17
** radians apart (measured): the e-form's signs held there, and
** test_fuzz_cases passes at 1e6 too; a value that guards the rare case
** of clip_near_parallel, which no fixture reaches. */
#define AFV_NEAR_PARALLEL_GAP 1e-3

/* keep_parts: a part bounded by two junctions whose length came out
** negative by at most this times |tau0| + |tau1| is a sliver of length
** zero lost to rounding, not an empty part.  Pinned (-1: no sliver kept)
** by test_geometry.c test_fuzz_cases.  0 (only a length of exactly 0
** kept) cannot be pinned: in 400000 random cells between two centres
** 1e-6..1e-16 l away nearly in a row (and two more), it changed the
** forces of 1372 and no area, and only where the forces are rounding
** on both sides (1e13..1e33 where the true ones are O(1); total force 0
** to 1e-16 either way). */
#define AFV_SLIVER_ROUNDING (8 * DBL_EPSILON)

/* clip_pruned: a neighbour whose bisector lies farther than the cell's
** farthest vertex plus AFV_PRUNE_MARGIN l cannot cut the cell (the margin
** covers the rounding of the vertices, so pruning keeps the bits).
** Pinned (-1e-6: a corner cut 1e-7 l deep pruned away) by
** test_geometry.c test_prune_keeps_a_corner_cut; 0 passes the suite (it
** could differ only for a line within rounding of a vertex, whose edge,
** ~1e-16 l, is no contact). */
#define AFV_PRUNE_MARGIN 1e-9

/* ---- 4. the neighbour search (neighbours.c) ------------------------------ */
/* window_around and reanchor: a reach (the bins around a point) is widened
** by AFV_REACH_MARGIN l to cover the rounding of the positions it is
** computed from.  Pinned (-1e-6: a pair re-anchored 5e-7 l inside the
** reach (2 + SKIN) l missed) by test_perf.c test_mover_at_the_reach. */
#define AFV_REACH_MARGIN 1e-9

/* DENSE (geom.c, afv_reach_cuts): the dense search proposes a centre to
** cell i only if it cuts the cell the nearer ones leave deeper than
** AFV_CUT_DEPTH l; below that its bisector only touches the cell (every
** centre of a circle touches the others' cells at the circle's centre, to
** rounding), and what it would cut off is a sliver narrower than
** AFV_CUT_DEPTH l.  Pinned (-1e-9: 199 neighbours a cell on a circle of
** 200) by test_reference.c test_degenerate_shapes_match_clipped_polygons. */
#define AFV_CUT_DEPTH 1e-9

/* NEAR: two centres closer than AFV_NEAR_IMAGE times the longer box side
** take their displacement from the unwrapped centres (wrapping rounds a
** centre to a multiple of eps L); the relative error is then below
** eps / AFV_NEAR_IMAGE = 2.3e-10.  2^-20, exact.  Pinned (0) by
** test_core.c test_coincident_and_nonfinite and test_geometry.c
** test_pair_force_periodic, test_coincident_named, test_fuzz_cases. */
#define AFV_NEAR_IMAGE 9.5367431640625e-07

/* ---- 5. rounding, the parameters' range, the finite-difference check ----- */
/* The relative rounding of a sum of a few dozen rounded terms: a cell's
** area, perimeter or energy (afv.c, the finite-difference check's
** uncertainty; geom.c, the asserted bounds of a shape).  Pinned (0: the
** exact forces, checked with steps of 1e-10 l, resolved wrong by 3e-6
** of the tension scale) by test_geometry.c
** test_check_rounding_unresolved. */
#define AFV_SUM_ROUNDING (64 * DBL_EPSILON)

/* afv.c, check_component: a distance between two centres formed from
** coordinates of size R is rounded to AFV_COORD_ROUNDING R, and moves the
** energy by up to the force times that; a step of a few ulps of the
** coordinates (a pair one ulp from detaching) cannot resolve the force.
** Pinned (0) by test_geometry.c test_check_one_ulp_from_detaching. */
#define AFV_COORD_ROUNDING DBL_EPSILON

/* afv_params_check refuses parameters for which the largest energy of the
** tissue (every cell at its worst area and perimeter: afv.c,
** energy_bound) times AFV_PARAMS_HEADROOM overflows: the forces are the
** energy's terms times the shape's derivatives (a few l, a few
** neighbours) and must stay finite too.  afv eval and afv check name the
** key by the same bound.  Pinned (1) by test_core.c
** test_params_refuse_overflow and test_geometry.c
** test_eval_refuses_overflow. */
#define AFV_PARAMS_HEADROOM 1e6

/* afv.c, KINKS: the finite-difference step for a cell is at most
** 1/AFV_CHECK_KINK_STEPS of its distance to the nearest kink of the energy
** (a pair at d = 2l or d = 0): the extrapolated difference's error, about
** (step / distance)^4 times the force, is then 1e-8 of it.  Pinned (1)
** by test_geometry.c test_check_near_kinks and test_check_still_fails. */
#define AFV_CHECK_KINK_STEPS 100

/* afv.c, check_record: an error is resolved (a wrong force, which fails
** the check) when it exceeds AFV_CHECK_UNRESOLVED times the difference's
** own uncertainty (its two steps' disagreement and the rounding); within
** it, finite differences cannot tell (inconclusive).  Pinned (1e12) by
** test_geometry.c test_check_still_fails (a force 1e-3 off near
** detaching is resolved). */
#define AFV_CHECK_UNRESOLVED 2

/* ---- 6. dynamics and relaxation ------------------------------------------ */
/* afv_sim_step is the paper's Euler step, r_i += dt (mu F_i + v0_i n_i)
** with the exact force, for every cell, however far it moves.  Near a
** contact that breaks (Lambda > 0) the force diverges like
** (2l - d)^(-1/2), and a finite step is what carries a pair over that
** barrier: the results depend on dt (doc/reproduction/convergence.md).
** A step in which some cell moves farther than AFV_MAX_STEP_DISP l (the
** forces change on the scale l, so Euler's method no longer follows the
** continuous dynamics there) is a jump, counted (afv_sim_jumps), not
** refused.  Pinned (0.25 and 1) by test_dynamics.c
** test_jump_is_a_move_over_half_l (free cells moving 0.4 l and 0.6 l a
** step). */
#define AFV_MAX_STEP_DISP 0.5

/* afv_sim_step refuses a step only if a force or position is not finite, or
** if it would move a cell farther than AFV_RUNAWAY_MOVE l: no force of the
** model does that at sane parameters (the divergence at detachment is cut
** off by the spacing of doubles near 2l: |F| < 1e7 at the paper's
** parameters, a move of 1e5 l in dt = 0.01), but a modulus like KA =
** 1e100 does, and positions that far off no longer resolve l.  Pinned
** (1e30) by test_dynamics.c test_run_unstable_exit. */
#define AFV_RUNAWAY_MOVE 1e8

/* afv_relax's kink criterion (dynamics.c, KINKS), at the end of a window of
** AFV_RELAX_WINDOW steps: every cell's mean force over the window (its
** displacement / (window time mu)) is at most AFV_RELAX_KINK_DRIFT and at
** most AFV_RELAX_KINK_CHATTER max_i |F_i| (the forces cancel over the
** window: cells chatter across a kink, where the energy's slope jumps),
** the window's mean energy changed by at most AFV_RELAX_KINK_DROP
** sum_i |e_i| since the previous window, and max_i |F_i| <=
** AFV_RELAX_KINK_FORCE.  AFV_RELAX_KINK_FORCE is pinned (0) by
** test_dynamics.c test_relax_stops_at_kink and test_protocol.c
** test_protocol_reduced, test_run_relaxation_reports; the others on
** their strict side by test_relax_stops_at_kink (AFV_RELAX_KINK_DRIFT
** 1e-9, AFV_RELAX_KINK_DROP 1e-12, AFV_RELAX_WINDOW 100000: no stop at
** P0 6's kink) and AFV_RELAX_KINK_CHATTER on its loose side by
** test_relax_energy_never_increases (100: P0 4's smooth convergence
** stopped at 3000 steps as a kink, max |F| 1.5e-6).  Not pinned: DRIFT 1
** (the chatter test binds first everywhere the suite relaxes), CHATTER 1
** and 1e-4, DROP 1 and WINDOW 100 (these two stop P0 6 at 2000 and 600
** steps instead of 3000, E 2e-4 and 3.6e-4 of E higher; but the flow at
** that kink itself wanders 3.4e-4 of E below where it stops over 10000
** more steps, so no energy tells an early stop from a late one:
** measured). */
#define AFV_RELAX_WINDOW      1000
#define AFV_RELAX_KINK_DRIFT  1e-3   /* force units (KA l^3) */
#define AFV_RELAX_KINK_CHATTER 0.1
#define AFV_RELAX_KINK_DROP   1e-4
#define AFV_RELAX_KINK_FORCE  5.0    /* force units (KA l^3) */

/* afv_relax_fire (relax_fire.c): a cell moves at most AFV_FIRE_MAX_MOVE l
** in one step (the forces change on the scale l); the search has stalled
** when its lowest energy did not drop by AFV_FIRE_STALL_DROP |E| over
** AFV_FIRE_STALL iterations (a minimum within rounding, or a kink).
** AFV_FIRE_MAX_MOVE is pinned (10: moves of 4.3 l) by test_relax_fire.c
** fire_moves_capped, AFV_FIRE_STALL_DROP (0.5: a stop at iteration 2000,
** 2e-5 of E above the state FIRE goes on to) by
** fire_stalls_only_when_stuck. */
#define AFV_FIRE_MAX_MOVE   0.1
#define AFV_FIRE_STALL      1000
#define AFV_FIRE_STALL_DROP 1e-8

/* ---- 7. pictures (svg.c) --------------------------------------------------- */
/* draw_arc: an arc within AFV_FULL_CIRCLE_TOL (radians) of 2 pi is a full
** circle (an isolated cell), drawn as two half arcs (one SVG arc command
** cannot draw a whole circle).  Pinned (-1: the isolated cell not
** drawn; 1: arcs of 2 pi - 0.2 drawn as whole circles) by
** test_pictures.c draw_whole_and_nearly_whole_circles. */
#define AFV_FULL_CIRCLE_TOL 1e-9

/* A plotted range narrower than AFV_PLOT_SPAN_TOL (times |lo| + 1 on a
** line plot's axis; absolute for a phase map's colour scale) holds one
** value, and is widened around it.  Pinned (0: NaN axes; and the ticks
** of a range of rounding, 0.1 + 0.2 against 0.3, loop forever) by
** test_pictures.c plot_of_one_value (afv_svg_plot; afv_svg_map's colour
** scale uses the same constant). */
#define AFV_PLOT_SPAN_TOL 1e-12

/* A tick within AFV_PLOT_TICK_TOL of a step from zero is labelled 0, and
** the ticks run to the axis end plus that much of a step (the rounding of
** lo + k step).  Pinned (0: the middle tick of -0.4 .. 0.4 labelled
** -2.77556e-17) by test_pictures.c plot_ticks_symmetric. */
#define AFV_PLOT_TICK_TOL 1e-9

/* A drawn coordinate is printed to AFV_SVG_RESOLUTION l, or to
** AFV_SVG_RESOLUTION_PX pixels on a magnified picture, whichever is
** finer: far below what an eye or a renderer resolves, far above the
** doubles' rounding.  Pinned (AFV_SVG_RESOLUTION 1: 3 digits, a centre
** 4.6e-4 l off, on a picture 100 pixels wide) by test_pictures.c
** draw_coordinates_of_a_small_picture. */
#define AFV_SVG_RESOLUTION    1e-4
#define AFV_SVG_RESOLUTION_PX 0.01

#endif /* AFV_CONFIG_H */
