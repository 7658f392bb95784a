#!/usr/bin/env python3
"""A hider of your own, as a ROS node beside the world and the seeker.

It sees what the shipped hider sees, each arena's 84 x 84 RGB camera image on hider/observations,
and answers every batch with one action per arena on hider/actions, echoing the batch's stamp and
step ids (the world refuses an answer to any other step). Its rule is a reflex, not a policy worth
evaluating: while the seeker's red back or yellow front is in view, turn away from it; otherwise
go forward.

    source devel/setup.bash
    roslaunch hideseek_world basic.launch start_hider:=false &      # the game, waiting for a hider
    /usr/bin/python3 examples/hider_node.py                          # this node plays it
    roslaunch hideseek_world evaluate.launch policy:=external        # or: evaluated on seeds 0-99

docs/launch_files.md, "A hider of your own", states the exchange.
"""
import numpy as np
import rospy
from hideseek_msgs.msg import ActionBatch, ObservationBatch

STAY, FORWARD, BACKWARD, TURN_LEFT, TURN_RIGHT = range(5)  # ActionBatch's constants


def seeker_columns(image):
    """The columns of an H x W x 3 uint8 image that show the seeker (its red back, its yellow front)."""
    r, g, b = (image[..., k].astype(np.int16) for k in range(3))
    seeker = ((r > 150) & (g < 90) & (b < 90)) | ((r > 200) & (g > 190) & (b < 70))
    return np.nonzero(seeker.any(axis=0))[0]


def act(image):
    columns = seeker_columns(image)
    if len(columns) == 0:
        return FORWARD
    # The seeker's image lies left of the middle: turn right, away from it; and the other way.
    return TURN_RIGHT if columns.mean() < image.shape[1] / 2 else TURN_LEFT


def main():
    rospy.init_node("my_hider")
    actions = rospy.Publisher("hider/actions", ActionBatch, queue_size=2, tcp_nodelay=True)

    def answer(batch):
        images = np.frombuffer(batch.images, np.uint8).reshape(batch.num_arenas, batch.height, batch.width, 3)
        reply = ActionBatch(actions=bytes(act(image) for image in images), step=list(batch.step))
        reply.header.stamp = batch.header.stamp
        actions.publish(reply)

    rospy.Subscriber("hider/observations", ObservationBatch, answer, queue_size=2, tcp_nodelay=True)
    rospy.spin()


if __name__ == "__main__":
    main()
