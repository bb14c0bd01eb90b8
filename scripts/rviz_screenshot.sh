#!/usr/bin/env bash
# The demo manoeuvre in RViz under a virtual X server (Xvfb, RViz from Debian, software OpenGL): builds the package,
# runs `roslaunch sphere_contact_estimator demo.launch rviz:=true` on its own display and ROS master, and while the
# robot brakes (the patch partly adhering, partly sliding: the zones and deflections at their most telling) writes a
# screenshot.
# It fails unless RViz subscribed to the marker, wrench and odometry topics, nothing in the launch logged an error or
# died, and the picture shows what the markers draw (adhering and sliding bristles, the friction circle, the force).
#   scripts/rviz_screenshot.sh [OUTPUT.png]   (default: $WS/output/rviz_demo.png; the one docs/node.md shows is
#                                              docs/figures/rviz_demo.png)
# SCE_RVIZ_AT: seconds into the manoeuvre of the screenshot (default 7.9: braking, the patch partly sliding).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

APT_PACKAGES+=(xvfb xfonts-base python3-pil libgl1-mesa-dri)  # fonts: Xvfb's "fixed"; mesa: software OpenGL
install_deps
build
OUT="$(realpath -m "${1:-$WS/output/rviz_demo.png}")"
AT="${SCE_RVIZ_AT:-7.9}"
mkdir -p "$(dirname "$OUT")"
RUN="$(mktemp -d)"
PIDS=()
cleanup() {
  for p in "${PIDS[@]}"; do kill -INT "$p" 2>/dev/null || true; done
  sleep 2
  for p in "${PIDS[@]}"; do kill -KILL "$p" 2>/dev/null || true; done
  rm -rf "$RUN"
}
trap cleanup EXIT

# a display and a master of our own: nothing else on the machine is disturbed, or disturbs
Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$RUN/display" 2>"$RUN/xvfb.log" &
PIDS+=($!)
for _ in $(seq 100); do [ -s "$RUN/display" ] && break; sleep 0.1; done
[ -s "$RUN/display" ] || { cat "$RUN/xvfb.log"; log "Xvfb did not start"; exit 1; }
export DISPLAY=":$(tr -d '\n' < "$RUN/display")" LIBGL_ALWAYS_SOFTWARE=1
PORT=$(( 20000 + RANDOM % 20000 ))
export ROS_MASTER_URI="http://localhost:$PORT" ROS_HOME="$RUN/ros"
log "the demo in RViz on display $DISPLAY, master port $PORT"
roslaunch -p "$PORT" sphere_contact_estimator demo.launch rviz:=true wait_for:=1 output_csv:="$RUN/estimates.csv" \
  >"$RUN/launch.log" 2>&1 &
PIDS+=($!)

# The check, in Python: when the manoeuvre is AT s in (the odometry's stamps say so: the run waits for this
# subscriber, wait_for:=1), a screenshot; then what RViz subscribed to and what the picture shows.
rc=0
/usr/bin/python3 - "$OUT" "$AT" <<'EOF' || rc=1
import sys
import time
import rosgraph
import rospy
from PIL import ImageGrab
from nav_msgs.msg import Odometry

out, at = sys.argv[1], float(sys.argv[2])
rospy.init_node("rviz_screenshot", anonymous=True, disable_signals=True)
first, now = [], []
def on_odometry(m):
    if not first:
        first.append(m.header.stamp.to_sec())
    now[:] = [m.header.stamp.to_sec()]
sub = rospy.Subscriber("/odom", Odometry, on_odometry, queue_size=100)
deadline = time.monotonic() + 90.0  # RViz starting in software OpenGL, then the manoeuvre
while time.monotonic() < deadline and not (first and now[0] - first[0] >= at):
    time.sleep(0.01)
if not first:
    sys.exit("rviz_screenshot: no odometry within 90 s (the demo waits for RViz to subscribe to /odom)")
if now[0] - first[0] < at:
    sys.exit(f"rviz_screenshot: the manoeuvre did not reach {at} s")
image = ImageGrab.grab(xdisplay=None).convert("RGB")
image.save(out)
print(f"rviz_screenshot: {now[0] - first[0]:.2f} s into the manoeuvre: {out}")

# RViz listens to what the configuration shows
master = rosgraph.Master("/rviz_screenshot")
_, subscribers, _ = master.getSystemState()
subscribed = {topic for topic, nodes in subscribers if "/rviz" in nodes}
problems = [f"RViz does not subscribe to {t}" for t in
            ("/contact_markers", "/brush_wrench", "/rolling_resistance_wrench", "/odom") if t not in subscribed]

# and drew the markers: pixels of the bristles' green and red, the friction circle's yellow, the force's blue
def count(rgb, tol=60):
    r0, g0, b0 = rgb
    return sum(1 for r, g, b in image.getdata() if abs(r - r0) + abs(g - g0) + abs(b - b0) < tol)

# (the least counts are a fifth of those of the committed picture: the drawing is there, whatever the timing)
for name, rgb, least in (("adhering bristles (green)", (25, 204, 25), 20), ("sliding bristles (red)", (230, 25, 25), 40),
                         ("friction circle (yellow)", (255, 217, 25), 80), ("brush force (blue)", (51, 102, 255), 10)):
    n = count(rgb)
    print(f"rviz_screenshot: {name}: {n} pixels")
    if n < least:
        problems.append(f"{name}: {n} pixels (at least {least} expected)")
for p in problems:
    print("rviz_screenshot: " + p, file=sys.stderr)
sys.exit(1 if problems else 0)
EOF
# nothing logged an error or died (the estimator's and RViz's output go to the launch's log)
if grep -nE "\[ERROR\]|\[FATAL\]|Segmentation|terminate called|has died" "$RUN/launch.log"; then
  log "errors in the launch's output (above)"
  rc=1
fi
if [ "$rc" -ne 0 ]; then
  log "RViz check FAILED; the launch's output:"
  tail -40 "$RUN/launch.log"
  exit 1
fi
log "RViz subscribed and drew the contact: $OUT"
