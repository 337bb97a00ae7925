#!/bin/bash
# Runs every script of analysis/ as the documentation runs it, at reduced sizes, from the top
# of a scratch clone of the repository with build/bkquake in place (the test
# AnalysisScripts.NoneChangesATrackedFile runs it and then checks `git status`). Everything
# goes under runs/ (ignored) unless a script is told otherwise with --out. One line per
# script; the test checks that every script of analysis/ is named here.
set -eo pipefail
B=build/bkquake
P=/usr/bin/python3
export MPLBACKEND=Agg
q() { "$@" > /dev/null; }

# One event run and one continuous run for the plot scripts that read a run folder.
q $B run --set run.events=4000 --set run.transient_events=500 --set output.event_slip=-2 --out runs/r
q $B run data/scenes/thesis.ini --set run.duration=200 --set output.energy=true --out runs/c
q $P analysis/plot_gr.py runs/r --out runs/r/gr.png
q $B fit runs/r --scan; q $P analysis/plot_b_scan.py runs/r
q $B seismicity runs/r; q $P analysis/plot_seismicity.py runs/r
q $B compare runs/r runs/r; q $P analysis/plot_rsf_events.py runs/r runs/r --from 0 --to 1e9 --out runs/r/rsf_events.png
q $P analysis/plot_slip_profiles.py runs/r --largest 4
q $P analysis/plot_energy.py runs/c --out runs/c/energy.png
q $P analysis/plot_brake.py timeseries runs/c
q $B stability data/scenes/thesis.ini --sweep drive.speed=0.05:0.2:5 --out runs/st
q $P analysis/plot_stability.py sweep runs/st --out runs/st/sweep.png
q $B sweep data/sweeps/carlson-langer-table.ini --set run.events=1500 --set run.transient_events=200 --out runs/sw
q $P analysis/plot_sweep.py runs/sw
q $B accuracy --schemes rk4 --dt 0.01 --samples 4 --long-events 200 --out runs/acc
q $P analysis/plot_work_precision.py runs/acc
q $B run data/scenes/rsf/qdyn-stickslip.ini --set output.blocks=true --set output.every=1 --set run.duration=2000 --out runs/rsf
q $P analysis/plot_rsf.py runs/rsf --out runs/rsf/rsf.png
q $B run --set model.blocks=8 --set model.rows=8 --set run.events=2000 --set run.transient_events=200 --out runs/lat
q $P analysis/plot_lattice.py runs/lat --out runs/lat/lattice.png
q $P analysis/plot_event_sizes.py data/reference/event_sizes_n100.csv --out runs/event_sizes.png
# Not run here: analysis/compare_modes.py keeps about 5000 slip episodes per continuous run
# (minutes); it writes under --out-dir (default runs/modes).
# Not run here: analysis/calibrate_errors.py runs 20-30 seeds of 1e5 events per case (tens of
# minutes); it writes only under its required --work folder (and --csv where given).
# The OFC exponent: told no --out, it writes into the current folder only (never into data/
# or docs/), so it runs from runs/.
(cd runs && q $P ../analysis/ofc_exponent.py --quick --sizes 8 --events 2000)
EVENTS=2000 analysis/scaling.sh 50 > runs/scaling.csv
 q $P analysis/plot_scaling.py runs/scaling.csv --out runs/scaling.png
q analysis/peak_memory.sh 1000
q analysis/run_carlson_langer.sh 1500
# Each run_coupling_*.sh draws its figure with analysis/plot_coupling.py,
# analysis/plot_coupling_viscosity.py or analysis/plot_coupling_fronts.py (--out under runs/).
q analysis/run_coupling_b.sh 1000 500 100 1 3
q analysis/run_coupling_viscosity.sh 500 200 2
q analysis/run_coupling_fronts.sh 20 0
# Not run here: analysis/run_rsf_events.sh runs the rate-and-state chain of 100, the 16 x 8
# lattice, velocity-weakening BK and OFC (about 10 CPU-minutes); it writes under its OUT_DIR
# (default runs/rsf-events).
# Not run here: analysis/run_lattice.sh runs the shipped lattice scenes at their own sizes
# (about 30 CPU-minutes); it writes under runs/lattice.
# A rough-D_c file without roughness is the scene's own asperity pattern: the same catalogue.
$P analysis/make_rough_blocks.py --nx 16 --ny 8 --period 4 --width 3 --rough 0 > runs/flat.csv
L="data/scenes/rsf/lattice-patches.ini --set drive.mode=events --set rsf.handover_speed=3e-6"
L="$L --set run.events=20 --set run.transient_events=0"
q $B run $L --out runs/lp
q $B run $L --set rsf.pattern=uniform --set rsf.blocks=runs/flat.csv --out runs/lf
cmp runs/lp/catalog.csv runs/lf/catalog.csv
