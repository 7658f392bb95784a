#!/usr/bin/env python3
"""Watches a running game for a soak (experiments/soak/soak.sh): every node's resident memory over time, the
world's input counters (missed decisions, rejected action messages) from /diagnostics and, with
--rviz, everything rviz subscribes to, so that the graph serves a viewer all along.

usage: soak_monitor.py --duration S --out DIR [--interval S] [--rviz] [--ns NS] [--continue]
Writes DIR/rss.csv (elapsed_s,node,pid,rss_kb), DIR/world.csv (elapsed_s and the world's counters)
and DIR/summary.md: per node the RSS at the start, after one hour and at the end, its growth per hour
(least-squares slope after the first 10 minutes, when caches and allocators have settled), and the
totals of missed decisions and rejected messages. The master is ROS_MASTER_URI's. A master or node
that does not answer (a sweep run paused by `hideseek_pipeline sweep hold`) is skipped for that sample.
--continue appends to DIR's files, timing from the first run's start: a watch cut short goes on.
"""
import argparse
import csv
import os
import socket
import time
import xmlrpc.client

import rosgraph
import rospy
from diagnostic_msgs.msg import DiagnosticArray

WARM_UP_S = 600.0
COUNTERS = ["decision_steps", "stale_decisions", "rejected_malformed", "rejected_wrong_arena_count", "rejected_invalid_action",
            "rejected_wrong_step", "rejected_second_publisher", "rejected_late", "real_time_factor"]


def node_pids(master, me):
    pids = {}
    try:
        state = master.getSystemState()
    except Exception:  # a master that does not answer now (paused, restarting)
        return pids
    names = {n for group in state for _, nodes in group for n in nodes}
    for name in sorted(names - {me}):
        try:
            uri = master.lookupNode(name)
            code, _, pid = xmlrpc.client.ServerProxy(uri).getPid(me)
            if code == 1:
                pids[name] = pid
        except Exception:  # a node that just left
            pass
    return pids


def rss_kb(pid):
    try:
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        return None
    return None


