# The test list. Each scene asserts its own accuracy bounds (Verification
# section); reviewed statistics (<name>.output, compared with numdiff) pin
# the whole history where one exists.

find_package(Python3 REQUIRED COMPONENTS Interpreter)

# 1. Vibrating bar (1D): centre-of-mass velocity within 1.5% of v0 of the
#    exact mode over one period; energy within 2.5%.
mpm_test(vibrating_bar)
mpm_test(vibrating_bar_neohookean PRM vibrating_bar.prm
  ARGS -s "Bodies/Body 0/material=neo-Hookean"
       -s "Bodies/Body 0/neo-Hookean/Young's modulus=100"
       -s "Bodies/Body 0/neo-Hookean/Poisson's ratio=0")

# 2. Block settling under gravity: sigma_yy against -rho g (H - y0).
mpm_test(block_settling)
#    The damping's work (statistics column damping_work, with 'Simulation/
#    energy residual'): the block settles from rest, and the damping takes
#    out what gravity released less the strain energy stored, so that the
#    energy residual is the numerics' small share (reviewed: global damping
#    8.545 J taken out of 8.54, residual -0.59 % of the energy put in;
#    local damping 0.3 8.468 J, -1.2 %; before the grid's work was
#    accounted the residual held all of the damping's, -100 %).
mpm_test(block_settling_damping_work PRM block_settling.prm
  ARGS -s "Simulation/energy residual=true")
mpm_test(block_settling_local_damping_work PRM block_settling.prm
  ARGS -s "Simulation/energy residual=true" -s "Simulation/damping=0"
       -s "Simulation/local damping=0.3")
#    At h = 1/32 plain USL needs the small-mass guard to stay finite ...
mpm_test(block_settling_h32 PRM block_settling.prm
  ARGS -s "Grid/cells=32" -s "Verification/error bound=0.2")
#    ... and without it the run stops with a diagnosis, keeping the output
#    written before (also the test of the NaN / det F <= 0 class).
mpm_test(block_settling_h32_unguarded PRM block_settling.prm EXIT 2
  ARGS -s "Grid/cells=32" -s "Simulation/small mass fraction=0"
       -s "Output/interval=0.01"
  ERROR "run stopped: step [0-9]+, t = [0-9.e-]+: material point [0-9]+ of body 0 at \\([-0-9. e]+\\) (would invert: det|has a non-finite).*Output up to t = 0.0[1-9]"
  FILES statistics.csv particles.pvd particles_00001.pvtu)

# 3. Two disks (Sulsky 1994): momentum to round-off, bounded energy loss,
#    for each update scheme.
mpm_test(two_disks)
mpm_test(two_disks_usf PRM two_disks.prm
  ARGS -s "Simulation/update scheme=USF" -s "Verification/energy change bound=0.08")
mpm_test(two_disks_musl PRM two_disks.prm
  ARGS -s "Simulation/update scheme=MUSL" -s "Verification/energy change bound=0.1")

# 4. The same scene on 2 MPI ranks gives the 1-rank statistics.
mpm_test(two_disks_mpi2 PRM two_disks.prm NP 2 REFERENCE two_disks.output RELTOL 1e-7)
mpm_test(block_3d_mpi2 PRM block_3d.prm NP 2 REFERENCE block_3d.output RELTOL 1e-7)
mpm_test(two_disks_usf_mpi2 PRM two_disks.prm NP 2 REFERENCE two_disks_usf.output RELTOL 1e-7
  ARGS -s "Simulation/update scheme=USF" -s "Verification/energy change bound=0.08")

# 4b. Tiles ('Grid/cells per tile', the T^dim grid cells deal.II stores as
#     one cell) change where the points are stored, not the answer: 1, 2
#     and 4 (auto) cells per tile give the same history on 1 and 2 ranks.
#     The cubic B-spline reaches one node beyond its cell's neighbours:
#     across tiles of one cell and across ranks. F-bar averages J over
#     grid cells, not tiles.
mpm_test(two_disks_tile1 PRM two_disks.prm REFERENCE two_disks.output
  RELTOL 1e-7 ARGS -s "Grid/cells per tile=1")
mpm_test(two_disks_tile2_mpi2 PRM two_disks.prm NP 2
  REFERENCE two_disks.output RELTOL 1e-7 ARGS -s "Grid/cells per tile=2")
mpm_test(block_3d_cbs_tile1_mpi2 PRM block_3d.prm NP 2
  REFERENCE block_3d_cbs.output RELTOL 1e-7
  ARGS -s "Simulation/basis=cubic B-spline" -s "Grid/cells per tile=1")
mpm_test(block_3d_cbs_tile2 PRM block_3d.prm
  REFERENCE block_3d_cbs.output RELTOL 1e-7
  ARGS -s "Simulation/basis=cubic B-spline" -s "Grid/cells per tile=2")
mpm_test(nearly_incompressible_block_tile1
  PRM nearly_incompressible_block.prm
  REFERENCE nearly_incompressible_block.output RELTOL 1e-7
  ARGS -s "Grid/cells per tile=1")
#     Dynamic load balancing: a block thrown along a long grid. On 2 and 4
#     ranks (oversubscribed) the grid is repartitioned as it travels, no
#     step runs above the imbalance limit of 0.2 (measured 0.199 and 0.198;
#     without repartitioning 0.98 and 2.95), and the statistics equal the
#     1-rank run's. A restart of it on 2 ranks agrees to round-off (the
#     partition of the points as they are replaces the one the run had).
mpm_test(thrown_block)
foreach(np 2 4)
  add_test(NAME load_balance_mpi${np}
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/load_balance.py
      --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/thrown_block.prm
      --np ${np} --limit 0.2)
endforeach()
add_test(NAME checkpoint_restart_thrown_block_mpi2
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/thrown_block.prm
    --end-time 2.4 --np 2 --tolerance 1e-10)
mpm_test(bad_load_imbalance_limit PRM two_disks.prm EXIT 1
  ARGS -s "Grid/load imbalance limit=-1"
  ERROR "parameter 'Grid/load imbalance limit' = '-1'")
mpm_test(bad_cells_per_tile PRM two_disks.prm EXIT 1
  ARGS -s "Grid/cells per tile=3"
  ERROR "parameter 'Grid/cells per tile' = '3': must be 1, 2, 4, 8 or auto")
mpm_test(bad_cells_per_tile_divides PRM two_disks.prm EXIT 1
  ARGS -s "Grid/cells per tile=8"
  ERROR "parameter 'Grid/cells per tile' = '8': must divide 'Grid/cells' in every direction")

# 5. Bad input: one line naming the parameter and what is allowed.
set(base two_disks.prm)
mpm_test(bad_density PRM ${base} EXIT 1 ARGS -s "Bodies/Body 0/density=-1000"
  ERROR "input error: parameter 'Bodies/Body 0/density' = '-1000': must be > 0")
mpm_test(bad_youngs_modulus PRM ${base} EXIT 1
  ARGS -s "Bodies/Body 1/linear elastic/Young's modulus=-5"
  ERROR "parameter 'Bodies/Body 1/linear elastic/Young's modulus' = '-5': allowed range is .0, 1e.15.")
mpm_test(bad_poisson_ratio PRM ${base} EXIT 1
  ARGS -s "Bodies/Body 0/linear elastic/Poisson's ratio=0.5"
  ERROR "parameter 'Bodies/Body 0/linear elastic/Poisson's ratio' = '0.5': allowed range is \\(-1, 0.5\\)")
mpm_test(bad_body_outside_grid PRM ${base} EXIT 1
  ARGS -s "Bodies/Body 1/center=0.9"
  ERROR "parameters 'Bodies/Body 1/center', 'Bodies/Body 1/radius': the body spans .* it must lie inside the grid box")
mpm_test(bad_unknown_material PRM ${base} EXIT 1
  ARGS -s "Bodies/Body 0/material=granite"
  ERROR "input error: .*granite.*(linear elastic|pattern)")
mpm_test(bad_vector_length PRM ${base} EXIT 1 ARGS -s "Simulation/gravity=0, -9.81, 0"
  ERROR "parameter 'Simulation/gravity' = '0, -9.81, 0': expects 2 comma-separated values")
#    A misspelt parameter is named with the closest declared ones, from
#    -s or from the file (with its line), before deal.II's own words.
mpm_test(bad_unknown_parameter PRM ${base} EXIT 1 ARGS -s "Grid/cellz=3"
  ERROR "input error: parameter 'Grid/cellz' .option -s. is not declared; did you mean 'Grid/cells'")
mpm_test(bad_misspelt_parameter PRM misspelt.prm EXIT 1
  ERROR "input error: parameter 'Simulation/end tme' .line 4 of [^)]*misspelt.prm. is not declared; did you mean 'Simulation/end time'")
mpm_test(bad_malformed_file PRM malformed.prm EXIT 1
  ERROR "input error: .*[Ll]ine <?4>?")
mpm_test(bad_missing_file PRM does_not_exist.prm EXIT 1
  ERROR "input error: .*does_not_exist.prm")
mpm_test(bad_expression PRM ${base} EXIT 1
  ARGS -s "Bodies/Body 0/initial velocity=0.1*foo(x)"
  ERROR "parameter 'Bodies/Body 0/initial velocity' = '0.1\\*foo\\(x\\)[^']*': is not a valid expression .*foo")
mpm_test(bad_constants PRM ${base} EXIT 1 ARGS -s "Simulation/constants=G 3"
  ERROR "parameter 'Simulation/constants' = 'G 3': must be a comma-separated list of name=number")
mpm_test(bad_fixed_time_step PRM ${base} EXIT 1 ARGS -s "Simulation/time step=0.1"
  ERROR "parameter 'Simulation/time step' = '0.1.*exceeds the stability limit")
mpm_test(leaving_grid_stop PRM leaving_grid.prm EXIT 2
  ERROR "run stopped: material point [0-9]+ of body 0 left the grid at \\(1\\.0[0-9]* [0-9.]+\\)"
  FILES statistics.csv particles.pvd)
mpm_test(leaving_grid_remove PRM leaving_grid.prm ARGS -s "Simulation/out of grid=remove")

# 6. 3D block dropped in a box: reviewed statistics (and the optional grid
#    output is written next to the particles).
mpm_test(block_3d ARGS -s "Output/grid output=true"
  FILES particles.pvd grid.pvd grid_00006.pvtu timing.csv)

# The parameter reference, reviewed: a change to any name, default or
# documentation shows up here.
mpm_test(print_parameters ARGS --print-parameters STDOUT print_parameters.output)
mpm_test(help ARGS --help STDOUT help.output)

# Convergence (issue 3's coarse ladder, through the sweep tool): the 1D, 2D and 3D
# manufactured solution at small amplitude converges at second order with
# the linear basis; at large amplitude the linear basis fails cleanly (the
# error grows under refinement, every run finishes with finite numbers).
function(mpm_sweep_test name)
  add_test(NAME ${name}
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/sweep.py
      --exe $<TARGET_FILE:dealii-mpm> --ladder coarse --check ${ARGN})
endfunction()
mpm_sweep_test(mms_1d_order --problems mms_1d_small --configs linear:USL-FLIP,linear:MUSL-FLIP
  --min-order 1.8 --max-error 3e-7)
mpm_sweep_test(mms_1d_large_linear_fails_cleanly --problems mms_1d_large
  --configs linear:USL-FLIP --expect-growth)
mpm_sweep_test(mms_2d_3d_order --problems mms_2d_small,mms_3d_small
  --configs linear:USL-FLIP --min-order 1.8)

# 7. Bases and transfers (issue 4).
#    The settling block at h = 1/32 with every basis, for USL and USF: all
#    stable, sigma_yy within 0.065 rho g H (measured 0.055-0.060). With the
#    linear basis USF reaches 3.5 rho g H here; the smooth bases cure it.
#    The two disks with every basis: momentum to round-off, and the energy
#    lost through the impact (measured: uGIMP/cpGIMP 7.9%, quadratic 12.7%,
#    cubic 21%: the wider the stencil, the earlier and longer the disks
#    interact through the grid).
foreach(case "ugimp;uGIMP;0.1" "cpgimp;cpGIMP;0.1"
             "qbs;quadratic B-spline;0.15" "cbs;cubic B-spline;0.25")
  list(GET case 0 tag)
  list(GET case 1 basis)
  list(GET case 2 energy_bound)
  foreach(scheme USL USF)
    string(TOLOWER ${scheme} s)
    mpm_test(block_settling_h32_${tag}_${s} PRM block_settling.prm
      ARGS -s "Grid/cells=32" -s "Simulation/basis=${basis}"
           -s "Simulation/update scheme=${scheme}"
           -s "Verification/error bound=0.065")
  endforeach()
  mpm_test(two_disks_${tag} PRM two_disks.prm
    ARGS -s "Simulation/basis=${basis}"
         -s "Verification/energy change bound=${energy_bound}")
endforeach()
#    Stencils that reach the neighbouring cells across ranks: 2 ranks give
#    the 1-rank history (reviewed references), in 2D and 3D.
mpm_test(two_disks_qbs_mpi2 PRM two_disks.prm NP 2
  REFERENCE two_disks_qbs.output RELTOL 1e-7
  ARGS -s "Simulation/basis=quadratic B-spline"
       -s "Verification/energy change bound=0.15")
mpm_test(block_3d_cbs ARGS -s "Simulation/basis=cubic B-spline" PRM block_3d.prm)
mpm_test(block_3d_cbs_mpi2 PRM block_3d.prm NP 2
  REFERENCE block_3d_cbs.output RELTOL 1e-7
  ARGS -s "Simulation/basis=cubic B-spline")
mpm_test(two_disks_cpgimp_apic_mpi2 PRM two_disks.prm NP 2
  REFERENCE two_disks_cpgimp_apic.output RELTOL 1e-7
  ARGS -s "Simulation/basis=cpGIMP" -s "Simulation/transfer=APIC"
       -s "Simulation/update scheme=MUSL"
       -s "Verification/energy change bound=0.15")
#    APIC with every scheme conserves momentum (reviewed history on 1 rank).
mpm_test(two_disks_cpgimp_apic PRM two_disks.prm
  ARGS -s "Simulation/basis=cpGIMP" -s "Simulation/transfer=APIC"
       -s "Simulation/update scheme=MUSL"
       -s "Verification/energy change bound=0.15")
mpm_test(two_disks_linear_apic_usf PRM two_disks.prm
  ARGS -s "Simulation/transfer=APIC" -s "Simulation/update scheme=USF"
       -s "Verification/energy change bound=0.15")
