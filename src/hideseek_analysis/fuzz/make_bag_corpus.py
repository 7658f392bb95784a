#!/usr/bin/env python3
"""Writes bag_fuzz's seed corpus (issue #49): small analysis bags as rosbag writes them, and copies
cut or altered the ways a copy, a killed recorder or a hostile file would. Each file is named for
what it holds; the corpus is committed, and this script says how each file was made.

usage: make_bag_corpus.py OUTPUT_DIR   (with the workspace's devel/setup.bash sourced)
"""
import io
import os
import struct
import sys

import rosbag
import rospy
from geometry_msgs.msg import Pose2D
from hideseek_msgs.msg import StepBatch
from std_msgs.msg import String


def batch(decision, arenas=2, image=0):
    m = StepBatch(decision=decision, num_arenas=arenas)
    m.episode = [0] * arenas
    m.seed = [7 + a for a in range(arenas)]
    m.step = [decision] * arenas
    m.hider_pose = [Pose2D(0.1 * decision, 0.2, 0.3) for _ in range(arenas)]
    m.seeker_pose = [Pose2D(1.0, 1.0, 0.0) for _ in range(arenas)]
    m.distance = [2.5] * arenas
    m.hider_sees_seeker = [decision % 2] * arenas
    m.seeker_sees_hider = [0] * arenas
    m.obstacle_in_view = [1] * arenas
    m.hider_action = [1] * arenas
    m.seeker_action = [2] * arenas
    m.reward = [0.001] * arenas
    m.outcome = [0] * arenas
    if image and decision % 2 == 0:
        m.image_every, m.height, m.width = 2, image, image
        m.images = bytes((7 * i) % 256 for i in range(arenas * image * image * 3))
    m.header.stamp = rospy.Time(1 + decision, 0)
    return m


def write(path, decisions, compression="lz4", threshold=1024, image=0, other_topic=False, raw=None):
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=threshold) as bag:
        for d in decisions:
            m = batch(d, image=image)
            bag.write("/world/steps", m, m.header.stamp)
            if other_topic and d % 5 == 0:
                bag.write("/rosout_note", String(data="decision %d" % d), m.header.stamp)
        if raw is not None:
            bag.write("/world/steps", (StepBatch._type, raw, StepBatch._md5sum, StepBatch), rospy.Time(99), raw=True)


def records(data):
    """(position, header fields, data position, data length) of each top-level record."""
    pos, out = 13, []
    while pos < len(data):
        (hlen,) = struct.unpack_from("<I", data, pos)
        fields, i = {}, pos + 4
        while i < pos + 4 + hlen:
            (flen,) = struct.unpack_from("<I", data, i)
            name, _, value = data[i + 4:i + 4 + flen].partition(b"=")
            fields[name.decode()] = (i + 4 + len(name) + 1, value)
            i += 4 + flen
        (dlen,) = struct.unpack_from("<I", data, pos + 4 + hlen)
        out.append((pos, fields, pos + 8 + hlen, dlen))
        pos += 8 + hlen + dlen
    return out


def op(fields):
    return fields["op"][1][0]


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    p = lambda name: os.path.join(out, name)
    write(p("steps_lz4"), range(24))
    write(p("steps_none"), range(12), compression="none")
    write(p("steps_bz2"), range(12), compression="bz2")
    write(p("steps_images"), range(8), image=2)
    write(p("steps_two_topics"), range(12), other_topic=True)
    write(p("steps_gap"), [0, 1, 2, 4, 5])
    # A StepBatch whose episode array claims 4,294,967,280 entries (roscpp would allocate them).
    good = io.BytesIO()
    batch(12).serialize(good)
    b = good.getvalue()
    at = 12 + 4 + struct.unpack_from("<I", b, 12)[0] + 8 + 4  # after header, decision, num_arenas
    write(p("hostile_array_length"), range(12), compression="none", raw=b[:at] + struct.pack("<I", 0xFFFFFFF0) + b[at + 4:])

    full = open(p("steps_lz4"), "rb").read()
    recs = records(full)
    chunks = [r for r in recs if op(r[1]) == 5]
    # Cut inside the second chunk, as a copy that did not finish.
    open(p("cut_mid_chunk"), "wb").write(full[: chunks[1][2] + chunks[1][3] // 2])
    # A recording killed before it was closed: no index (index_pos 0), the file ends after a chunk.
    head = recs[0]
    unindexed = bytearray(full[: chunks[1][0]])
    unindexed[head[1]["index_pos"][0]: head[1]["index_pos"][0] + 8] = struct.pack("<Q", 0)
    open(p("unindexed"), "wb").write(bytes(unindexed))
    # A chunk that declares 4 GiB uncompressed.
    huge = bytearray(full)
    huge[chunks[0][1]["size"][0]: chunks[0][1]["size"][0] + 4] = struct.pack("<I", 0xFFFFFFF0)
    open(p("huge_chunk_size"), "wb").write(bytes(huge))
    # An index entry pointing one byte into a message record, in a stored bag.
    stored = open(p("steps_none"), "rb").read()
    index = [r for r in records(stored) if op(r[1]) == 4 and r[3] >= 24][0]
    shifted = bytearray(stored)
    entry = index[2] + 12 + 8  # the second entry's offset
    shifted[entry: entry + 4] = struct.pack("<I", struct.unpack_from("<I", stored, entry)[0] + 1)
    open(p("index_offset_mid_record"), "wb").write(bytes(shifted))
    # A record header claiming 2 GiB, just after the bag header.
    long_header = bytearray(full)
    long_header[chunks[0][0]: chunks[0][0] + 4] = struct.pack("<I", 0x7FFFFFFF)
    open(p("record_header_2gib"), "wb").write(bytes(long_header))


if __name__ == "__main__":
    main()