def slope_per_hour(points):
    """Least-squares slope of (seconds, kB) points, in MB per hour."""
    if len(points) < 3:
        return float("nan")
    n = len(points)
    mx = sum(p[0] for p in points) / n
    my = sum(p[1] for p in points) / n
    sxx = sum((p[0] - mx) ** 2 for p in points)
    if sxx == 0:
        return float("nan")
    return sum((p[0] - mx) * (p[1] - my) for p in points) / sxx * 3600.0 / 1024.0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--duration", type=float, required=True, help="seconds to watch")
    p.add_argument("--interval", type=float, default=30.0, help="seconds between samples")
    p.add_argument("--out", required=True)
    p.add_argument("--rviz", action="store_true", help="subscribe to what rviz shows (config/hideseek.rviz)")
    p.add_argument("--ns", default="", help="the game's namespace")
    p.add_argument("--continue", dest="resume", action="store_true",
                   help="append to DIR's rss.csv and world.csv, timing from their start")
    args = p.parse_args()
    socket.setdefaulttimeout(10.0)  # a stopped node never answers: give up on it for this sample
    os.makedirs(args.out, exist_ok=True)
    rospy.init_node("soak_monitor", anonymous=True, disable_signals=True)
    me = rospy.get_name()
    master = rosgraph.Master(me)
    world = {}

    def on_diagnostics(msg):
        for s in msg.status:
            if s.name.startswith("hideseek world"):
                world.update({kv.key: kv.value for kv in s.values})

    rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics, queue_size=10)
    received = {}
    if args.rviz:
        from nav_msgs.msg import OccupancyGrid, Path
        from sensor_msgs.msg import Image
        from tf2_msgs.msg import TFMessage
        from visualization_msgs.msg import MarkerArray

        prefix = "/" + args.ns.strip("/") + "/" if args.ns.strip("/") else "/"
        topics = [("map", OccupancyGrid), ("world/markers", MarkerArray), ("hider/path", Path),
                  ("seeker/path", Path), ("hider/camera/image_raw", Image), ("seeker/camera/image_raw", Image)]
        topics = [(prefix + t, c) for t, c in topics] + [("/tf", TFMessage), ("/tf_static", TFMessage)]
        for topic, cls in topics:
            received[topic] = 0

            def count(_msg, topic=topic):
                received[topic] += 1

            rospy.Subscriber(topic, cls, count, queue_size=5)

    rss_path, world_path = os.path.join(args.out, "rss.csv"), os.path.join(args.out, "world.csv")
    samples = {}
    start = time.time()
    if args.resume and os.path.exists(rss_path):
        with open(rss_path) as f:
            rows = list(csv.DictReader(f))
        for r in rows:
            samples.setdefault(r["node"], []).append((float(r["elapsed_s"]), int(r["rss_kb"])))
        start = os.path.getmtime(os.path.join(args.out, "started"))
    else:
        open(os.path.join(args.out, "started"), "w").close()  # its time is the watch's start
        start = os.path.getmtime(os.path.join(args.out, "started"))
        with open(rss_path, "w", newline="") as f:
            csv.writer(f).writerow(["elapsed_s", "node", "pid", "rss_kb"])
        with open(world_path, "w", newline="") as f:
            csv.writer(f).writerow(["elapsed_s"] + COUNTERS)
    rss_file = open(rss_path, "a", newline="")
    rss_csv = csv.writer(rss_file)
    world_file = open(world_path, "a", newline="")
    world_csv = csv.writer(world_file)
    pids = {}
    while True:
        elapsed = time.time() - start
        pids.update(node_pids(master, me))
        for name, pid in sorted(pids.items()):
            kb = rss_kb(pid)
            if kb is not None:
                rss_csv.writerow(["%.0f" % elapsed, name, pid, kb])
                samples.setdefault(name, []).append((elapsed, kb))
        world_csv.writerow(["%.0f" % elapsed] + [world.get(k, "") for k in COUNTERS])
        rss_file.flush()
        world_file.flush()
        print("soak %.0f / %.0f s: %s" % (elapsed, args.duration, ", ".join(
            "%s %.0f MB" % (n, s[-1][1] / 1024.0) for n, s in sorted(samples.items()))), flush=True)
        if elapsed >= args.duration:
            break
        time.sleep(min(args.interval, max(0.0, args.duration - elapsed)))

    def at(points, t):
        return min(points, key=lambda q: abs(q[0] - t))

    with open(os.path.join(args.out, "summary.md"), "w") as f:
        f.write("Watched %.0f s, a sample every %.0f s. Growth: least-squares slope after the first %.0f s.\n\n"
                % (elapsed, args.interval, WARM_UP_S))
        f.write("| node | RSS at start (MB) | after 1 h (MB) | at the end (MB) | growth (MB/h) |\n")
        f.write("| --- | --- | --- | --- | --- |\n")
        for name, pts in sorted(samples.items()):
            one_hour = "%.1f" % (at(pts, 3600.0)[1] / 1024.0) if pts[-1][0] >= 3600.0 else "-"
            settled = [q for q in pts if q[0] >= WARM_UP_S] or pts
            f.write("| %s | %.1f | %s | %.1f | %+.2f |\n" % (name, pts[0][1] / 1024.0, one_hour, pts[-1][1] / 1024.0,
                                                           slope_per_hour(settled)))
        rejected = sum(int(world.get(k, 0) or 0) for k in COUNTERS if k.startswith("rejected"))
        f.write("\nWorld: %s decision steps, %s missed decisions (an agent's answer absent: it stood still), "
                "%d rejected action messages, real-time factor %s at the end.\n"
                % (world.get("decision_steps", "?"), world.get("stale_decisions", "?"), rejected,
                   world.get("real_time_factor", "?")))
        if received:
            f.write("\nMessages received on rviz's topics: %s.\n" % ", ".join(
                "%s %d" % (t, n) for t, n in sorted(received.items())))
    print(open(os.path.join(args.out, "summary.md")).read())


if __name__ == "__main__":
    main()
