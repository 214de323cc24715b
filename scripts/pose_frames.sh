#!/usr/bin/env bash
# The frames of a bench table measured along an animation, one row each: which pose it was
# (the frame's number along the path and the path's angle there), its host ms and the host ms
# of the pose update before it (the cell's `wall_ms` and `pose_ms`, in order). A table's entries
# are medians over its frames; this is where a median hides a pattern along the path (T3: a
# bottom level rebuilt around the turned dragon, results/photon_trace_paths_findings.md).
#
#   bash scripts/pose_frames.sh results/<device>/photon_trace_moving.json.gz [OUT.csv]
#
# OUT defaults to results/<table>_frames.csv. Frame f of a cell is its warm-up frames plus the
# sample's index (frame 0, the scene's own pose, has no pose update and no row) (each attempt of a cell measured again starts at frame 0; its kept attempt's
# samples are the cell's); its angle is 360° × (f mod period) / period
# (`caustics::animation`). Needs python3.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: scripts/pose_frames.sh TABLE.json.gz [OUT.csv]" >&2; exit 2; }
table=$1
[ -f "$table" ] || { echo "pose_frames.sh: $table: no such file" >&2; exit 2; }
name=$(basename "$table")
name=${name%.gz}
out=${2:-results/${name%.json}_frames.csv}
TABLE="$table" OUT="$out" python3 - <<'ROWS'
import csv, gzip, json, os, sys
# A table as the bench writes it (gzip-compressed, whatever its name) or unpacked.
with open(os.environ["TABLE"], "rb") as f:
    gz = f.read(2) == b"\x1f\x8b"
table = json.load(gzip.open(os.environ["TABLE"], "rt") if gz else open(os.environ["TABLE"]))
run = table["run"]
if all(run[k] == "static" for k in ("light_path", "camera_path", "object_path")):
    sys.exit(f"pose_frames.sh: {os.environ['TABLE']}: every path is static, no pose changes")
period, warmup = max(run["period_frames"], 1), run["warmup_frames"]
rows = [["frame", "scene", "technique", "photons", "orientation", "angle_deg", "frame_ms", "pose_ms"]]
for c in table["cells"]:
    cell = c["cell"]
    scene = os.path.basename(cell["scene"]).removesuffix(".toml")
    poses, walls = c.get("pose_ms", []), c["wall_ms"]
    # Frame 0 is the scene's own pose, without an update: without warm-up it is measured too.
    first = 1 if warmup == 0 else 0
    if len(poses) != len(walls) - first:
        sys.exit(f"pose_frames.sh: cell {cell['index']}: {len(poses)} pose updates for {len(walls)} frames")
    for i, (wall, pose) in enumerate(zip(walls[first:], poses)):
        f = warmup + first + i
        angle = 360.0 * (f % period) / period
        orientation = "axis-aligned" if angle % 90.0 == 0.0 else "turned"
        rows.append([f"f{f}", scene, cell["technique_label"], cell["photons"], orientation, angle, wall, pose])
with open(os.environ["OUT"], "w", newline="") as f:
    csv.writer(f).writerows(rows)
print(f"wrote {os.environ['OUT']} ({len(rows) - 1} frames)")
ROWS
