#!/usr/bin/env bash
# The classroom-scale measurements (sweep, HTTP floor, classroom, fairness) at the sizes asked for, old (the commit before
# the change) beside new (this tree). Run from anywhere on a quiet machine; about an hour in all (the old
# elastic scenes dominate the sweep; the classroom runs take 60 s each plus start-up).
#
#   bash bench/run_classroom_scale.sh [OLD_TREE]        # default /tmp/mdl-old, made with git worktree if missing
#   QUICK=1 RESULTS=/tmp/r bash bench/run_classroom_scale.sh   # a few minutes at tiny sizes: does everything run?
#
# Results: $RESULTS (default bench/results)/{scene_sweep,http_floor,classroom_30,classroom_60,classroom_100,
#          classroom_30_base,classroom_60_base,classroom_100_base,fairness}.md
set -euo pipefail
cd "$(dirname "$0")/.."
OLD=${1:-/tmp/mdl-old}
BASE=276f0e6
if [ ! -d "$OLD/server" ]; then
    git worktree add --detach "$OLD" "$BASE"
fi
RESULTS=${RESULTS:-bench/results}
mkdir -p "$RESULTS"
if [ "${QUICK:-0}" = 1 ]; then
    POINTS=2 REQUESTS=20 SCENE_REQUESTS=2 ELASTIC_REQUESTS=1 SECONDS_=3 HEAVY=8 FAIR_SECONDS=3 CLASSES="3"
else
    POINTS=21 REQUESTS=500 SCENE_REQUESTS=30 ELASTIC_REQUESTS=20 SECONDS_=60 HEAVY=64 FAIR_SECONDS=20 CLASSES="30 60 100"
fi
echo "old: $OLD ($(git -C "$OLD" rev-parse --short HEAD)), new: $(pwd) ($(git rev-parse --short HEAD))"

# Point 1: every scene, every slider over 21 positions, server compute in-process, old and new taking turns.
python3 bench/scene_sweep.py --old "$OLD" --points "$POINTS" --rounds 1 --output "$RESULTS/scene_sweep.md"

# Point 2: kinematics round trip against the bare floor; every scene's default request on idle servers.
python3 bench/http_floor.py --old "$OLD" --requests "$REQUESTS" --scene-requests "$SCENE_REQUESTS" \
    --elastic-requests "$ELASTIC_REQUESTS" --output "$RESULTS/http_floor.md"

# Point 4: the class of 30, 60 and 100 on 1 and 2 workers, the new page pattern and the old one on the new
# server; then the baseline: the old page pattern on the old server.
for students in $CLASSES; do
    python3 bench/classroom.py --students "$students" --seconds "$SECONDS_" --workers 1 2 --pattern new old \
        --compare-clients 0 --output "$RESULTS/classroom_${students}.md"
    python3 bench/classroom.py --students "$students" --seconds "$SECONDS_" --workers 1 2 --pattern old \
        --tree "$OLD" --compare-clients 0 --output "$RESULTS/classroom_${students}_base.md"
done

# Point 5: 64 heavy requests from one client against another client's kinematics, honouring Retry-After or not.
python3 bench/fairness.py --old "$OLD" --heavy "$HEAVY" --seconds "$FAIR_SECONDS" --ramp 3 --output "$RESULTS/fairness.md"

# Point 3 (the browser) has its own scripts: bench/browser.py (family-web), bench/static_visit.py (fairness).
