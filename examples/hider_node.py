#!/usr/bin/env python3
"""A hider of your own, as a ROS node beside the world and the seeker.

It sees what the shipped hider sees, each arena's 84 x 84 RGB camera image on hider/observations,
and answers every batch with one action per arena on hider/actions, echoing the batch's stamp and
step ids (the world refuses an answer to any other step). Its rule is a reflex, not a policy worth
evaluating: while the seeker's red back or yellow front is in view, turn away from it; otherwise
go forward.

    source devel/setup.bash
    roslaunch hideseek_world basic.launch policy:=external &        # the game, waiting for a hider
    /usr/bin/python3 examples/hider_node.py                          # this node plays it
    # or, instead of basic.launch: evaluated on seeds 0-99, as a policy is
    roslaunch hideseek_world evaluate.launch policy:=external

In a namespaced game (ns:=game1), start it there: examples/hider_node.py __ns:=game1.
docs/launch_files.md, "A hider of your own", states the exchange.
"""
import numpy as np
import rospy
from hideseek_msgs.msg import ActionBatch, ObservationBatch


def seeker_columns(image):
    """The columns of an H x W x 3 uint8 image that show the seeker (its red back, its yellow front)."""
    r, g, b = (image[..., k].astype(np.int16) for k in range(3))
    seeker = ((r > 150) & (g < 90) & (b < 90)) | ((r > 200) & (g > 190) & (b < 70))
    return np.nonzero(seeker.any(axis=0))[0]


def act(image):
    columns = seeker_columns(image)
    if len(columns) == 0:
        return ActionBatch.FORWARD
    # The seeker's image lies left of the middle: turn right, away from it; and the other way.
    return ActionBatch.TURN_RIGHT if columns.mean() < image.shape[1] / 2 else ActionBatch.TURN_LEFT


def main():
    rospy.init_node("my_hider")
    actions = rospy.Publisher("hider/actions", ActionBatch, queue_size=2, tcp_nodelay=True)

    def answer(batch):
        try:
            images = np.frombuffer(batch.images, np.uint8).reshape(batch.num_arenas, batch.height, batch.width, 3)
        except ValueError as e:  # a batch whose image bytes do not fit its sizes: say so and wait for the next
            rospy.logwarn_throttle(5.0, "my_hider: skipped a malformed observation batch: %s" % e)
            return
        reply = ActionBatch(actions=bytes(act(image) for image in images), step=list(batch.step))
        reply.header.stamp = batch.header.stamp
        actions.publish(reply)

    # A batch of 16 arenas is about 340 kB: a receive buffer that holds one whole.
    rospy.Subscriber("hider/observations", ObservationBatch, answer, queue_size=2, buff_size=2 ** 24,
                     tcp_nodelay=True)
    rospy.spin()


if __name__ == "__main__":
    main()