#    The linear basis with APIC: a light node's force increment (growing as
#    1 / mass), or a massless node's absent velocity, no longer enters C_p
#    with the basis' full-size gradient. With outputs every 0.125 s (each
#    output shortens a step, and at t = 0.125 + k / 4 half the points lie
#    on node lines) every scheme gained 30 % energy and was stopped at
#    t = 1.125-1.25, before the disks touch; now none ever exceeds its
#    initial energy (measured: never above it, to round-off) under a guard
#    of 1e-6. The USF history on 1 and 2 ranks against a reviewed output:
#    free flight keeps the strain energy at round-off (before 5e-3 J).
foreach(s USL USF MUSL)
  mpm_test(two_disks_linear_apic_${s}_light_nodes PRM two_disks.prm
    ARGS -s "Simulation/transfer=APIC" -s "Simulation/update scheme=${s}"
         -s "Output/interval=0.125" -s "Verification/energy change bound=0"
         -s "Simulation/energy growth bound=1e-6")
endforeach()
#    The rule keeps uniform accelerations: a block falling freely (gravity
#    1 m/s^2, thrown at (0.3, 0.3) m/s, outputs every 0.0625 s) keeps its
#    strain energy at round-off (reviewed history: at most 2e-28 J) while
#    the light nodes at its edges are accelerated with it.
mpm_test(falling_block_linear_apic PRM thrown_block.prm
  ARGS -s "Simulation/basis=linear" -s "Simulation/transfer=APIC"
       -s "Simulation/update scheme=USF" -s "Simulation/gravity=0, -1"
       -s "Bodies/Body 0/initial velocity=0.3"
       -s "Simulation/end time=0.6" -s "Output/interval=0.0625"
       -s "Verification/momentum change bound=0")
mpm_test(two_disks_linear_apic_USF_light_nodes_mpi2 PRM two_disks.prm NP 2
  REFERENCE two_disks_linear_apic_USF_light_nodes.output RELTOL 1e-7
  ARGS -s "Simulation/transfer=APIC" -s "Simulation/update scheme=USF"
       -s "Output/interval=0.125" -s "Verification/energy change bound=0"
       -s "Simulation/energy growth bound=1e-6")
#    A body that starts displaced needs a material with a reference state.
mpm_test(bad_initial_displacement_material PRM block_settling.prm EXIT 1
  ARGS -s "Bodies/Body 0/initial displacement=0.01*x"
  ERROR "parameter 'Bodies/Body 0/initial displacement' = '0.01\\*x': needs a material whose stress follows from F")
mpm_test(bad_initial_displacement_inverts PRM block_settling.prm EXIT 1
  ARGS -s "Bodies/Body 0/material=neo-Hookean"
       -s "Bodies/Body 0/initial displacement=-2*x"
  ERROR "parameter 'Bodies/Body 0/initial displacement'.*det\\(I \\+ grad u0\\) = -1 <= 0")
#    A basis the grid cannot serve is an input error.
mpm_test(bad_cubic_bspline_grid PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/basis=cubic B-spline" -s "Grid/cells=1, 16"
  ERROR "parameter 'Simulation/basis' = 'cubic B-spline': needs at least 2 grid cells in every direction")
#    Convergence: second order for every smooth basis at small amplitude;
#    at large amplitude (cell crossing) cpGIMP keeps second order. In the
#    column, the smooth bases converge in stress while the linear basis
#    stops converging once the top cells are crossed (h = 1/64).
mpm_sweep_test(mms_1d_bases_order --problems mms_1d_small
  --configs uGIMP:USL-FLIP,cpGIMP:USL-FLIP,QBS:USL-FLIP,CBS:USL-FLIP,QBS:MUSL-APIC
  --min-order 1.8 --max-error 4e-7)
mpm_sweep_test(mms_1d_large_cpgimp_order --problems mms_1d_large
  --configs cpGIMP:USL-FLIP,cpGIMP:MUSL-FLIP --min-order 1.8 --max-error 1.2e-4)
mpm_sweep_test(mms_2d_bases_order --problems mms_2d_small
  --configs cpGIMP:USL-FLIP,QBS:MUSL-FLIP,CBS:USL-FLIP --min-order 1.8)
mpm_sweep_test(column_bases_converge --problems self_weight_column
  --configs uGIMP:USL-FLIP,QBS:USL-FLIP,CBS:USL-FLIP --cells 10,20,40,80
  --min-order 1.0 --max-error 3e-3)
#    The issue's phase-shifted axis-aligned MMS (the body starts displaced)
#    converges at second order at small amplitude.
mpm_sweep_test(mms_2d_phased_order --problems mms_2d_phased_small
  --configs linear:USL-FLIP,QBS:USL-FLIP --min-order 1.8)
mpm_sweep_test(column_linear_fails_cleanly --problems self_weight_column
  --configs linear:USL-FLIP --cells 40,80 --expect-growth)
#    The generalized vortex at A = 0.1 (large rotation, moderate shear)
#    converges at second order with the smooth bases (measured 2.5-2.6 from
#    h = 1/8 to 1/16); at A = 1 (shear strain 6) every configuration stops
#    cleanly near t = 0.4 with a point thrown out of the grid (numerical
#    fracture, see doc/verification.md), never a crash or a hang.
mpm_sweep_test(vortex_order --problems vortex
  --configs cpGIMP:USL-FLIP,QBS:MUSL-APIC --cells 24,48 --min-order 1.8 --max-error 1.1e-2)
mpm_test(vortex_large_stops_cleanly PRM ../benchmarks/verification/vortex.prm EXIT 2
  ARGS -s "Grid/cells=48" -s "Simulation/basis=quadratic B-spline"
  ERROR "run stopped: material point [0-9]+ of body 0 left the grid at .*Output up to t = 0.[34]"
  FILES statistics.csv particles.pvd)

# 8. Plasticity (issue 8). Single-point closed forms are in the unit test
#    constitutive_models. In the grid: the strip footing on a Tresca soil
#    (von Mises, plane strain) reaches Prandtl's bearing pressure
#    (2 + pi) c; at 5 cells across the half width the peak is 11% above it
#    (measured 5.71 c; 5.36 c, +4.3%, at 10 cells: see
#    benchmarks/plasticity/README.md).
#    Issue 29's audit of velocity regions under shear: the scene's FLIP
#    0.95, APIC and FLIP with a PIC relaxation time of 1 s give the same
#    peak within 2 % (measured 5.682, 5.689, 5.658: 0.54 %), and the energy
#    residual (the region's work against strain energy, plastic work and
#    kinetic energy) is within 2 % of the work put in (measured -0.91,
#    -0.69, -1.23 %).
#    Release only: against deal.II's debug library this run takes over 6
#    minutes; the Debug suite checks the same code paths (footing, velocity
#    region, plasticity) through footing_mohr_coulomb below.
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME strip_footing_prandtl
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/plasticity/strip_footing.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 5 --end-time 2.6 --check --max-error 0.13
      --transfers scene,APIC,relaxation --max-residual 0.02)
  # Issue 9: the footing as a rigid body (the region's box, pushed at the
  # same speed, rough contact) gives the region's peak (measured -2.3 % at
  # B/10, -0.3 % at B/20; -0.7 % and -0.1 % with the small-mass guard on
  # the smooth bases' strain rate, taken off by issue 30).
  # Issue 33: softening in a shear band (a Tresca specimen in unconfined
  # compression, benchmarks/plasticity/softening_band.*), at h = 0.1 and
  # 0.05 m: the peak is 2 c (-3 % measured); the platen's slip from the
  # peak to half the drop shrinks like h with local softening (0.0113 ->
  # 0.0060 m, ratio 0.53) and does not with 'shear band thickness' 0.1 m
  # (0.0113 -> 0.0149, 1.32: it grows instead); with a nonlocal length of
  # 0.2 m it stays (0.0171 -> 0.0163, 0.95; 0.0157 at 0.025 m, the ladder
  # converges), so the check fails for local softening or the band's
  # scaling in its place. Release only (about 70 s).
  add_test(NAME softening_band_regularised
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/plasticity/softening_band.py
      --exe $<TARGET_FILE:dealii-mpm> --ladder 0.1,0.05 --end-time 1.2 --check)
  add_test(NAME strip_footing_rigid_body
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/plasticity/strip_footing.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 5 --end-time 2.6 --footing both
      --check --max-error 0.13 --max-difference 0.03)
  # The footing pushed by a rigid body with pure FLIP (no dissipation of
  # the transfer's own), beside the region, to t = 2.6 s: the energy
  # residual stays within 10 % of the work (USL; measured: region -2.0 %,
  # rigid body -6.3 %) and 15 % (MUSL; -1.9 %, -10.0 %). The contact
  # normal at the footing's corner on the symmetry face must lie in the
  # face (GridFaces::keep_contact_normals_in_faces): without it a soil
  # point trapped under the corner was pumped to 8.6 m/s, the residual
  # read -34 % with USL and MUSL stopped on the energy guard at t = 0.4 s.
  # MUSL's strain-rate velocities do no work (counted there, the rigid
  # footing with pure FLIP and MUSL read -18.4 % at t = 2.6 s; with FLIP
  # 0.95 -59 % at 0.7 s before the normal's fix).
  foreach(scheme USL MUSL)
    if(scheme STREQUAL "USL")
      set(bound 0.1)
    else()
      set(bound 0.15)
    endif()
    add_test(NAME strip_footing_energy_balance_${scheme}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/plasticity/strip_footing.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 5 --end-time 2.6 --footing both
        --transfers FLIP --max-residual ${bound} --check --max-error 0.13
        --max-difference 0.03 -s "Simulation/update scheme=${scheme}")
  endforeach()
endif()
#    A plastic body must start inside its yield surface.
mpm_test(bad_initial_stress_outside_yield PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Bodies/Body 0/initial stress=-1e5*(x>2)" -s "Grid/cells=10,7"
  ERROR "parameter 'Bodies/Body 0/initial stress' = '-1e5\\*\\(x>2\\)[^']*': the stress .* at \\(2.* lies outside the yield surface .* of 'von Mises'")
mpm_test(bad_initial_stress_neo_hookean PRM block_settling.prm EXIT 1
  ARGS -s "Bodies/Body 0/material=neo-Hookean" -s "Bodies/Body 0/initial stress=-1"
  ERROR "parameter 'Bodies/Body 0/initial stress' = '-1': 'neo-Hookean' takes its stress from F alone")
