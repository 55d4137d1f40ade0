#!/usr/bin/env bash
# Accuracy on real and semi-real frames, every mode, one table: the battery
# to judge a change by. One sequence is no evidence (these runs are chaotic:
# a 1e-9 m change moves one ATE by 5 %), so a change is judged over all of
# them, with frames without a pose next to every ATE.
#
#   scripts/real_table.sh [OUT]            (default: real-table)
#
# Sequences (from DLSLAM_SHARED_DATA, default ../shared/data; missing ones
# are skipped with a message):
#   bonn      real Bonn crowd frames 280-579 (Xtion, three people walking)
#   kitchen   7-Scenes redkitchen, 500 real Kinect frames, static
#   k5s1..k5s4, k8s5   the kitchen with real photos of people walked through
#             it (`dlslam composite`, 5 people seeds 1-4, 8 people seed 5),
#             rendered once into OUT
# Environment: DLSLAM (default build/bin/dlslam), MODES (default
# "orb geometry full"), SEQUENCES (default all), RUN_ARGS (extra `dlslam run`
# flags, default --sequential; set it to "" for threaded runs), TAG (a name
# for this variant: reports go to OUT/TAG, default "run"). Reports newer
# than the binary are reused, so an interrupted table resumes.
# The semi-real ratio is ATE over that of the same mode on the kitchen
# without people (issue 14's goal: <= 1.3).
set -euo pipefail

OUT=${1:-real-table}
DLSLAM=${DLSLAM:-build/bin/dlslam}
DATA=${DLSLAM_SHARED_DATA:-../shared/data}
MODES=${MODES:-"orb geometry full"}
SEQUENCES=${SEQUENCES:-"bonn kitchen k5s1 k5s2 k5s3 k5s4 k8s5"}
RUN_ARGS=${RUN_ARGS---sequential}
TAG=${TAG:-run}

[[ -x $DLSLAM ]] || { echo "no $DLSLAM: build first (scripts/setup.sh)" >&2; exit 1; }
KITCHEN=$DATA/7scenes-redkitchen-500
PEOPLE=$DATA/segmentation/ccp-person
mkdir -p "$OUT/$TAG"

# Prints the sequence folder of a name, rendering a semi-real one if needed;
# nothing when its data is absent.
sequence_dir() {
  case $1 in
    bonn) [[ -d $DATA/bonn/rgbd_bonn_crowd_280-579 ]] && echo "$DATA/bonn/rgbd_bonn_crowd_280-579" ;;
    kitchen) [[ -d $KITCHEN ]] && echo "$KITCHEN" ;;
    k[0-9]s[0-9])
      [[ -d $KITCHEN && -d $PEOPLE ]] || return 0
      local count=${1:1:1} seed=${1:3:1} dir=$OUT/semi-real/$1
      if [[ ! -f $dir/groundtruth.txt ]]; then
        echo "== rendering $1" >&2
        nice -n 10 "$DLSLAM" composite --background "$KITCHEN" --people "$PEOPLE" --count "$count" \
          --min-distance 0.8 --max-distance 1.8 --seed "$seed" --out "$dir" >"$OUT/semi-real/$1.log" 2>&1
      fi
      echo "$dir" ;;
  esac
}

mkdir -p "$OUT/semi-real"
for seq in $SEQUENCES; do
  dir=$(sequence_dir "$seq")
  [[ -n $dir ]] || { echo "== $seq: data not in $DATA, skipped" >&2; continue; }
  for mode in $MODES; do
    report=$OUT/$TAG/$seq.$mode.json
    if [[ $report -nt $DLSLAM ]]; then
      echo "== $TAG $seq $mode (reused)" >&2
      continue
    fi
    echo "== $TAG $seq $mode" >&2
    # shellcheck disable=SC2086
    nice -n 5 "$DLSLAM" run --sequence "$dir" --mode "$mode" $RUN_ARGS \
      --out "$OUT/$TAG/$seq.$mode.txt" --report "$report" >"$OUT/$TAG/$seq.$mode.log" 2>&1 ||
      echo "== $seq $mode failed: $OUT/$TAG/$seq.$mode.log" >&2
  done
done

/usr/bin/python3 - "$OUT/$TAG" "$SEQUENCES" "$MODES" <<'PY'
import json, os, statistics, sys
out, sequences, modes = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
def load(seq, mode):
    path = os.path.join(out, f"{seq}.{mode}.json")
    return json.load(open(path)) if os.path.exists(path) else None
def cell(r, base=None):
    if not r or "ate" not in r:
        return "-"
    s = r.get("pose_sources", {})
    posed = r.get("frames_posed", r["frames"])
    text = f"{r['ate']['rmse']:.4f} ({posed}/{r['frames']}"
    other = [f"{s[k]} {k}" for k in ("coasted", "relocalized", "new_map") if s.get(k)]
    text += (", " + ", ".join(other) if other else "") + ")"
    if base and "ate" in base:
        text += f" x{r['ate']['rmse'] / base['ate']['rmse']:.2f}"
    return text
lines = ["| sequence | " + " | ".join(modes) + " |", "|---|" + "---|" * len(modes)]
ratios = {m: [] for m in modes}
for seq in sequences:
    semi = seq[0] == "k" and seq != "kitchen"
    row = []
    for m in modes:
        r, base = load(seq, m), load("kitchen", m) if semi else None
        row.append(cell(r, base))
        if semi and r and base and "ate" in r and "ate" in base:
            ratios[m].append(r["ate"]["rmse"] / base["ate"]["rmse"])
    lines.append(f"| {seq} | " + " | ".join(row) + " |")
if any(ratios.values()):
    lines.append("| semi-real: median ratio, <= 1.3 | " + " | ".join(
        f"{statistics.median(v):.2f}, {sum(x <= 1.3 for x in v)} of {len(v)}" if v else "-"
        for v in ratios.values()) + " |")
text = "ATE RMSE [m] (frames posed / frames, how the rest were posed) x ratio to the kitchen without people\n\n" + \
    "\n".join(lines) + "\n"
open(os.path.join(out, "table.md"), "w").write(text)
print(text)
PY
