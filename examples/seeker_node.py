#!/usr/bin/env python3
"""A seeker of your own, as a ROS node beside the world and the hider.

It reads what the scripted seeker reads, each arena's seeker/observations entry (its pose in the
map frame, whether it sees the hider and, only then, where the hider is), and answers every batch
with one action per arena on seeker/actions, echoing the batch's stamp and step ids. Its rule: head
for where it last saw the hider (turn toward it, then go forward); with nothing seen yet, or once
there, turn on the spot to look around. A plain pursuer without path planning: obstacles stop it.

    source devel/setup.bash
    roslaunch hideseek_world basic.launch seeker_mode:=external &     # the game, waiting for a seeker
    /usr/bin/python3 examples/seeker_node.py                         # this node plays it
    # or, instead of basic.launch: the shipped hider evaluated against it on seeds 0-99
    roslaunch hideseek_world evaluate.launch policy:=shipped seeker_mode:=external

It decides when the scripted seeker would (seeker_decides:=game: every physics frame in v2 and v3,
six times a step) or once a step (seeker_decides:=step); it needs no change for either. In a
namespaced game (ns:=game1), start it there: examples/seeker_node.py __ns:=game1.
docs/launch_files.md, "A seeker of your own", states the exchange.
"""
import math

import rospy
from hideseek_msgs.msg import ActionBatch, SeekerObservationBatch

TURN_TOLERANCE = math.radians(15)  # go forward when the target lies within this of straight ahead
ARRIVED = 0.5                      # m: at the last place seen, look around


def act(pose, target):
    """One arena's action: toward `target` (x, y) from `pose` (Pose2D), or a turn to look around."""
    if target is None or math.hypot(target[0] - pose.x, target[1] - pose.y) < ARRIVED:
        return ActionBatch.TURN_LEFT
    bearing = math.atan2(target[1] - pose.y, target[0] - pose.x) - pose.theta
    bearing = math.atan2(math.sin(bearing), math.cos(bearing))
    if abs(bearing) <= TURN_TOLERANCE:
        return ActionBatch.FORWARD
    return ActionBatch.TURN_LEFT if bearing > 0 else ActionBatch.TURN_RIGHT


def main():
    rospy.init_node("my_seeker")
    actions = rospy.Publisher("seeker/actions", ActionBatch, queue_size=2, tcp_nodelay=True)
    last_seen = {}  # arena -> (episode, (x, y)) where it last saw the hider

    def answer(batch):
        n = batch.num_arenas
        if not (len(batch.pose) == len(batch.sees_hider) == len(batch.hider_position) == len(batch.step)
                == len(batch.episode) == n):
            rospy.logwarn_throttle(5.0, "my_seeker: skipped a malformed observation batch")
            return
        chosen = []
        for i in range(n):
            if last_seen.get(i, (None,))[0] != batch.episode[i]:
                last_seen[i] = (batch.episode[i], None)  # a new episode: nothing seen yet
            if batch.sees_hider[i]:
                last_seen[i] = (batch.episode[i], (batch.hider_position[i].x, batch.hider_position[i].y))
            chosen.append(act(batch.pose[i], last_seen[i][1]))
        reply = ActionBatch(actions=bytes(chosen), step=list(batch.step))
        reply.header.stamp = batch.header.stamp
        actions.publish(reply)

    # Every map rides along in every batch: a receive buffer that holds one whole.
    rospy.Subscriber("seeker/observations", SeekerObservationBatch, answer, queue_size=2, buff_size=2 ** 24,
                     tcp_nodelay=True)
    rospy.spin()


if __name__ == "__main__":
    main()