mpm_test(bad_dilation_angle PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Bodies/Body 0/material=Mohr-Coulomb" -s "Bodies/Body 0/Mohr-Coulomb/dilation angle=40"
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/dilation angle' = '40': allowed range is \\[0, 30\\]")
#    A stiffness beyond 1e15 Pa is a typo: the energies overflow (issue
#    32, class 4; test material_range_ends runs every model at the ends of
#    every range).
mpm_test(bad_youngs_modulus_huge PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Bodies/Body 0/von Mises/Young's modulus=1e300"
  ERROR "parameter 'Bodies/Body 0/von Mises/Young's modulus' = '1e300': allowed range is .0, 1e.15.")
#    Mohr-Coulomb with softening under the footing: a reviewed history
#    (energies, momentum, region force), and 2 ranks reproduce it (the
#    region force is summed over ranks).
set(footing_mc ARGS -s "Grid/cells=20,14" -s "Simulation/end time=0.5"
  -s "Output/interval=0.1"
  -s "Bodies/Body 0/material=Mohr-Coulomb"
  -s "Bodies/Body 0/Mohr-Coulomb/Young's modulus=1e7"
  -s "Bodies/Body 0/Mohr-Coulomb/cohesion=1e4"
  -s "Bodies/Body 0/Mohr-Coulomb/softening=linear"
  -s "Bodies/Body 0/Mohr-Coulomb/residual cohesion=5e3"
  -s "Bodies/Body 0/Mohr-Coulomb/residual friction angle=20")
mpm_test(footing_mohr_coulomb PRM ../benchmarks/plasticity/strip_footing.prm ${footing_mc})
mpm_test(bad_shear_band_thickness PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ${footing_mc} -s "Bodies/Body 0/Mohr-Coulomb/shear band thickness=0"
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/shear band thickness' = '0': must be 'local' or a thickness in m, > 0")
#    Inertial rate strengthening (mu(I)) names what it lacks, and does not
#    combine with softening.
mpm_test(bad_rate_strengthening_with_softening PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ${footing_mc} -s "Bodies/Body 0/Mohr-Coulomb/rate strengthening=inertial"
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/rate strengthening' = 'inertial': cannot be combined with softening = linear")
mpm_test(bad_rate_strengthening_without_diameter PRM ../benchmarks/granular/bui2008.prm EXIT 1
  ARGS -s "Bodies/Body 0/Mohr-Coulomb/rate strengthening=inertial"
  -s "Bodies/Body 0/Mohr-Coulomb/grain diameter="
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/grain diameter' = '': is needed with rate strengthening = inertial: a diameter in m, > 0")
mpm_test(bad_dynamic_friction_angle PRM ../benchmarks/granular/bui2008.prm EXIT 1
  ARGS -s "Bodies/Body 0/Mohr-Coulomb/rate strengthening=inertial"
  -s "Bodies/Body 0/Mohr-Coulomb/dynamic friction angle=15"
  -s "Bodies/Body 0/Mohr-Coulomb/grain diameter=1e-3"
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/dynamic friction angle' = '15': allowed range is .19.8, 90.")
mpm_test(footing_mohr_coulomb_mpi2 PRM ../benchmarks/plasticity/strip_footing.prm NP 2
  REFERENCE footing_mohr_coulomb.output RELTOL 1e-7 ${footing_mc})
#    The same with nonlocal softening (over-nonlocal, l = 0.5 m, two
#    cells): a reviewed history, and 2 ranks reproduce it, so the average's
#    halo brings every neighbour from the other rank and the decision to
#    average again is the same on both.
set(footing_mc_nonlocal ${footing_mc}
  -s "Bodies/Body 0/Mohr-Coulomb/nonlocal length=0.5")
mpm_test(footing_mohr_coulomb_nonlocal PRM ../benchmarks/plasticity/strip_footing.prm
  ${footing_mc_nonlocal})
mpm_test(footing_mohr_coulomb_nonlocal_mpi2 PRM ../benchmarks/plasticity/strip_footing.prm NP 2
  REFERENCE footing_mohr_coulomb_nonlocal.output RELTOL 1e-7 ${footing_mc_nonlocal})
#    A nonlocal length needs softening, excludes the band's scaling, and
#    its factor is at least 1.
mpm_test(bad_nonlocal_softening_without_softening PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ${footing_mc} -s "Bodies/Body 0/Mohr-Coulomb/softening=none"
  -s "Bodies/Body 0/Mohr-Coulomb/nonlocal length=0.5"
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/nonlocal length' = '0.5': averages the softening's plastic strain: it needs softening = linear")
mpm_test(bad_nonlocal_softening_with_band PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ${footing_mc_nonlocal} -s "Bodies/Body 0/Mohr-Coulomb/shear band thickness=0.5"
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/nonlocal length' = '0.5': cannot be combined with a shear band thickness")
mpm_test(bad_nonlocal_factor PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ${footing_mc_nonlocal} -s "Bodies/Body 0/Mohr-Coulomb/nonlocal factor=0.5"
  ERROR "parameter 'Bodies/Body 0/Mohr-Coulomb/nonlocal factor' = '0.5': must be >= 1")
#    Bad values of the new parameters name the parameter.
mpm_test(bad_velocity_region PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Boundary conditions/Velocity region/velocity=0, fast"
  ERROR "parameter 'Boundary conditions/Velocity region/velocity' = '0, fast': each entry must be a number or 'free'")
mpm_test(bad_tension_cutoff PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Bodies/Body 0/material=Drucker-Prager" -s "Bodies/Body 0/Drucker-Prager/tension cutoff=-5"
  ERROR "parameter 'Bodies/Body 0/Drucker-Prager/tension cutoff' = '-5': must be >= 0")

# 9. Bodies from a mesh file and the closed-form shapes (the shapes
#    themselves, their errors, and mesh seeds against exact cell areas:
#    body_shapes).
#    A reviewed history starting with the exact mass; 2 ranks reproduce it.
mpm_test(mesh_bodies)
mpm_test(mesh_bodies_mpi2 PRM mesh_bodies.prm NP 2 REFERENCE mesh_bodies.output RELTOL 1e-7)
#    'mesh points = grid' (issue 33): the same bodies seeded on the grid's
#    lattice of 2 x 2 points per cell, whatever the mesh's own cells (147
#    points, mass 3656.25, 0.9 % under the cells' exact 3688.17: the
#    lattice's counting error at the boundary, half a spacing wide; the
#    lattice itself is checked against the cells' areas in body_shapes).
#    The history is reviewed: it falls as the Gauss-point bodies do
#    (kinetic energy 1828.1 at 0.1 s against 1844.1, in proportion to the
#    mass) until the floor.
mpm_test(mesh_bodies_grid PRM mesh_bodies.prm
  ARGS -s "Bodies/Body 0/mesh points=grid" -s "Bodies/Body 1/mesh points=grid"
       -s "Bodies/Body 1/particles per cell=2")
#    Gauss points coarser than the grid are told so, with the remedy.
mpm_test(mesh_bodies_sparse_warns PRM mesh_bodies.prm
  ARGS -s "Bodies/Body 0/particles per cell=1" -s "Grid/cells=48"
       -s "Simulation/end time=0.001"
  OUTPUT "warning: Bodies/Body 0 has 12 points for the about 248 grid cells its mesh covers .fewer than one per cell: the body is coarser than the grid.; set its 'mesh points' = grid, or raise 'particles per cell'")
#    A pressure on mesh faces needs the Gauss points the faces belong to.
mpm_test(bad_mesh_pressure_on_grid PRM ../benchmarks/plasticity/thick_cylinder.prm EXIT 1
  ARGS -s "Bodies/Body 0/mesh points=grid"
  ERROR "parameter 'Bodies/Body 0/pressure boundary ids' = '10': needs 'mesh points' = Gauss points")
mpm_test(bad_mesh_file PRM mesh_bodies.prm EXIT 1
  ARGS -s "Bodies/Body 1/mesh file=meshes/missing.msh"
  ERROR "parameter 'Bodies/Body 1/mesh file' = '.*tests/meshes/missing.msh': cannot be opened for reading")
mpm_test(bad_mesh_material_id PRM mesh_bodies.prm EXIT 1
  ARGS -s "Bodies/Body 0/mesh material ids=1, x"
  ERROR "parameter 'Bodies/Body 0/mesh material ids' = '1, x': must be a comma-separated list of whole numbers")
mpm_test(bad_mesh_gauss_order PRM mesh_bodies.prm EXIT 1
  ARGS -s "Bodies/Body 1/particles per cell=5"
  ERROR "parameter 'Bodies/Body 1/particles per cell' = '5': deal.II has no Gauss rule of this order on the mesh's Tri cells")

# 10. Validation scenes of the plasticity issue, coarse (the ladders are in
#     benchmarks/, with their numbers in the READMEs there).
#     Taylor bar (3D, von Mises with hardening, quarter cylinder): final
#     length and footprint radius against the finite-element reference
#     (21.4-21.6 mm, 7.0 mm); at 4 cells across the radius 21.66 mm and
#     6.51 mm, at 8 cells 21.51 mm and 6.97 mm. Release only (3D quadratic
#     B-splines against deal.II's debug library take minutes); the Debug
#     suite runs its first 10 us against a reviewed history.
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME taylor_bar
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/impact/taylor_bar.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 4 --check
      --length-tolerance 0.3 --footprint-tolerance 0.6)
endif()
mpm_test(taylor_bar_impact PRM ../benchmarks/impact/taylor_bar.prm
  ARGS -s "Simulation/end time=1e-5" -s "Output/interval=2.5e-6")
#    Thick-walled cylinder under internal pressure (von Mises, plane strain,
#    quasi-static with damping): the outer displacement against Hill's
#    closed form up to 0.8 p_L, within 2 % of the displacement at first
#    yield (measured: 0.5 % with MUSL, 1.0 % with USL). Release only (30,000 steps).
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME thick_cylinder
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/plasticity/thick_cylinder.py
      --exe $<TARGET_FILE:dealii-mpm> --up-to 0.8 --check --max-error 0.02)
endif()
#    Granular column collapse (Mohr-Coulomb, a = 1, friction floor, the
#    shipped numerics: MUSL, quadratic B-spline, FLIP with a PIC relaxation
#    time of 0.1 s) against the channel laws: the 99 % front within their
#    envelope (0.96-1.44 at a = 1) and the deposit at rest. Measured at 16
#    cells across the column: 1.317 (furthest point 1.449, deposit 1.198;
#    at CFL 0.25 1.341), kinetic energy left 3.9e-6 of the released; at 8
#    cells (the Debug build) 1.065. 2 ranks reproduce the APIC history to
#    1e-7 (friction faces and Mohr-Coulomb in parallel); FLIP's history is
#    not a reference for that: the ranks' different sums grow by 10-50
#    times each 0.1 s of the flow.
if(CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(column_cells 8)
else()
  set(column_cells 16)
endif()
add_test(NAME column_collapse
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/column_collapse.py
    --exe $<TARGET_FILE:dealii-mpm> --aspect 1 --cells ${column_cells} --check)
set(column ARGS -s "Grid/upper corner=0.6, 0.25" -s "Grid/cells=24, 10"
  -s "Simulation/end time=1" -s "Output/interval=0.1")
mpm_test(column_collapse_mpi2 PRM ../benchmarks/granular/column_collapse.prm NP 2
  REFERENCE column_collapse_apic.output RELTOL 1e-7 ${column}
  -s "Simulation/transfer=APIC" -s "Simulation/PIC relaxation time=0")
#    Where bodies reach (reviewed): the wedge's deposit edge 0.775 (exact
#    0.75, the edge of the outermost point of the last column 0.05 thick),
#    the strip's 99 % front 0.9941 (the last column of points holds more than
#    1 % of them), the boxes as before. The third body, a wall with two
#    sheets one point thick reaching out from its foot and its top, has its
#    deposit edge at the wall, 0.05: a column's thickness is the volume of
#    its points over its width (0.025 beyond the wall), not their span
#    (0.3, which gave 1). A deposit front needs gravity.
mpm_test(body_fronts)
#    A deposit counts its grains, not the gaps between them: a cohesionless
#    wedge spread along x to twice its length at zero stress keeps its
#    points' heights, and its grains are 0.05 deep at x = 1.0 (edge read
#    1.046), where counted with the points' volume (all of it opening)
#    the edge read about 1.55 (tests/deposit_of_parted_grains.prm).
mpm_test(deposit_of_parted_grains)
mpm_test(bad_front_thickness PRM free_expansion.prm EXIT 1
  ARGS -s "Output/body extents=true" -s "Output/front thickness=0.01"
  ERROR "parameter 'Output/front thickness' = '0.01': needs 'Simulation/gravity' along one axis of the grid")
mpm_test(bad_front_percentile PRM body_fronts.prm EXIT 1
  ARGS -s "Output/front percentile=20"
  ERROR "parameter 'Output/front percentile' = '20': .*50")
#    APIC's affine velocity moves with the material: a cohesionless block
#    thrown apart with no stress spreads ballistically, J = (1 + a t)^2,
#    with every basis and scheme (median J within 1e-3; measured 0 with
#    USL, below 5e-5 with MUSL; 2e-3 to 1e-2 before).
add_test(NAME free_expansion
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/free_expansion.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/free_expansion.prm)
#    A sheared cohesionless layer on a Coulomb floor (4 cells across): the
#    floor takes mu times the weight while it slides (deceleration within
#    2 % of mu g; measured 0.3 %), and APIC keeps the shear it kept when
#    reviewed (difference between its halves at t = 0.04 s in
#    [0.24, 0.30] m/s; measured 0.282 and 0.291; FLIP 0.99: 0.009, its PIC
#    share's viscosity). A guard on APIC, not the continuum's value: FLIP
#    with a PIC relaxation time converges to 0.315 at 16 cells, and APIC
#    moves towards it as h falls (0.27 at 16 cells).
foreach(basis "quadratic B-spline" "cubic B-spline")
  string(REPLACE " " "_" tag "${basis}")
  add_test(NAME sheared_layer_${tag}
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 4 --check -s "Simulation/basis=${basis}")
endforeach()
#    Friction faces audited under a sheared layer (issue 29): with either
#    recommended transfer and every smooth basis, on 1, 2 and 4 cells
#    across, the floor takes mu times the weight while the layer slides
#    (deceleration within 2 % of mu g; measured within 0.4 % in all 18
#    runs). On a face inclined at 10 degrees (below atan mu = 16.7) the
#    layer decelerates at g (mu cos - sin) and comes to rest (kinetic
#    energy below 1e-3 of the initial; measured 1e-7 to 1.4e-4), FLIP with
#    the relaxation time on 1 and 2 cells. On a rigid wall with the same
#    friction (penalty contact, two cells above a slip floor) the wall's
#    tangential force is mu times its normal force over t = 0.02-0.1 s
#    (within 2 %; measured to 1e-12 with both transfers and every smooth
#    basis: every point in contact slides) and the deceleration within 5 %
#    of mu g (measured -2.6 % to +3.6 %: the layer also settles on the
#    penalty, which the force ratio does not see). APIC fails the inclined case
#    today: a front point skates down the face and is torn apart (J > 1000
#    at t = 0.2-0.4 s on 1, 2 and 4 cells; benchmarks/granular/README.md).
#    Release only (12-25 s each).
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  foreach(basis "quadratic B-spline" "cubic B-spline" "cpGIMP")
    string(REPLACE " " "_" tag "${basis}")
    add_test(NAME sheared_layer_friction_apic_${tag}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 1,2,4 --shear none --check
        -s "Simulation/basis=${basis}")
    add_test(NAME sheared_layer_friction_flip_${tag}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 1,2,4 --shear none --check
        -s "Simulation/basis=${basis}" -s "Simulation/transfer=FLIP"
        -s "Simulation/PIC relaxation time=0.1")
    add_test(NAME sheared_layer_rigid_wall_apic_${tag}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 1,2,4 --rigid-wall --shear none
        --check -s "Simulation/basis=${basis}")
    add_test(NAME sheared_layer_rigid_wall_flip_${tag}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 1,2,4 --rigid-wall --shear none
        --check -s "Simulation/basis=${basis}" -s "Simulation/transfer=FLIP"
        -s "Simulation/PIC relaxation time=0.1")
    add_test(NAME sheared_layer_incline_flip_${tag}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 1,2 --incline 10 --check
        -s "Simulation/basis=${basis}" -s "Simulation/transfer=FLIP"
        -s "Simulation/PIC relaxation time=0.1")
    # APIC too, since a parted point alone near the face gives up its
    # affine field along the face's normal (session 37): deceleration
    # within 0.8 % on 1, 2 and 4 cells, kinetic energy left 1e-10 to
    # 7e-9. Before, the front point was torn apart (J > 1000) on every
    # basis and grid.
    add_test(NAME sheared_layer_incline_apic_${tag}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 1,2 --incline 10 --check
        -s "Simulation/basis=${basis}" -s "Simulation/transfer=APIC")
  endforeach()
endif()
#    The friction face's work (statistics column face_friction_work, with
#    'Simulation/energy residual'; issue 29 item 2, issue 33 item 4).
#    A layer sliding as one at 1 m/s: the face's work is mu M g times the
#    slip within 2 % and the energy residual (the numerics' share, now
#    without the faces' work) at most 1 % of the energy put in (measured:
#    FLIP with the relaxation time -0.75/-0.52/-0.51 % and residual -0.15
#    to -0.02 % on 1/2/4 cells; APIC -1.3/-0.8 % and -0.6/-0.3 % on 2/4
#    cells. On 1 cell APIC's face takes 2.9 % too little: the floor's
#    friction gives the bottom points a shear C_xy, and their affine field
#    brings the floor nodes less than the points' slip; not asserted).
#    The sheared layer (4 cells, FLIP with the relaxation time, each smooth
#    basis): the face's work by t = 0.12 s within 3 % of 0.630 J, where
#    every transfer and basis converges (8 cells: FLIP 0.630-0.631, APIC
#    0.606-0.622; measured here +1.2 to +2.1 %), and a residual of at most
#    2 % (measured -1.3 to -0.9 %). APIC falls 3-10 % short at 4 cells and
#    10-38 % at 1-2 (benchmarks/granular/README.md). Release only (9 s
#    each).
#    APIC's energy is that of the points' affine fields v_p + C_p (x - x_p):
#    the energy residual counts 1/2 m_p D_p : C_p C_p (column
#    affine_kinetic_energy), and the transfer then only takes energy out.
#    The sheared layer on 1 and 2 cells: residual <= 0 (measured -1.5 %
#    and -0.6 % of the energy put in; +11.8 % and +4.7 % without the
#    affine part, the initial shear's energy that E(0) did not count).
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME sheared_layer_apic_energy
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 1,2 --shear none --max-residual 0
      --check)
  add_test(NAME face_friction_work_slide_apic
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 2,4 --rigid --shear none
      --friction-work slip --max-residual 0.01 --check)
  add_test(NAME face_friction_work_slide_flip
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 1,2,4 --rigid --shear none
      --friction-work slip --max-residual 0.01 --check
      -s "Simulation/transfer=FLIP" -s "Simulation/PIC relaxation time=0.1")
  foreach(basis "quadratic B-spline" "cubic B-spline" "cpGIMP")
    string(REPLACE " " "_" tag "${basis}")
    add_test(NAME face_friction_work_sheared_flip_${tag}
      COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
        --exe $<TARGET_FILE:dealii-mpm> --cells 4 --shear none
        --friction-work 0.630,0.03 --max-residual 0.02 --check
        -s "Simulation/basis=${basis}" -s "Simulation/transfer=FLIP"
        -s "Simulation/PIC relaxation time=0.1")
  endforeach()
endif()
#    The same layer at two CFL numbers with FLIP and a PIC relaxation
#    time: the damping is a rate, so the shear the layer keeps does not
#    depend on the time step (measured: within 0.0015 m/s at CFL 0.5 and
#    0.125; allowed 0.01). With 'FLIP fraction = 0.999', a share per step,
#    the smaller step takes the shear out three times faster (0.253 against
#    0.110 m/s at t = 0.04 s) and this test fails.
#    Release only (12 s; the Debug build takes 10 minutes).
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME sheared_layer_pic_relaxation_cfl
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/sheared_layer.py
      --exe $<TARGET_FILE:dealii-mpm> --cells 4 --cfl 0.5,0.125 --check
      -s "Simulation/transfer=FLIP" -s "Simulation/PIC relaxation time=0.1")
endif()
#    A lone point dropped on a friction face (issue 29; the slope runout's
#    point that kept bouncing ahead of the deposit): with MUSL and USF its
#    strain rate sees the floor hold the nodes its stress pushed into it,
#    so the stress relaxes as it leaves the floor, and the bodies' energy
#    and the energy residual stay within 10 % of the energy put in
#    (measured 0 and 0.033 at most; the run stops otherwise). Before, the
#    floor threw the point off with a stress that never relaxed: the runs
#    stopped at t = 0.9 and 0.85 s with 13 % and 9 % more energy than the
#    point started with. USL already held them (its strain rate comes from
#    the force update's velocities).
#    The same on a rigid body's field (Contact): the runs stopped at
#    t = 0.7 s with 4 % and 7 % more energy than the point started with.
foreach(scheme MUSL USF)
  mpm_test(lone_point_bounce_${scheme} PRM lone_point_bounce.prm
    ARGS -s "Simulation/update scheme=${scheme}"
    OUTPUT "Finished [0-9]+ steps to t = 4 ")
  mpm_test(lone_point_bounce_rigid_${scheme} PRM lone_point_bounce_rigid.prm
    ARGS -s "Simulation/update scheme=${scheme}"
    OUTPUT "Finished [0-9]+ steps to t = 4 ")
endforeach()
#    The collapse of a column of aluminium rods (Bui et al. 2008; MUSL,
#    FLIP with a PIC relaxation time of 0.1 s, quadratic B-spline, the rods'
#    mu(I) rate strengthening, h = 5 mm): the toe (where the deposit is a
#    rod, 1.5 mm, thick) within 0.42-0.50 m, as issue 29 asks (measured
#    0.44-0.46; here 0.470, and 0.460, 0.464 at 2.5, 1.25 mm; without the
#    rate strengthening 0.495 at this h, still inside the bound, and 0.52
#    at 1.25 mm, outside it: at 5 mm this is a guard of the scene, and the
#    ladder in benchmarks/granular/README.md is the validation), the
#    column's top kept at 0.100 m next to the wall over
#    0.01-0.06 m (measured about 0.03; here 0.020), at rest. Release only
#    (25 s).
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME bui2008_collapse
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/granular/bui2008.py
      --exe $<TARGET_FILE:dealii-mpm> --h 0.005 --check)
endif()
#    A rigid wall moving at 10 m/s (and 100 m/s) into the two disks: the
#    time step counts the wall's speed (reviewed history: dt <= 0.5 h /
#    (c + |v| + 10 m/s) = 2.2e-3 s, cut to the outputs; the wall moves at
#    most 0.44 of a cell per step; it moved two cells per step before), and
#    no point falls more than a quarter of its size behind it (issue 32,
#    class 2): body0_x_min >= wall - 0.00625 at every output (the wall is at
#    -0.01 + v t; before, the points fell 2.7 cm behind at 10 m/s). The
#    front layer the wall sweeps moves with it: momentum 37.1 (374.6) kg m/s,
#    kinetic energy 190 (18,753) J, which the wall's work accounts for (the
#    energy guard, bound 0.25, lets the runs finish).
foreach(speed 10 100)
  if(speed EQUAL 10)
    set(times -s "Simulation/end time=0.005" -s "Output/interval=0.001")
    set(name rigid_wall_fast)
  else()
    set(times -s "Simulation/end time=0.0005" -s "Output/interval=0.0001")
    set(name rigid_wall_very_fast)
  endif()
  mpm_test(${name} PRM two_disks.prm
    ARGS -s "Boundary conditions/number of rigid walls=1"
         -s "Boundary conditions/Rigid wall 0/point=-0.01, 0"
         -s "Boundary conditions/Rigid wall 0/normal=1, 0"
         -s "Boundary conditions/Rigid wall 0/velocity=${speed}, 0"
         ${times} -s "Output/body extents=true"
         -s "Verification/energy change bound=1e9"
         -s "Verification/momentum change bound=1e9")
endforeach()
#    A grid too small for the arithmetic is an input error naming its
#    extent (the fuzzer's Taylor bar with 'Grid/upper corner = 1e-308' had
#    subnormal cells and failed in an eigensolver naming nothing; issue 32).
mpm_test(bad_grid_subnormal_cells PRM ../benchmarks/impact/taylor_bar.prm EXIT 1
  ARGS -s "Grid/upper corner=1e-308"
  ERROR "parameter 'Grid/upper corner' = '1e-308': with 'Grid/lower corner' and 'Grid/cells' gives cells [0-9.e-]+ m wide in direction 0: a cell must be at least 1e-50 m")
#    Two rigid walls closing on the disks at 10 m/s each, ten times their
#    wave speed: they push the disks together and meet at x = 0.5 at
#    t = 0.051. A point put back by one wall is then behind the other; the
#    walls are tried in turn per point (a corner settles so), and a point
#    still behind after that is pinched: the run stops naming it and keeps
#    the output of t = 0.05 (issue 32). Before, both disks were packed into
#    a sheet, the walls passed through each other and the run finished
#    with exit 0.
mpm_test(rigid_walls_pinch PRM two_disks.prm EXIT 2
  ARGS -s "Boundary conditions/number of rigid walls=2"
       -s "Boundary conditions/Rigid wall 0/point=-0.01, 0"
       -s "Boundary conditions/Rigid wall 0/normal=1, 0"
       -s "Boundary conditions/Rigid wall 0/velocity=10, 0"
       -s "Boundary conditions/Rigid wall 1/point=1.01, 0"
       -s "Boundary conditions/Rigid wall 1/normal=-1, 0"
       -s "Boundary conditions/Rigid wall 1/velocity=-10, 0"
       -s "Simulation/end time=0.06" -s "Output/interval=0.005"
       -s "Verification/energy change bound=1e9"
       -s "Verification/momentum change bound=1e9"
  ERROR "run stopped: step [0-9]+, t = 0.05[01][0-9]*: material point [0-9]+ of body [01] at \\(0.49[0-9]* [0-9.]+\\) is pinched between rigid walls.*Output up to t = 0.05 "
  FILES particles_00010.pvtu)
#    So does a rigid body's prescribed speed, before its points have it
#    (they start at 'initial velocity'): the second disk made rigid and
#    driven at (-10, -10) m/s (one value for both) takes a first step of 0.5 h / (c + 14.14 m/s)
#    = 1.63e-3 s (reviewed; before, 3e-3 s, cut only by the end time).
mpm_test(rigid_body_fast PRM two_disks.prm
  ARGS -s "Bodies/Body 1/rigid velocity=-10"
       -s "Simulation/end time=0.003" -s "Output/interval=0"
       -s "Verification/energy change bound=1e9"
       -s "Verification/momentum change bound=1e9")
#    A message shows a vector as given, not expanded to its components.
mpm_test(bad_rigid_velocity_commas PRM two_disks.prm EXIT 1
  ARGS -s "Bodies/Body 1/rigid velocity=-10, -10"
  ERROR "parameter 'Bodies/Body 1/rigid velocity' = '-10, -10': has a ',' outside parentheses")
#    A velocity region counts in the time step from the first step, before
#    the points it drives have its speed (reviewed history of the first
#    steps: dt = CFL h / (c + 100 m/s) = 0.04 / (116.0 + 100) = 1.85e-4 s
#    against 3.45e-4 s before).
mpm_test(velocity_region_fast PRM ../benchmarks/plasticity/strip_footing.prm
  ARGS -s "Boundary conditions/Velocity region/velocity=0, -100"
       -s "Simulation/end time=1e-3" -s "Output/interval=0")
#    A frictional body with FLIP's PIC share per step is told at the start
#    that the share shortens granular runouts and depends on the step
#    (benchmarks/granular/README.md); with 'PIC relaxation time' (the
#    shipped scene) it is quiet, as the other granular tests show.
mpm_test(column_collapse_flip_warns PRM ../benchmarks/granular/column_collapse.prm
  ARGS -s "Simulation/PIC relaxation time=0" -s "Simulation/FLIP fraction=0.999"
       -s "Simulation/end time=0.01"
  OUTPUT "warning: body 0 is frictional .Mohr-Coulomb. and the transfer is FLIP with a PIC share of 0.001 per step: it acts on shear bands like a viscosity that does not shrink with the grid and grows as the step shrinks")
#    A cohesionless body
#    with APIC on a fixed or friction face is told that its parted points
#    slide along the face undamped (issue 29: in the Bui collapse at
#    h = 2.5 mm a sheet of them ran to the end of the grid).
mpm_test(bui2008_apic_warns PRM ../benchmarks/granular/bui2008.prm
  ARGS -s "Simulation/transfer=APIC" -s "Simulation/PIC relaxation time=0"
       -s "Simulation/end time=1e-4"
  OUTPUT "warning: body 0 is cohesionless .Mohr-Coulomb. and the transfer is APIC with 'Grid/boundary y min' = fixed: points that part carry their shear")
#    Friction floor (Coulomb): a sliding block decelerates at mu g and stops
#    after v0^2 / (2 mu g), both within 2 % (measured: 1e-4 and 5e-4).
add_test(NAME sliding_block_friction
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/sliding_block.py
    --exe $<TARGET_FILE:dealii-mpm> --mu 0.3 --check --max-error 0.02)
#    A pressure needs loaded mesh faces.
mpm_test(bad_pressure_without_surface PRM two_disks.prm EXIT 1
  ARGS -s "Bodies/Body 0/pressure=1e5"
  ERROR "parameter 'Bodies/Body 0/pressure' = '1e5': needs a loaded surface: 'loaded surface' for a shape, 'pressure boundary ids' for a mesh")
mpm_test(bad_friction_coefficient PRM two_disks.prm EXIT 1
  ARGS -s "Grid/friction coefficient=-0.1"
  ERROR "parameter 'Grid/friction coefficient' = '-0.1': must be >= 0")
#    Rigid wall at 30 and 45 degrees to the grid (penalty on the points,
#    Coulomb stick spring): a sliding block accelerates at
#    g (sin theta - mu cos theta) within 2 % (measured with PIC: -8e-5 and
#    1.4e-4), and at mu = 0.7 it sticks: less than 0.1 mm of slide over the
#    last 0.2 s (measured 0.000 mm, the wall carrying the weight to 1e-4).
add_test(NAME inclined_plane_rigid_wall
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/inclined_plane.py
    --exe $<TARGET_FILE:dealii-mpm> --cases 30/0.3,30/0.7,45/0.5 --check --max-error 0.02
    --max-slide-mm 0.1)
mpm_test(bad_wall_normal PRM ../benchmarks/contact/inclined_plane.prm EXIT 1
  ARGS -s "Boundary conditions/Rigid wall 0/normal=0, 0"
  ERROR "parameter 'Boundary conditions/Rigid wall 0/normal' = '0, 0': must be a non-zero, finite vector")
#    The rigid wall's history (the lattice-filled block dropping onto the
#    plane and sliding), and 2 ranks reproduce it (wall force summed over
#    ranks).
set(wall ARGS -s "Simulation/end time=0.2" -s "Output/interval=0.05")
mpm_test(rigid_wall PRM ../benchmarks/contact/inclined_plane.prm ${wall})
mpm_test(rigid_wall_mpi2 PRM ../benchmarks/contact/inclined_plane.prm NP 2
  REFERENCE rigid_wall.output RELTOL 1e-7 ${wall})
#    Messages show the value as given, and a number is judged by its value
#    (issue 32, class 7): a normal of tiny components is the same
#    direction (before: "must be numbers" below 1e-308, "must be a
#    non-zero vector" below 1e-154; the history is the wall's to 1e-12;
#    subnormal components are accepted but carry few digits), a modulus beyond the doubles is out of range (before: "must
#    be a number"), an empty velocity region names both corners (before:
#    "upper corner = ''").
mpm_test(rigid_wall_subnormal_normal PRM ../benchmarks/contact/inclined_plane.prm
  REFERENCE rigid_wall.output RELTOL 1e-12 ${wall}
  -s "Boundary conditions/Rigid wall 0/normal=0.5e-300, 0.8660254037844386e-300")
mpm_test(bad_youngs_modulus_overflow PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Bodies/Body 0/von Mises/Young's modulus=1e400"
  ERROR "parameter 'Bodies/Body 0/von Mises/Young's modulus' = '1e400': allowed range is .0, 1e.15.")
mpm_test(bad_velocity_region_no_node PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Boundary conditions/Velocity region/lower corner=10, 10"
       -s "Boundary conditions/Velocity region/upper corner=11, 11"
  ERROR "parameter 'Boundary conditions/Velocity region/upper corner' = '11, 11': with 'lower corner' = '10, 10' the box holds no grid node")

# 12. Surface loads at the points (issue 9): a column under a top pressure
#     and its weight against sigma_yy = -p0 - rho g (H - y0) (linear basis,
#     measured 0.032; uGIMP 0.020), the same load given as a pressure, and
#     2 ranks reproduce the 1-rank history. A traction on points picked by
#     an expression: momentum_x = 25 t exactly (reviewed).
mpm_test(loaded_column)
mpm_test(loaded_column_mpi2 PRM loaded_column.prm NP 2
  REFERENCE loaded_column.output RELTOL 1e-7)
mpm_test(loaded_column_pressure_ugimp PRM loaded_column.prm
  ARGS -s "Bodies/Body 0/traction=0" -s "Bodies/Body 0/pressure=p0"
       -s "Simulation/basis=uGIMP" -s "Verification/error bound=0.025")
#    The quadratic B-spline takes the load's weights at the surface itself
#    (to first order its node beyond the surface was out of balance and
#    FLIP runs grew until the energy guard stopped them): MUSL measured
#    0.028, every scheme and transfer 0.028-0.064 (combinations.py).
mpm_test(loaded_column_qbs PRM loaded_column.prm
  ARGS -s "Simulation/basis=quadratic B-spline" -s "Simulation/update scheme=MUSL"
       -s "Verification/error bound=0.035")
mpm_test(traction_expression)
mpm_test(bad_loaded_surface_empty PRM traction_expression.prm EXIT 1
  ARGS -s "Bodies/Body 0/loaded surface=x > 0.7"
  ERROR "parameter 'Bodies/Body 0/loaded surface' = 'x > 0.7': no material point of the body lies on its loaded surface")
mpm_test(bad_pressure_on_expression_surface PRM traction_expression.prm EXIT 1
  ARGS -s "Bodies/Body 0/pressure=100"
  ERROR "parameter 'Bodies/Body 0/pressure' = '100': needs a surface with a normal")
mpm_test(bad_loaded_face PRM traction_expression.prm EXIT 1
  ARGS -s "Bodies/Body 0/loaded surface=z max"
  ERROR "parameter 'Bodies/Body 0/loaded surface' = 'z max': names an axis this 2D scene does not have")

# 13. Absorbing faces (issue 9): a pulse that meets Lysmer-Kuhlemeyer
#     dashpots leaves less than 5 % of its energy behind (measured: 1D bar
#     0.08 %; 2D square, waves at every angle: s-wave 0.22 %, p-wave
#     0.01 %), while fixed or slip faces keep 42-92 % of it. The 2D square
#     is Release only (30 s against deal.II's debug library).
set(absorbing_cases bar)
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(absorbing_cases bar,square_s,square_p)
endif()
add_test(NAME absorbing_faces
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/boundaries/absorbing_faces.py
    --exe $<TARGET_FILE:dealii-mpm> --cases ${absorbing_cases} --check --max-reflection 0.05)
mpm_test(bad_absorbing_body PRM ../benchmarks/boundaries/absorbing_bar.prm EXIT 1
  ARGS -s "Grid/absorbing body=1"
  ERROR "parameter 'Grid/absorbing body' = '1': must be the index of a body, < 1")
#     The dashpots act on owned nodes only: 2 ranks reproduce the 1-rank
#     history (reviewed, coarse square).
set(absorbing_coarse ARGS -s "Grid/cells=32" -s "Simulation/end time=0.04"
  -s "Output/interval=0.01")
mpm_test(absorbing_square PRM ../benchmarks/boundaries/absorbing_square.prm ${absorbing_coarse})
mpm_test(absorbing_square_mpi2 PRM ../benchmarks/boundaries/absorbing_square.prm NP 2
  REFERENCE absorbing_square.output RELTOL 1e-7 ${absorbing_coarse})

# 14. Virtual fluid, the virtual stress method (issue 9). A floating block
#     rests at the draft H rho_s / rho_f (measured +0.06 %; uGIMP +0.08 %;
#     quadratic B-spline at 16 cells +0.50 %, 7.3 % with a looser mask)
#     and a submerged block carries the hydrostatic stress (RMS error 3.6 %
#     at 16 cells, first order); a uniform virtual pressure on the column
#     gives sigma_yy = -p0 - rho g (H - y) (measured 0.020, quadratic
#     B-spline 0.022); 2 ranks reproduce the floating block's history.
#     (Debug: linear only; the pair takes 95 s against the debug library.)
set(buoyancy_configs "32:linear,16:quadratic B-spline")
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(buoyancy_configs "32:linear,32:uGIMP,16:quadratic B-spline")
endif()
add_test(NAME buoyancy
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/boundaries/buoyancy.py
    --exe $<TARGET_FILE:dealii-mpm> --configs ${buoyancy_configs} --check --max-error 0.02,0.05)
set(virtual_pressure -s "Bodies/Body 0/traction=0"
  -s "Boundary conditions/Virtual fluid/enabled=true"
  -s "Boundary conditions/Virtual fluid/density=0"
  -s "Boundary conditions/Virtual fluid/pressure=p0")
mpm_test(virtual_fluid_pressure PRM loaded_column.prm
  ARGS ${virtual_pressure} -s "Verification/error bound=0.025")
mpm_test(virtual_fluid_pressure_qbs PRM loaded_column.prm
  ARGS ${virtual_pressure} -s "Simulation/basis=quadratic B-spline"
       -s "Verification/error bound=0.03")
set(floating_coarse ARGS -s "Grid/cells=16" -s "Simulation/end time=0.5")
mpm_test(floating_block PRM ../benchmarks/boundaries/floating_block.prm ${floating_coarse})
mpm_test(floating_block_mpi2 PRM ../benchmarks/boundaries/floating_block.prm NP 2
  REFERENCE floating_block.output RELTOL 1e-7 ${floating_coarse})
mpm_test(bad_fluid_bodies PRM ../benchmarks/boundaries/floating_block.prm EXIT 1
  ARGS -s "Boundary conditions/Virtual fluid/bodies=0, 1"
  ERROR "parameter 'Boundary conditions/Virtual fluid/bodies' = '0, 1': must be comma-separated body indices in .0, 1.")

# 15. Multi-body contact and rigid bodies (issue 9). Two disks with a field
#     each: momentum to round-off, they never overlap (closest points 1.35
#     spacings apart), separate, and keep more energy than with one field
#     (0.914 against 0.889); a reviewed history on 1 and 2 ranks.
add_test(NAME two_disks_contact_check
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/two_disks_contact.py
    --exe $<TARGET_FILE:dealii-mpm> --check --min-gap 0.9)
#     MUSL takes the strain rate from velocities transferred after the
#     force update: where the disks pressed on each other there, the fields
#     stay together at the strain rate's velocities too. Without it the
#     disks gained energy as they parted (uGIMP, FLIP 1: 1.075 of the
#     initial energy against 1.004 with one field; PIC: 0.975 against
#     0.570); now 1.000 and 0.577. USF, whose strain rate comes before its
#     force update, tries one with the stress the step starts from to find
#     where they press (before: 1.088 and 1.001 against 1.027 and 0.630;
#     now 1.018 and 0.610).
function(two_disks_energy_test name scheme flip_fraction excess)
  add_test(NAME ${name}
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/two_disks_contact.py
      --exe $<TARGET_FILE:dealii-mpm> --check --min-gap 0.9
      --max-over-single ${excess} -s "Simulation/basis=uGIMP"
      -s "Simulation/update scheme=${scheme}"
      -s "Simulation/FLIP fraction=${flip_fraction}")
endfunction()
two_disks_energy_test(two_disks_contact_musl MUSL 1 0.01)
two_disks_energy_test(two_disks_contact_musl_pic MUSL 0 0.02)
two_disks_energy_test(two_disks_contact_usf USF 1 0.01)
two_disks_energy_test(two_disks_contact_usf_pic USF 0 0.02)
#     Their histories on 1 and 2 ranks.
foreach(scheme MUSL USF)
  string(TOLOWER ${scheme} s)
  set(two_disks_contact_${s} ARGS -s "Contact/bodies=0, 1"
    -s "Simulation/update scheme=${scheme}" -s "Simulation/basis=uGIMP"
    -s "Verification/energy change bound=0.15")
  mpm_test(two_disks_contact_${s}_history PRM two_disks.prm ${two_disks_contact_${s}})
  mpm_test(two_disks_contact_${s}_mpi2 PRM two_disks.prm NP 2
    REFERENCE two_disks_contact_${s}_history.output RELTOL 1e-7
    ${two_disks_contact_${s}})
endforeach()
set(two_disks_contact ARGS -s "Contact/bodies=0, 1"
  -s "Verification/energy change bound=0.15")
mpm_test(two_disks_contact PRM two_disks.prm ${two_disks_contact})
mpm_test(two_disks_contact_mpi2 PRM two_disks.prm NP 2
  REFERENCE two_disks_contact.output RELTOL 1e-7 ${two_disks_contact})
#     Where one disk's field is light at a node (only the edge of its
#     stencils reaches it) the fields do not part along the normal: with
#     the linear basis and APIC the light field's velocity grew as 1 / mass
#     where the disks parted, and they gained up to 86 % energy. Now the
#     energy guard, at 1 % of the energy put in, lets the run finish
#     (measured: at most 1.000 of the initial energy, 0.894 at the end).
mpm_test(two_disks_contact_apic_linear PRM two_disks.prm
  ARGS -s "Contact/bodies=0, 1" -s "Simulation/transfer=APIC"
       -s "Output/interval=0.05" -s "Verification/energy change bound=0"
       -s "Simulation/energy growth bound=0.01")
#     A disk on a rigid incline: frictionless it slides at g sin(theta)
#     (measured 3e-6), at mu = 0.1 at g (sin - mu cos) (1.4e-4); with
#     mu = 1 it rolls at (2/3) g sin(theta) within 3 % at 20 cells across
#     the radius (measured -1.5 %; -19 % at 10, -68 % at 5: the stuck
#     patch, see benchmarks/contact/README.md). Rolling is Release only.
set(rolling_cases --mu 0,0.1 --cells 5 --max-error 0.01 -s "Simulation/end time=0.2")
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(rolling_cases --mu 0,0.1 --cells 10 --max-error 0.01)
  add_test(NAME rolling_disk_stick
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/rolling_disk.py
      --exe $<TARGET_FILE:dealii-mpm> --check --mu 1 --cells 20 --max-error 0.03)
endif()
#     With the energy residual, the contact's work (column contact_work):
#     frictionless it does none (measured 0.001 J), at mu = 0.1 it is mu N
#     times the slip of the disk's contact point within 2 % (measured
#     -0.3 % at 5 and 10 cells across the radius), and the residual is
#     within 1 % (measured -0.07 % to -0.02 %). The disk slides without
#     turning (omega below 0.02 rad/s where it should reach 6.8 rad/s at
#     t = 0.4 s): the contact's nodes make a flat under it (below).
add_test(NAME rolling_disk
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/rolling_disk.py
    --exe $<TARGET_FILE:dealii-mpm> --check --friction-work ${rolling_cases})
#     Friction's torque (issue 29): a disk sliding at mu = 0.1 spins up at
#     2 mu g cos(theta) / R. On a rigid wall (friction on the points) a disk
#     seeded round from a mesh (disk_mesh.py, 32 core cells) does, within
#     15 % (measured -10.9 %; its centre's acceleration -0.1 %); seeded on
#     the lattice its flat bottom row holds it (-89 %), and on the grid's
#     friction face or a rigid body (on the nodes) it does not turn at all
#     (-100 %): benchmarks/contact/README.md, "Friction's torque". The
#     program warns of both flats.
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME spinning_disk_wall
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/spinning_disk.py
      --exe $<TARGET_FILE:dealii-mpm> --check --seeding 32 --cells 5
      --max-error 0.02 --max-spin-error 0.15)
endif()
mpm_test(spinning_disk_lattice_warns PRM ../benchmarks/contact/spinning_disk.prm
  ARGS -s "Simulation/end time=0.001"
  OUTPUT "warning: body 0 is round .radius 0.1. and seeded on the grid's lattice, whose bottom row is a flat of up to 0.0447214 either side of its lowest point, wider than mu R = 0.01 of a rigid wall's friction")
mpm_test(rolling_disk_nodes_warn PRM ../benchmarks/contact/rolling_disk.prm
  ARGS -s "Simulation/end time=0.001" -s "Contact/friction coefficient=0.1"
  OUTPUT "warning: body 0 is round .radius 0.1. and its friction .contact with a rigid body, mu = 0.1. acts at the grid's nodes: every node its stencils reach holds it, a flat of about 0.0707107 either side of its lowest point, wider than mu R = 0.01")
#     A prescribed body's density does not change what it does (issue 32,
#     class 8): the disk slides on floors of density 1000, 1 and 1e-300 with
#     the same acceleration to 1e-9 (before: 4.056, 4.060 and 4.905 m/s^2,
#     the light floor moving the small-mass guard's threshold and the
#     lightest one no longer acting).
#     (Debug: two of the densities, 70 s instead of 100.)
set(floor_densities 1000,1,1e-300)
if(CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(floor_densities 1,1e-300)
endif()
add_test(NAME rolling_disk_floor_density
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/rolling_disk.py
    --exe $<TARGET_FILE:dealii-mpm> --check --mu 0.1 --cells 5 --max-error 0.01
    -s "Simulation/end time=0.2" --floor-density ${floor_densities})
mpm_test(bad_contact_bodies PRM two_disks.prm EXIT 1
  ARGS -s "Contact/bodies=0, 2"
  ERROR "parameter 'Contact/bodies' = '0, 2': must be comma-separated body indices in .0, 2.")
mpm_test(bad_rigid_velocity PRM two_disks.prm EXIT 1
  ARGS -s "Bodies/Body 1/rigid velocity=0.1*foo"
  ERROR "parameter 'Bodies/Body 1/rigid velocity' = '0.1\\*foo[^']*': is not a valid expression")
#     A rigid body on 2 ranks: the rolling disk's history (its floor is
#     rigid, its force summed over ranks) is the 1-rank one.
set(rolling_coarse ARGS -s "Simulation/end time=0.1" -s "Output/interval=0.025"
  -s "Contact/friction coefficient=1")
mpm_test(rolling_disk_history PRM ../benchmarks/contact/rolling_disk.prm ${rolling_coarse})
mpm_test(rolling_disk_history_mpi2 PRM ../benchmarks/contact/rolling_disk.prm NP 2
  REFERENCE rolling_disk_history.output RELTOL 1e-7 ${rolling_coarse})
#     Several rigid walls: a disk at rest in a notch of two walls at +-45
#     degrees loads each with (-+ m g / 2, -m g / 2) (measured to 1.4e-7);
#     with friction on both (a stick spring per wall) the split is
#     indeterminate and the walls' sum carries m g (measured to 1e-7).
add_test(NAME v_notch_walls
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/v_notch.py
    --exe $<TARGET_FILE:dealii-mpm> --check --max-error 0.01)
#     cpGIMP with USF: the domains follow F, which the stress update
#     changes before the forces: mass, momentum and force now come from the
#     same stencils (before, a node that a grown domain reached got a force
#     and almost no mass, and a point was thrown out of the grid; measured
#     1.9e-5 of m g / 2 now).
add_test(NAME v_notch_walls_cpgimp_usf
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/v_notch.py
    --exe $<TARGET_FILE:dealii-mpm> --check --max-error 0.01
    -s "Simulation/basis=cpGIMP" -s "Simulation/update scheme=USF")
add_test(NAME v_notch_walls_friction
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/v_notch.py
    --exe $<TARGET_FILE:dealii-mpm> --check --max-error 0.01 --sum-only
    -s "Boundary conditions/Rigid wall 0/friction coefficient=0.3"
    -s "Boundary conditions/Rigid wall 1/friction coefficient=0.5")
#     Sticking through grid contact: a block on a rigid floor body at 30
#     degrees with mu = 0.7 stays put (0.0000 mm after 0.5 s) and the floor
#     carries m g (sin, cos) to 1e-5 (PIC; with FLIP 0.99 it ratchets 36 mm
#     down in 0.5 s, which the check also tells apart).
add_test(NAME sticking_block_contact
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/contact/sticking_block.py
    --exe $<TARGET_FILE:dealii-mpm> --check --max-slide-mm 0.1 --max-error 0.01)

# 16. Quasi-static helpers (issue 11): the settling column reaches its
#     static stress (error <= 0.08 to the end) in 72 steps with Cundall's
#     local damping (alpha 0.8) and 74 with it and mass scaling 100, against
#     279 with the shipped global damping.
add_test(NAME quasi_static_helpers
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/quasi_static.py
    --exe $<TARGET_FILE:dealii-mpm> --check)
mpm_test(bad_local_damping PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/local damping=1"
  ERROR "parameter 'Simulation/local damping' = '1': allowed range is .0, 1.")
mpm_test(bad_mass_scaling PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/mass scaling=0.5"
  ERROR "parameter 'Simulation/mass scaling' = '0.5': .*1")

# 16. Constitutive library II (issue 10). Single points: test
#     viscous_and_damage_models. In the grid: Glen's law (a slab on an
#     incline from rest to the steady profile, within 5 % at 8 cells across;
#     1.6 % measured), the Newtonian fluid (a hydrostatic column keeps
#     rho g (H - y) within 2 %; the dam break front within 10 % of Martin
#     and Moyce at every measurement).
add_test(NAME glen_slab
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/glaciology/glen_slab.py
    --exe $<TARGET_FILE:dealii-mpm> --cells 8 --check --max-error 0.05)
add_test(NAME fluid_hydrostatic
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/fluids/fluids.py
    --exe $<TARGET_FILE:dealii-mpm> --cases hydrostatic --cells 16 --check --max-error 0.02,0.1)
# A fluid so soft that its weight halves its volume at the bottom keeps the
# Tait fluid's equilibrium pressure within 2 % (0.05 % measured at 16 cells);
# the time step counts the stiffening under pressure, K + gamma p (issue 32,
# class 3: with K alone the column blew up within 16 steps).
add_test(NAME fluid_soft_column
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/fluids/fluids.py
    --exe $<TARGET_FILE:dealii-mpm> --cases soft_column --cells 16 --check --max-error 0.02,0.1)
set(dam_break_cells 8)
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(dam_break_cells 8,16)
endif()
add_test(NAME dam_break
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/fluids/fluids.py
    --exe $<TARGET_FILE:dealii-mpm> --cases dam_break --cells ${dam_break_cells} --check --max-error 0.02,0.1)
#     Damage: in a bar torn by a tensile wave the dissipated energy falls
#     with h with local damage (halves per halving) and converges with a
#     nonlocal length (the two finest of 128, 256, 512 cells within 10 %;
#     2.9 % measured); the nonlocal average reaches across MPI ranks through
#     a halo wider than the ghost layer (a 2-rank strip gives the 1-rank
#     history; without the halo its kinetic energy is 2 % off).
add_test(NAME damage_bar
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/damage/damage_bar.py
    --exe $<TARGET_FILE:dealii-mpm> --cells 128,256,512 --check)
mpm_test(damage_strip_nonlocal)
mpm_test(damage_strip_nonlocal_mpi2 PRM damage_strip_nonlocal.prm NP 2
  REFERENCE damage_strip_nonlocal.output RELTOL 1e-7)
set(damage "Bodies/Body 0/Hencky elastic/Damage")
mpm_test(bad_failure_strain PRM damage_strip_nonlocal.prm EXIT 1
  ARGS -s "${damage}/failure strain=1e-4"
  ERROR "parameter 'Bodies/Body 0/Hencky elastic/Damage/failure strain' = '1e-4': must be > 0.0001")
mpm_test(bad_nonlocal_length PRM damage_strip_nonlocal.prm EXIT 1
  ARGS -s "${damage}/nonlocal length=-1"
  ERROR "parameter 'Bodies/Body 0/Hencky elastic/Damage/nonlocal length' = '-1': must be >= 0")
mpm_test(bad_glen_exponent PRM ../benchmarks/glaciology/glen_slab.prm EXIT 1
  ARGS -s "Bodies/Body 1/Maxwell viscoelastic/Glen exponent=0.5"
  ERROR "parameter 'Bodies/Body 1/Maxwell viscoelastic/Glen exponent' = '0.5': allowed range is .1, 10.")
mpm_test(bad_fluid_bulk_modulus PRM ../benchmarks/fluids/hydrostatic_column.prm EXIT 1
  ARGS -s "Bodies/Body 0/Newtonian fluid/bulk modulus=0"
  ERROR "parameter 'Bodies/Body 0/Newtonian fluid/bulk modulus' = '0': allowed range is .0, 1e.15.")
mpm_test(bad_fluid_shear_stress PRM ../benchmarks/fluids/hydrostatic_column.prm EXIT 1
  ARGS -s "Bodies/Body 0/initial stress=-1000"
  ERROR "parameter 'Bodies/Body 0/initial stress'.*carries shear stress, which is not a state at rest of 'Newtonian fluid'")
# Initial states the material cannot carry are input errors that name the
# initial stress and the stiffness (issue 32, class 3): before, the first
# step stopped blaming the CFL number, and the soft ice wrote an infinite
# strain energy to statistics.csv.
mpm_test(bad_initial_stress_soft_ice PRM ../benchmarks/glaciology/calving.prm EXIT 1
  ARGS -s "Bodies/Body 0/Maxwell viscoelastic/Young's modulus=1"
  ERROR "parameter 'Bodies/Body 0/initial stress' = 'rho.g.\\(y-H\\)[^']*': the stress .* gives 'Maxwell viscoelastic' a strain energy of inf: the stress is too large for its stiffness, 'Bodies/Body 0/Maxwell viscoelastic/Young's modulus' = '1'")
mpm_test(bad_initial_stress_soft_fluid PRM ../benchmarks/fluids/dam_break.prm EXIT 1
  ARGS -s "Bodies/Body 0/Newtonian fluid/bulk modulus=1e-20"
  ERROR "parameter 'Bodies/Body 0/initial stress'.* gives 'Newtonian fluid' a volume ratio J = V / V0 = 0.000323.*, outside 'Simulation/J bounds' .0.001, 1000.: the stress is too large for its stiffness, 'Bodies/Body 0/Newtonian fluid/bulk modulus' = '1e-20'")

# 17. Reliability (issue 12, part). Output survives a kill (frames written
#     aside and moved in complete; the .pvd lists only complete frames); a
#     new run replaces an earlier run's frames, or refuses by parameter; an
#     output directory that cannot be made stops every rank with one line.
add_test(NAME output_robustness
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/output_robustness.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/two_disks.prm)
mpm_test(bad_output_directory_mpi2 PRM two_disks.prm NP 2 EXIT 1
  ARGS -s "Output/directory=/dev/null"
  ERROR "parameter 'Output/directory' = '/dev/null': cannot be created or written")
#     Bad inputs that were accepted silently or crashed, one line each.
mpm_test(bad_scene_directory PRM meshes EXIT 1
  ERROR "input error: scene '.*meshes' is a directory, not a scene file")
mpm_test(bad_scene_empty PRM empty.prm EXIT 1
  ERROR "input error: scene file '.*empty.prm' is empty: nothing to simulate")
mpm_test(bad_duplicate_parameter PRM duplicate_parameter.prm EXIT 1
  ERROR "parameter 'Simulation/end time' is written twice \\(line 4 of [^ ]*duplicate_parameter.prm and line 5 of [^ ]*duplicate_parameter.prm\\): the second would silently win")
mpm_test(bad_duplicate_section PRM duplicate_section.prm EXIT 1
  ERROR "section 'Simulation' is written twice \\(line 2 of [^ ]*duplicate_section.prm and line 5 of [^ ]*duplicate_section.prm\\)")
#    'include' works as deal.II reads it (relative to the directory the
#    program runs in); the scene's checks follow it, and a file it names
#    that is not there is said so, not "no section 'Bodies/Body 0'".
mpm_test(bad_include_missing PRM include_missing.prm EXIT 1
  ERROR "input error: scene file 'no_such_body.prm' does not exist .an 'include' names it; it is read relative to the directory the program runs in.")
mpm_test(bad_missing_body PRM two_disks.prm EXIT 1 ARGS -s "Bodies/number of bodies=3"
  ERROR "parameter 'Bodies/number of bodies' = '3': but the scene has no section 'Bodies/Body 2'")
mpm_test(bad_constant_pi PRM two_disks.prm EXIT 1 ARGS -s "Simulation/constants=a=1, pi=3"
  ERROR "parameter 'Simulation/constants' = 'a=1, pi=3': defines 'pi' again")
mpm_test(bad_empty_vector PRM two_disks.prm EXIT 1 ARGS -s "Simulation/gravity="
  ERROR "parameter 'Simulation/gravity' = '': is empty: give 2 comma-separated numbers")
mpm_test(bad_huge_corner PRM two_disks.prm EXIT 1 ARGS -s "Grid/upper corner=1e308"
  ERROR "parameter 'Grid/upper corner' = '1e308': must be finite numbers of magnitude up to 1e15")
mpm_test(bad_grid_too_large PRM two_disks.prm EXIT 1 ARGS -s "Grid/cells=100000"
  ERROR "parameter 'Grid/cells' = '100000': 1e.10 cells need about .* GB for the grid")
#     Checkpoint and restart: restarted at T/2 the run equals the
#     uninterrupted one bit for bit (1 and 2 ranks), to round-off on another
#     rank count (2 -> 1), and after random SIGKILLs (inside checkpoints
#     too), each followed by a restart, still bit for bit.
set(restart_cells 80)
if(CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(restart_cells 40)
endif()
set(restart_scene --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/two_disks.prm
  --end-time 3 -s "Grid/cells=${restart_cells}" -s "Verification/energy change bound=0")
#     A restart continues its checkpoint's physics (issue 32, class 6): a
#     changed material constant, an end time already passed and output
#     fields that need other point data are refused, naming what differs;
#     another output interval runs on, bit for bit.
add_test(NAME restart_hygiene
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/restart_hygiene.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/two_disks.prm)
add_test(NAME checkpoint_restart
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    ${restart_scene} --kills 4)
add_test(NAME checkpoint_restart_mpi2
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    ${restart_scene} --np 2 --kills 3)
add_test(NAME checkpoint_restart_2_to_1
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    ${restart_scene} --np 2 --restart-np 1 --tolerance 1e-12)
#     The Glen slab (MUSL, APIC, tractions, initial stress, two bodies) at
#     T/2 = 0.3: bit for bit since output times are decimal multiples of
#     the interval (6 x 0.05 was 0.30000000000000004, where the run to 0.3
#     ended at 0.3 and so took another last step).
add_test(NAME checkpoint_restart_glen_slab
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_SOURCE_DIR}/benchmarks/glaciology/glen_slab.prm
    --end-time 0.6)
#     ... with the energy residual, whose sums (the stresses' work, the
#     initial strain energy) the checkpoint carries.
add_test(NAME checkpoint_restart_glen_slab_residual
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_SOURCE_DIR}/benchmarks/glaciology/glen_slab.prm
    --end-time 0.6 -s "Simulation/energy residual=true")
#     ... and on 2 ranks, where the grid is partitioned by work: deal.II
#     loads a checkpoint with a uniform partition, and the restart puts
#     the work partition back (the nodal sums at the rank boundary ran in
#     another order, and the momentum differed in its last digits).
add_test(NAME checkpoint_restart_glen_slab_mpi2
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_SOURCE_DIR}/benchmarks/glaciology/glen_slab.prm
    --end-time 0.6 --np 2)
mpm_test(bad_restart_missing PRM two_disks.prm EXIT 1 ARGS --restart nowhere
  ERROR "parameter '--restart' = 'nowhere': holds no complete checkpoint")
mpm_test(bad_checkpoint_1d PRM vibrating_bar.prm EXIT 1 ARGS -s "Checkpoint/interval=0.1"
  ERROR "parameter 'Checkpoint/interval'.*checkpoints need dimension 2 or 3")
#     Run-health guard on J: a point crushed or torn beyond 'Simulation/J
#     bounds' stops the run, naming it (here with bounds tight enough for
#     the colliding disks to reach them).
mpm_test(J_guard PRM two_disks.prm EXIT 2 ARGS -s "Simulation/J bounds=0.99, 1.01"
  ERROR "run stopped: step [0-9]+, t = [0-9.e-]+: material point [0-9]+ of body [01] at \\([-0-9. e]+\\) has J = V / V0 = [0-9.e-]+, outside 'Simulation/J bounds' .0.99, 1.01.: it was crushed")
mpm_test(bad_J_bounds PRM two_disks.prm EXIT 1 ARGS -s "Simulation/J bounds=2, 3"
  ERROR "parameter 'Simulation/J bounds' = '2, 3': must be two numbers J_min, J_max with 0 < J_min < 1 < J_max")
mpm_test(bad_overlapping_bodies PRM two_disks.prm EXIT 1 ARGS -s "Bodies/Body 1/center=0.3, 0.3"
  ERROR "parameter 'Bodies/Body 0/shape' = 'ball': overlaps 'Bodies/Body 1' .the point at .* lies in both.")
#     A fuzzer over the shipped scenes: bad values for their parameters end
#     in a clean run, a one-line input error naming a parameter, or a
#     stopped run; never a crash or a hang. A seeded sample here; every
#     case with 'tests/fuzz_parameters.py --exe build/dealii-mpm'.
set(fuzz_sample 40)
if(CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(fuzz_sample 12)
endif()
add_test(NAME fuzz_parameters
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/fuzz_parameters.py
    --exe $<TARGET_FILE:dealii-mpm> --sample ${fuzz_sample} --seed 3 --timeout 120)
#     The same on 2 ranks (issue 32, class 9: a failure one rank sees
#     alone must stop both), with the values 1e-30, 1e12 and 1 among the
#     bad ones; the sweep's numbers are in benchmarks/fuzz/README.md.
add_test(NAME fuzz_parameters_mpi2
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/fuzz_parameters.py
    --exe $<TARGET_FILE:dealii-mpm> --np 2 --sample 10 --seed 4 --timeout 120)
#     Volumetric locking (issue 12, item 3): a block at nu = 0.499 settling
#     under gravity with F-bar is within the compressible block's bound
#     (0.061 against 0.065 at nu = 0.3 without it); without F-bar it locks
#     (error 1.56) and a warning names the body and the remedy; 2 ranks give
#     the 1-rank history; 3D the same (0.061; 1.68 without).
mpm_test(nearly_incompressible_block)
mpm_test(nearly_incompressible_block_mpi2 PRM nearly_incompressible_block.prm NP 2
  REFERENCE nearly_incompressible_block.output RELTOL 1e-7)
mpm_test(compressible_block PRM nearly_incompressible_block.prm
  ARGS -s "Simulation/F-bar=false" -s "Bodies/Body 0/linear elastic/Poisson's ratio=0.3")
mpm_test(nearly_incompressible_block_locks PRM nearly_incompressible_block.prm EXIT 2
  ARGS -s "Simulation/F-bar=false"
  ERROR "run stopped: verification failed: error [0-9.]+ > bound 0.07"
  OUTPUT "warning: body 0 has Poisson's ratio > 0.45 .'Bodies/Body 0/linear elastic/Young's modulus' = '[^']*', 'Bodies/Body 0/linear elastic/Poisson's ratio' = '0.499'.: nearly incompressible bodies lock .too stiff, noisy pressure. on every basis. set 'Simulation/F-bar = true'")
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  mpm_test(nearly_incompressible_block_3d PRM nearly_incompressible_block.prm
    ARGS -s "Simulation/dimension=3" -s "Simulation/gravity=0, 0, -9.81"
         -s "Grid/upper corner=0.5, 0.5, 1.25" -s "Grid/cells=8, 8, 20"
         -s "Grid/boundary y min=slip" -s "Grid/boundary z min=slip"
         -s "Bodies/Body 0/upper corner=0.25, 0.25, 0.5")
endif()
#     Issue 30: two elastic disks meet and part (time step 0.01 s, to
#     t = 3.5 s); their total energy at the end is the initial 2.6 J within
#     1 % with MUSL and 1.5 % with USF on every basis (measured: MUSL
#     -0.37 % to +0.59 %, USF +0.55 % to +1.22 %; Karamelo -0.3 % and
#     +1.2 %). Until then the small-mass guard's force, not adjoint to its
#     strain rate, gave them +5 % (MUSL) and +9 % (USF).
add_test(NAME two_disks_energy_musl
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/two_disks_energy.py
    --exe $<TARGET_FILE:dealii-mpm> --scheme MUSL --check --max-gain 0.01)
add_test(NAME two_disks_energy_usf
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/two_disks_energy.py
    --exe $<TARGET_FILE:dealii-mpm> --scheme USF --check --max-gain 0.015)
#     APIC's light-node rule (discount_light_node_increments, issue 30
#     item 2) changes C_p, which enters neither the internal force nor the
#     strain rate: its check is the energy. With APIC the parted disks end
#     with less energy than they were given, every basis and scheme
#     (measured -7.6 % to -45 %); without the rule (small mass fraction 0)
#     linear MUSL and USF invert after the disks meet.
add_test(NAME two_disks_energy_apic
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/two_disks_energy.py
    --exe $<TARGET_FILE:dealii-mpm> --scheme MUSL,USF,USL -s "Simulation/transfer=APIC"
    --check --no-gain --max-gain 0)
#     Run-health guard on the energy balance: with USF the two disks gain
#     0.0053 of the energy put in by t = 2.25 (USF's own time-stepping
#     drift at the CFL step: +3.1 % by t = 3.5; +1.1 % at dt = 0.01, as
#     CB-Geo and Karamelo give); under a bound of 0.005 the run
#     stops there, naming the fastest point, with the frames up to t = 2
#     kept. (Until issue 30 the small-mass guard's force, not adjoint to
#     its strain rate, gained 0.065 by t = 2.75.) Every other scene of this
#     suite runs with the guard on (the default bound 0.25), two with a
#     documented bound of their own.
mpm_test(energy_guard PRM two_disks.prm EXIT 2
  ARGS -s "Simulation/update scheme=USF" -s "Verification/energy change bound=0"
       -s "Simulation/energy growth bound=0.005"
  ERROR "run stopped: t = 2.25: the energy of the bodies grew by [0-9.]+ J beyond the work done on them .energy 2.6 -> [0-9.]+ J, work 0 J., 0.005[0-9]+ of the energy put in .2.6 J., more than 'Simulation/energy growth bound' = 0.005. the run is unstable .the fastest point: material point [0-9]+ of body [01] at .*Output up to t = 2 "
  FILES particles_00008.pvtu)
#     Issue 30, the energy residual ('Simulation/energy residual'): the
#     balance with the work the stresses absorbed in place of the strain
#     energy. Elastic, it is the energy balance (USF +0.94 % against
#     +1.10 %, MUSL -0.39 % against -0.09 %, USL -9.1 % against -8.6 %);
#     with von Mises plasticity (40 Pa) the total falls by 92 % and hides
#     everything, while the residual still shows USF's +1.2 % (MUSL -1.0 %,
#     USL -10.6 %).
add_test(NAME energy_residual
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/energy_residual.py
    --exe $<TARGET_FILE:dealii-mpm> --check)
#     ... so the guard sees it: under a bound of 0.005 the plastic USF run
#     runs to the end on the total energy, and stops at t = 1.75 on the
#     residual (0.0067 of the energy put in).
set(plastic_disks
  -s "Simulation/update scheme=USF" -s "Verification/energy change bound=0"
  -s "Simulation/energy growth bound=0.005" -s "Simulation/end time=2.5")
foreach(b 0 1)
  list(APPEND plastic_disks -s "Bodies/Body ${b}/material=von Mises"
    -s "Bodies/Body ${b}/von Mises/Young's modulus=1000"
    -s "Bodies/Body ${b}/von Mises/Poisson's ratio=0.3"
    -s "Bodies/Body ${b}/von Mises/yield stress=40")
endforeach()
mpm_test(energy_guard_plastic_total PRM two_disks.prm ARGS ${plastic_disks}
  FILES particles_00010.pvtu)
mpm_test(energy_guard_plastic_residual PRM two_disks.prm EXIT 2
  ARGS ${plastic_disks} -s "Simulation/energy residual=true"
  ERROR "run stopped: t = 1.75: the energy residual is 0.017[0-9]+ J .the bodies' kinetic and gravitational energy plus the work their stresses absorbed, 1.11[0-9]+ J of it, beyond their initial energy and the work done on them., 0.0067[0-9]+ of the energy put in .2.6 J., more than 'Simulation/energy growth bound' = 0.005: the numerics create energy, which plasticity hides in the total energy .the fastest point: material point [0-9]+ of body [01] at .*Output up to t = 1.5 "
  FILES particles_00006.pvtu)
#     Asking for the residual changes no number of the run (the other
#     columns are two_disks_usf's, bit for bit), on 1 and 2 ranks.
mpm_test(two_disks_usf_residual PRM two_disks.prm
  ARGS -s "Simulation/update scheme=USF" -s "Verification/energy change bound=0.08"
       -s "Simulation/energy residual=true")
mpm_test(two_disks_usf_residual_mpi2 PRM two_disks.prm NP 2
  REFERENCE two_disks_usf_residual.output RELTOL 1e-7
  ARGS -s "Simulation/update scheme=USF" -s "Verification/energy change bound=0.08"
       -s "Simulation/energy residual=true")
#     The CFL numbers allowed are those stable with every basis on the
#     sweep of benchmarks/verification/cfl_range.py: up to 0.8 (the linear
#     basis and GIMP fail at 0.9, the B-splines hold at 1).
mpm_test(bad_cfl_number PRM two_disks.prm EXIT 1 ARGS -s "Simulation/CFL number=0.9"
  ERROR "parameter 'Simulation/CFL number' = '0.9': allowed range is \\(0, 0.8.")
mpm_test(bad_energy_growth_bound PRM two_disks.prm EXIT 1
  ARGS -s "Simulation/energy growth bound=-1"
  ERROR "parameter 'Simulation/energy growth bound' = '-1': ")
#     Bad values that used to name a sibling parameter (found by the
#     fuzzer's --report) now name both that set the quantity, and a section
#     beyond its count names the count, not just a line of the file.
mpm_test(bad_box_corners PRM block_settling.prm EXIT 1 ARGS -s "Bodies/Body 0/lower corner=0.6"
  ERROR "parameters 'Bodies/Body 0/lower corner', 'Bodies/Body 0/upper corner' = '0.6', '0.5': the upper corner must exceed the lower corner in every direction")
mpm_test(bad_initial_velocity_commas PRM two_disks.prm EXIT 1 ARGS -s "Bodies/Body 0/initial velocity=0.1, 0"
  ERROR "parameter 'Bodies/Body 0/initial velocity' = '0.1, 0; 0.1, 0': has a ',' outside parentheses; the components of a vector are separated by ';'")
mpm_test(bad_initial_velocity_overflow PRM two_disks.prm EXIT 1 ARGS -s "Bodies/Body 0/initial velocity=1e200*x"
  ERROR "parameter 'Bodies/Body 0/initial velocity' = '1e200.x; 1e200.x': is infinite or overflows at")
mpm_test(bad_extra_wall_section PRM ../benchmarks/contact/inclined_plane.prm EXIT 1
  ARGS -s "Boundary conditions/number of rigid walls=0"
  ERROR "parameter 'Boundary conditions/number of rigid walls' = '0': but the scene has a section 'Boundary conditions/Rigid wall 0': raise the count or remove the section")
#     Loads given by expressions are checked where they are evaluated: a
#     value beyond 1e15 names its parameter (it overflowed into a
#     non-finite point that named none).
#     An initial displacement that moves points out of the grid names
#     itself (the run stopped on a point leaving the grid).
mpm_test(bad_initial_displacement_out_of_grid PRM ../benchmarks/verification/mms_2d.prm EXIT 1
  ARGS -s "Simulation/constants=A=1, c=100, rho=1, mu=3846.153846153846, lambda=5769.230769230769, px=0, py=2.0943951023931953"
  ERROR "parameter 'Bodies/Body 0/initial displacement' = 'A.sin.pi.x..sin.px.. A.sin.pi.y..sin.py.': moves the point at X = .0.015625 0.328125. to .0.015625 1.07094., outside the grid")
mpm_test(bad_region_velocity_nan PRM ../benchmarks/plasticity/strip_footing.prm EXIT 1
  ARGS -s "Boundary conditions/Velocity region/velocity=nan"
  ERROR "parameter 'Boundary conditions/Velocity region/velocity' = 'nan': must be finite numbers of magnitude up to 1e15 .or 'free'.")
mpm_test(bad_traction_huge PRM loaded_column.prm EXIT 2 ARGS -s "Simulation/constants=p0=1e308"
  ERROR "run stopped: step 0, t = 0: parameter 'Bodies/Body 0/traction' is inf in magnitude at .[0-9. ]+.: a load must be finite and at most 1e.15")
mpm_test(bad_body_force_huge PRM ../benchmarks/verification/vortex.prm EXIT 2
  ARGS -s "Simulation/constants=A=1, mu=1e300, rho=1000"
  ERROR "run stopped: step 1, t = [0-9.e-]+: parameter 'Bodies/Body 0/body force' is [0-9.e+inf]+ in magnitude at .[-0-9. ]+.: a load must be finite")
mpm_test(bad_rigid_velocity_huge PRM ../benchmarks/contact/rolling_disk.prm EXIT 1
  ARGS -s "Bodies/Body 1/rigid velocity=1e308"
  ERROR "parameter 'Bodies/Body 1/rigid velocity' gives .1e.308 1e.308. at t = 0: a velocity must be finite and below 1e15 m/s")
mpm_test(bad_initial_stress_huge PRM ../benchmarks/glaciology/glen_slab.prm EXIT 1
  ARGS -s "Bodies/Body 0/initial stress=1e308"
  ERROR "parameter 'Bodies/Body 0/initial stress' = '1e308; 1e308; 1e308; 1e308': the stress .* is infinite or beyond 1e15 Pa")

# 17. Substepping (issue 11, seed 003). The reconstruction in the test
#     program substepping (affine fields exact with every basis, momentum
#     of the reconstructed grid state, S = 1 is the plain step). In the
#     grid: at a macro step of 10x the explicit limit the 1D MMS and the
#     vibrating bar converge as the substeps grow, each macro run matching
#     the plain run at its substep (benchmarks/verification/substepping.py;
#     the coarse ladder here). Kinetic damping once per macro step settles
#     the column of quasi_static_helpers in fewer steps than the global
#     damping (asserted there).
add_test(NAME substepping_convergence
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/substepping.py
    --exe $<TARGET_FILE:dealii-mpm> --levels 3 --mismatch-ratios "" --reconstruction-cells "" --check)
mpm_test(bad_substeps_beyond_cfl PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/macro time step=0.05" -s "Simulation/substeps=2"
  ERROR "parameter 'Simulation/substeps' = '2': gives substeps of 0.025 s, beyond the stability limit [0-9.e-]+ of the initial state; use at least [0-9]+, or 0 to follow the CFL condition")
mpm_test(bad_macro_with_time_step PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/macro time step=0.05" -s "Simulation/time step=1e-4"
  ERROR "parameter 'Simulation/time step' = '1e-4': must be 0 with 'Simulation/macro time step' > 0 .the substeps are set by 'Simulation/substeps'.")
mpm_test(bad_kinetic_damping_without_macro PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/kinetic damping=true"
  ERROR "parameter 'Simulation/kinetic damping' = 'true': needs 'Simulation/macro time step' > 0 .it acts once per macro step.")
# Runs that would never end or fill the disk are refused before the first
# step, with the estimate and what sets the step (issue 32, class 5); a
# macro step of many substeps prints progress lines within it.
mpm_test(bad_output_interval_below_step PRM block_settling.prm EXIT 1
  ARGS -s "Output/interval=1e-30"
  ERROR "parameter 'Output/interval' = '1e-30': is shorter than the time step, 0.00246.* s .set by the CFL condition.*Young's modulus' = '1e5'.*'density' = 1000..: every step would be cut to it and write a frame, 1.5e.30 in all")
mpm_test(bad_endless_run_density PRM block_settling.prm EXIT 1
  ARGS -s "Bodies/Body 0/density=1e-30"
  ERROR "parameter 'Simulation/end time' = '1.5': would take about 1.9.*e.19 steps of 7.8.*e-20 s .set by the CFL condition.*'density' = 1e-30..*more than 1e.09")
mpm_test(bad_density_tiny PRM damage_strip_nonlocal.prm EXIT 1
  ARGS -s "Bodies/Body 0/density=1e-308"
  ERROR "parameter 'Bodies/Body 0/density' = '1e-308': gives a point at .* a mass of .* kg, below 1e-150: its density and energy would overflow")
mpm_test(bad_endless_run_viscosity PRM ../benchmarks/fluids/dam_break.prm EXIT 1
  ARGS -s "Bodies/Body 0/Newtonian fluid/viscosity=1e9"
  ERROR "parameter 'Simulation/end time' = '0.36': would take about 1.8.*e.10 steps of 1.95.*e-11 s .set by the viscous limit .* of Bodies/Body 0 .'Newtonian fluid', viscosity 1e.09 Pa s")
mpm_test(bad_endless_run_macro_step PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/macro time step=1e-30"
  ERROR "parameter 'Simulation/end time' = '1.5': would take about 1.5e.30 steps of 1e-30 s .set by 'Simulation/macro time step'.")
mpm_test(bad_endless_run_substeps PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/macro time step=1e-3" -s "Simulation/substeps=1000000"
  ERROR "would take about 1.5e.09 steps of 1e-09 s .set by 'Simulation/macro time step' = 0.001 s over 'Simulation/substeps' = 1000000.")
mpm_test(progress_within_macro_step PRM block_settling.prm
  ARGS -s "Verification/exact solution=none"
       -s "Simulation/macro time step=0.01" -s "Simulation/substeps=5"
       -s "Simulation/end time=0.01" -s "Output/progress interval=0"
  OUTPUT "step +2  t = +0.004 ")
mpm_test(bad_macro_time_step PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/macro time step=-1"
  ERROR "parameter 'Simulation/macro time step' = '-1': must be >= 0")
#     Newmark's gamma (explicit, beta = 0) on the vibrating bar over one
#     period: gamma = 1/2 (the plain step) has a second-order period and
#     loses at most 1e-3 of its energy; gamma > 1/2 loses energy at first
#     order in dt (measured: period orders 1.85-1.99 for every gamma,
#     energy-loss orders 0.99-1.00).
set(newmark_dts 0.04,0.02,0.01,0.005)
if(CMAKE_BUILD_TYPE STREQUAL "Debug")
  set(newmark_dts 0.04,0.02,0.01)
endif()
add_test(NAME newmark_gamma
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/verification/newmark.py
    --exe $<TARGET_FILE:dealii-mpm> --gammas 0.5,0.6 --dts ${newmark_dts} --check)
mpm_test(bad_newmark_gamma PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/Newmark gamma=0.4"
  ERROR "parameter 'Simulation/Newmark gamma' = '0.4': allowed range is .0.5, 1.")
mpm_test(bad_newmark_gamma_musl PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/Newmark gamma=0.6" -s "Simulation/update scheme=MUSL"
  ERROR "parameter 'Simulation/Newmark gamma' = '0.6': other than 0.5 needs 'Simulation/update scheme = USL' and 'Simulation/transfer = FLIP'")
mpm_test(bad_pic_relaxation_time_apic PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/PIC relaxation time=0.1" -s "Simulation/transfer=APIC"
  ERROR "parameter 'Simulation/PIC relaxation time' = '0.1': must be 0 unless 'Simulation/transfer = FLIP'")
mpm_test(bad_pic_relaxation_time PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/PIC relaxation time=-1"
  ERROR "parameter 'Simulation/PIC relaxation time' = '-1': must be >= 0")
mpm_test(bad_least_squares_with_contact PRM ../benchmarks/contact/rolling_disk.prm EXIT 1
  ARGS -s "Simulation/macro time step=0.001" -s "Simulation/macro reconstruction=least squares"
  ERROR "parameter 'Simulation/macro reconstruction' = 'least squares': works on one velocity field; a scene with bodies in 'Contact/bodies' or rigid bodies needs 'APIC'")
mpm_test(bad_least_squares_weight PRM block_settling.prm EXIT 1
  ARGS -s "Simulation/macro time step=0.05" -s "Simulation/least-squares weight=-1"
  ERROR "parameter 'Simulation/least-squares weight' = '-1': allowed range is .0, 100.")
#     Substepping with kinetic damping restarts bit for bit: the macro
#     step's counters and the last peak's kinetic energy are in the
#     checkpoint (checkpoints fall on output times, which end macro steps).
add_test(NAME checkpoint_restart_kinetic_damping
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint_restart.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/block_settling.prm
    --end-time 0.5 -s "Simulation/damping=0" -s "Simulation/macro time step=0.005"
    -s "Simulation/kinetic damping=true" -s "Output/interval=0.05")

# 18. Parallel particle output (issue 13): HDF5 + XDMF holds what VTU holds,
#     frame by frame, on 1 and 2 ranks (positions to VTU's single
#     precision, fields exactly); 1D has no HDF5 output in deal.II.
#     The check reads HDF5 with h5py (Debian's python3-h5py, which
#     scripts/setup installs): a Python that has it, if the first one found
#     (a pyenv's, say) has not.
execute_process(COMMAND ${Python3_EXECUTABLE} -c "import h5py"
  RESULT_VARIABLE python_lacks_h5py OUTPUT_QUIET ERROR_QUIET)
set(h5py_python ${Python3_EXECUTABLE})
if(python_lacks_h5py)
  find_program(SYSTEM_PYTHON3 NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
  set(h5py_python ${SYSTEM_PYTHON3})
endif()
add_test(NAME hdf5_output
  COMMAND ${h5py_python} ${CMAKE_CURRENT_SOURCE_DIR}/hdf5_output.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/two_disks.prm
    -s "Simulation/end time=0.6" -s "Output/interval=0.1")
add_test(NAME hdf5_output_mpi2
  COMMAND ${h5py_python} ${CMAKE_CURRENT_SOURCE_DIR}/hdf5_output.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/two_disks.prm --np 2
    -s "Simulation/end time=0.6" -s "Output/interval=0.1")
set_tests_properties(hdf5_output_mpi2 PROPERTIES PROCESSORS 2)
#    A rank without points (the 3D block on 2 ranks: HDF5 hung in deal.II
#    9.4's collective write) and frames without points (the disk thrown out
#    of the grid, 'remove': deal.II's generic I/O error before), in HDF5 and
#    VTU alike, on 1 and 2 ranks.
add_test(NAME hdf5_output_empty_rank_3d_mpi2
  COMMAND ${h5py_python} ${CMAKE_CURRENT_SOURCE_DIR}/hdf5_output.py
    --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/block_3d.prm
    --np 2 --dim 3 -s "Simulation/end time=0.02" -s "Output/interval=0.01")
foreach(np 1 2)
  add_test(NAME hdf5_output_empty_frames_np${np}
    COMMAND ${h5py_python} ${CMAKE_CURRENT_SOURCE_DIR}/hdf5_output.py
      --exe $<TARGET_FILE:dealii-mpm> --scene ${CMAKE_CURRENT_SOURCE_DIR}/leaving_grid.prm
      --np ${np} --empty-frames 2 -s "Simulation/out of grid=remove")
endforeach()
set_tests_properties(hdf5_output_empty_rank_3d_mpi2 hdf5_output_empty_frames_np2
  PROPERTIES PROCESSORS 2)
mpm_test(bad_hdf5_in_1d PRM vibrating_bar.prm EXIT 1
  ARGS -s "Output/particle format=HDF5"
  ERROR "parameter 'Output/particle format' = 'HDF5': needs dimension 2 or 3")
#     Macro steps on 2 ranks give the 1-rank history (two disks, quadratic
#     B-spline, macro steps of 0.125 s, about 7 substeps each): the
#     reconstruction's sums and the least-squares system cross the rank
#     boundary, and the swaps move points between ranks. The statistics
#     include the macro steps and the mismatch (0.055 cells for the closed
#     form, 0.016 for least squares).
set(macro_args -s "Simulation/basis=quadratic B-spline" -s "Simulation/macro time step=0.125")
mpm_test(two_disks_macro PRM two_disks.prm ARGS ${macro_args})
mpm_test(two_disks_macro_mpi2 PRM two_disks.prm NP 2 REFERENCE two_disks_macro.output
  RELTOL 1e-7 ARGS ${macro_args})
mpm_test(two_disks_macro_ls PRM two_disks.prm
  ARGS ${macro_args} -s "Simulation/macro reconstruction=least squares")
mpm_test(two_disks_macro_ls_mpi2 PRM two_disks.prm NP 2 REFERENCE two_disks_macro_ls.output
  RELTOL 1e-7 ARGS ${macro_args} -s "Simulation/macro reconstruction=least squares")

# 20. Stages (issue 33): the slope of Griffiths and Lane (1999), 2 m cells.
#     Gravity loading under local damping ends in equilibrium (the
#     out-of-balance force below 1e-3 of the weight, t = 21.3 s), the
#     displacements count from the release (8.8 mm before, 0.09 mm since),
#     the released slope stays at rest (kinetic energy 2.3e-6 of the strain
#     energy), and restarts
#     within stage 1 and from the end of stage 0 are bit for bit; on 1 and
#     2 ranks.
foreach(np 1 2)
  add_test(NAME slope_stages_np${np}
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/slope/slope.py
      --exe $<TARGET_FILE:dealii-mpm> --check-stages --cells "16, 6" --np ${np})
endforeach()
set_tests_properties(slope_stages_np2 PROPERTIES PROCESSORS 2)
#     What a stage may not do, named with the parameter.
set(slope_prm ../benchmarks/slope/slope.prm)
mpm_test(bad_stage_change_fixed PRM ${slope_prm} EXIT 1
  ARGS -s "Stages/Stage 1/changes=Grid/cells=8"
  ERROR "parameter 'Stages/Stage 1/changes' = 'Grid/cells=8': a stage cannot change 'Grid/cells', which is fixed for the whole run")
mpm_test(bad_stage_change_misspelt PRM ${slope_prm} EXIT 1
  ARGS -s "Stages/Stage 1/changes=Simulation/locl damping = 0"
  ERROR "'Simulation/locl damping' is not a declared parameter; did you mean 'Simulation/local damping'")
mpm_test(bad_stage_change_value PRM ${slope_prm} EXIT 1
  ARGS -s "Stages/Stage 1/changes=Simulation/local damping = 2"
  ERROR "parameter 'Simulation/local damping' = '2': allowed range is")
mpm_test(bad_stage_equilibrium_without_gravity PRM ${slope_prm} EXIT 1
  ARGS -s "Simulation/gravity=0, 0"
  ERROR "parameter 'Stages/Stage 0/end' = 'equilibrium': needs gravity")
mpm_test(bad_stage_section_missing PRM ${slope_prm} EXIT 1
  ARGS -s "Stages/number of stages=3"
  ERROR "but the scene has no section 'Stages/Stage 2'")
mpm_test(bad_stage_not_in_equilibrium PRM ${slope_prm} EXIT 2
  ARGS -s "Stages/Stage 0/duration=0.2"
  ERROR "stage 0 .'Stages/Stage 0'. did not reach equilibrium within its duration of 0.2 s")

#     Strength reduction (issue 33): the factor of safety of the same slope
#     at 1 m cells, bisected to 0.02 (duration 30 s per trial). Bishop's
#     simplified method gives 1.374 (benchmarks/slope/limit_equilibrium.py);
#     the ladder at 2, 1, 0.5 m cells gives 1.191, 1.363, 1.387
#     (benchmarks/slope/README.md). Release only (40 s; minutes against
#     deal.II's debug library, whose build runs the stages above).
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME slope_factor_of_safety
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/slope/slope.py
      --exe $<TARGET_FILE:dealii-mpm> --factor-of-safety --ladder "32,12"
      --tolerance 0.02 --expect 1.32,1.43)
endif()
#     A softening failure and its runout (issue 33, item 3), 2 m cells:
#     stage 0 on a friction base ends in equilibrium (the out-of-balance
#     force no longer counts the damping a friction face takes: it read 0.16
#     of the weight at rest), stage 1 starts from its checkpoint although
#     softening to no cohesion adds the opening field (the points keep the
#     fields of every stage), the mass is kept, the slope fails and comes
#     to rest (kinetic energy 0.005 of its largest), and the numerics
#     create no energy (residual -0.18 of the energy put in). The deposit
#     front (0.5 m thick): 9.79 m beyond the toe at 2 m cells, 15.92 at
#     1 m with the nonlocal softening of session 41 (10.40 and 16.22 with
#     the band's scaling before; ladder: benchmarks/slope/README.md). At
#     2 m a point is 1 m square, half a column's 0.5 m, so one point
#     decides a column, hence the wide bound; there the 1 m nonlocal
#     length reaches no neighbour, and the softening is local. The 1 m rung (Release) is the one that fails with the
#     F-bar before session 39: its slide sprays points, one leaves the grid
#     at x = -30 m and the run stops (22.4 m with points removed); the 2 m
#     rung passes there too and only guards.
add_test(NAME slope_runout
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/slope/runout.py
    --exe $<TARGET_FILE:dealii-mpm> --check --ladder "30,6" --expect 9.5,14.5)
if(NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_test(NAME slope_runout_1m
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/benchmarks/slope/runout.py
      --exe $<TARGET_FILE:dealii-mpm> --check --ladder "60,12" --expect 15,18.5)
endif()
mpm_test(bad_strength_reduction_not_last PRM ${slope_prm} EXIT 1
  ARGS -s "Stages/Stage 0/strength reduction=true"
  ERROR "parameter 'Stages/Stage 0/strength reduction' = 'true': only the last stage, after one that brings the bodies to equilibrium, can search the factor of safety")
mpm_test(bad_strength_reduction_end_time PRM ${slope_prm} EXIT 1
  ARGS -s "Stages/Stage 1/strength reduction=true"
  ERROR "parameter 'Stages/Stage 1/strength reduction' = 'true': needs 'Stages/Stage 1/end' = equilibrium")
