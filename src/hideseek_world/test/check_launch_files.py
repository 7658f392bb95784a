#!/usr/bin/env python3
"""Loads every launch file of a folder with roslaunch's own loader (arguments, includes,
substitutions) and checks that each node's package and executable exist, that every
node that writes to the screen flushes each log line (ROSCONSOLE_STDOUT_LINE_BUFFERED), every
argument a user can set carries a doc= (roslaunch --ros-args lists it, and must load the file to do so), and
that the `policy`
argument of a variant's launch file defaults to `shipped` (the policy policies/policies.yaml ships
for the variant, else the random hider). The training parameters (output_dir, ppo_config, ...)
reach the agent that trains and no other: an agent that plays a policy, at random or by script
shows none in rosparam. train.launch is loaded again with role:=seeker and with a seeker's checkpoint
as the opponent (both given steps and checkpoint_interval), evaluate.launch with
seeker_mode:=random and with external sides, and basic.launch and play.launch with record:=true, whose world must wait for
the recorder (one more listener of world/steps and world/episodes than without); policy:=external
and seeker_mode:=external start no node for that side; that a path
argument starting with ~/ reaches its node under $HOME; and that game_config:= and variant_config:=
reach every node that reads the game.
Writes an xunit result. hideseek_world's package.xml declares the packages its launch files start
(catkin_lint checks that); this checks that each named executable exists.

usage: check_launch_files.py LAUNCH_DIR XUNIT_OUTPUT
"""
import glob
import os
import sys
import xml.etree.ElementTree as ET
from xml.sax.saxutils import escape

import roslaunch.arg_dump
import roslaunch.config
import roslaunch.xmlloader
import rospkg
from roslib.packages import find_node


def undocumented_arguments(path):
    """Arguments with a default (settable from the command line) but no doc=."""
    return [a.get("name") for a in ET.parse(path).getroot().iter("arg")
            if a.get("value") is None and a.get("doc") is None]


def variant_problems(path, config, argv=None):
    """A variant's launch file (named for a config/variants file) plays that variant, and its hider
    plays the policy the run registry ships for it (`shipped`: else the random hider) by default."""
    package = rospkg.RosPack().get_path("hideseek_game")
    variant = os.path.basename(path)[:-len(".launch")]
    if not os.path.isfile(os.path.join(package, "config", "variants", variant + ".yaml")):
        return []
    problems = []
    # The nodes resolve ~variant (a name) through hideseek_game's resolver; a variant's launch file
    # names its variant and overrides no file.
    played = {k: v.value for k, v in config.params.items() if k.endswith("/variant")}
    if not played or any(v != variant for v in played.values()):
        problems.append("plays %s, not the variant %s" % (sorted(set(played.values())) or "no variant", variant))
    files = sorted(k for k in config.params if k.endswith("/variant_config") or k.endswith("/game_config"))
    if files:
        problems.append("overrides the resolver with files: %s" % ", ".join(files))
    policy = [v.value for k, v in config.params.items() if k.endswith("/hider/policy")]
    if policy != ["shipped"] and not any(a.startswith("policy:=") for a in argv or []):
        problems.append("the hider's policy defaults to %s, not 'shipped' (the registry's shipped policy, else "
                        "the random hider)" % policy)
    return problems


# What an agent's node reads in train mode only (hideseek_hider::loadLearnerParams).
TRAINING_PARAMS = ("output_dir", "ppo_config", "num_arenas", "seed", "total_steps", "checkpoint_interval",
                   "world_size", "rank", "rendezvous", "rendezvous_timeout", "rendezvous_interface")
# Other launch files loaded a second time, with these arguments.
TRAINING_ARGS = ["steps:=128", "checkpoint_interval:=60"]
EXTRA_LOADS = {"train.launch": [["role:=seeker"] + TRAINING_ARGS, ["opponent:=/tmp/seeker.pt"] + TRAINING_ARGS],
               "evaluate.launch": [["seeker_mode:=random"], ["policy:=external", "seeker_mode:=external"],
                                   ["seeker_mode:=external", "seeker_decides:=step"]],
               "basic.launch": [["record:=true"], ["policy:=external"], ["seeker_mode:=external"]],
               "play.launch": [["record:=true"]]}


# Loads whose path argument starts with ~/: the parameter a node reads is under $HOME, as a shell
# would have written it (the shell does not expand ~ after :=).
HOME_LOADS = {"train.launch": ("output_dir:=~/hs_check/run", "/hider/output_dir"),
              "evaluate.launch": ("output_dir:=~/hs_check/eval", "/evaluator/output_dir"),
              "basic.launch": ("policy:=~/hs_check/policy.pt", "/hider/policy")}


def home_problems(path):
    """A leading ~/ in a path argument is the home folder."""
    name = os.path.basename(path)
    if name not in HOME_LOADS:
        return []
    argument, param = HOME_LOADS[name]
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(path, config, argv=[argument], verbose=False)
    got = config.params[param].value if param in config.params else None
    want = os.path.expanduser(argument.split(":=", 1)[1])
    return [] if got == want else ["%s gives %s = %s, not %s" % (argument, param, got, want)]


# Loads given files of one's own: each reaches every node that resolves the game (each node with a
# ~variant), under $HOME where given with ~/, and no node of the game is left to the config's.
OWN_FILES = ["game_config:=~/hs_check/game.yaml", "variant_config:=~/hs_check/variant.yaml"]
OWN_FILE_LOADS = ("basic.launch", "evaluate.launch", "train.launch", "analyze.launch", "play.launch")


def own_file_problems(path):
    """game_config:= and variant_config:= reach every node that reads the game."""
    if os.path.basename(path) not in OWN_FILE_LOADS:
        return []
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(path, config, argv=OWN_FILES, verbose=False)
    nodes = sorted(k[:-len("/variant")] for k in config.params if k.endswith("/variant"))
    problems = [] if len(nodes) >= 3 else ["only %s read the variant" % nodes]
    for node in nodes:
        for argument in OWN_FILES:
            key, value = argument.split(":=", 1)
            got = config.params[node + "/" + key].value if node + "/" + key in config.params else None
            if got != os.path.expanduser(value):
                problems.append("%s gives %s/%s = %s" % (argument, node, key, got))
    return problems


def listeners(path, argv):
    """The world's step_listeners and episode_listeners when `path` is loaded with `argv`."""
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(path, config, argv=argv, verbose=False)
    return {name.rsplit("/", 1)[-1]: int(p.value) for name, p in config.params.items()
            if name.endswith("/world/step_listeners") or name.endswith("/world/episode_listeners")}


def recording_problems(path, config, argv):
    """With record:=true the world also waits for the recorder on world/steps and world/episodes, one
    more listener of each than without, so that the bag starts at the game's first decision."""
    if "record:=true" not in (argv or []):
        return []
    if not any(n.package == "rosbag" and n.type == "record" for n in config.nodes):
        return ["record:=true starts no recorder"]
    recording = listeners(path, argv)
    plain = listeners(path, [a for a in argv if a != "record:=true"])
    return ["record:=true sets %s to %s, not one more than without it (%s)" % (k, recording.get(k), v)
            for k, v in sorted(plain.items()) if recording.get(k) != v + 1] or \
        ([] if plain else ["no world/step_listeners or world/episode_listeners parameters"])


def external_problems(config, argv):
    """policy:=external starts no hider node, seeker_mode:=external no seeker node: a node of one's
    own plays that side. The world asks an external seeker when the scripted seeker would be asked
    (seeker_decides game: learned_seeker false, no seeker images) or once a step, with its camera
    (seeker_decides step), and an evaluator names it."""
    argv = argv or []
    problems = []
    started = {n.name for n in config.nodes}
    for side, argument in (("hider", "policy:=external"), ("seeker", "seeker_mode:=external")):
        if argument in argv and side in started:
            problems.append("%s starts a %s node" % (argument, side))
    if "seeker_mode:=external" in argv:
        step = "seeker_decides:=step" in argv
        world = {k.rsplit("/", 1)[-1]: v.value for k, v in config.params.items()
                 if k.rsplit("/", 2)[-2:-1] == ["world"]}
        for key in ("learned_seeker", "seeker_images"):
            if world.get(key) != step:
                problems.append("seeker_mode:=external %s sets the world's %s to %s, not %s"
                                % (" ".join(a for a in argv if a.startswith("seeker_decides")) or "(decides: game)",
                                   key, world.get(key), step))
        label = [v.value for k, v in config.params.items() if k.endswith("/evaluator/seeker")]
        if label and (not str(label[0]).startswith("external") or "," in str(label[0])):
            problems.append("the evaluator names the external seeker '%s' (a name without a comma, which "
                            "would split evaluation.csv's columns, starting with external)" % label[0])
    return problems


def training_problems(config):
    """An agent node (hider, seeker) gets the training parameters if and only if its mode is train."""
    problems = []
    for key, mode in sorted(config.params.items()):
        agent = key[:-len("/mode")]
        if not key.endswith("/mode") or agent.rsplit("/", 1)[-1] not in ("hider", "seeker"):
            continue
        given = [p for p in TRAINING_PARAMS if agent + "/" + p in config.params]
        if mode.value == "train" and "output_dir" not in given:
            problems.append("%s trains, but has no %s/output_dir" % (agent, agent))
        elif mode.value != "train" and given:
            problems.append("%s is in %s mode, but gets the training parameters %s" % (agent, mode.value, ", ".join(given)))
    return problems


def ros_args_problems(path):
    """`roslaunch --ros-args` lists the file's arguments (docs/launch_files.md points users to it), and an
    argument it lists as required (no default, or an empty one) is one a user can set: documented."""
    try:
        listed = roslaunch.arg_dump.get_args([path])
    except Exception as e:  # roslaunch raises several unrelated exception types
        return ["roslaunch --ros-args fails: %s" % str(e).strip().splitlines()[0]]
    return ["roslaunch --ros-args lists '%s', a computed argument, as required" % name
            for name, (doc, default) in sorted(listed.items()) if not doc and not default]


def check(path, argv=None):
    problems = ["argument '%s' has no doc=" % name for name in undocumented_arguments(path)]
    if argv is None:
        problems += ros_args_problems(path)
    if path.endswith(".launch.xml"):
        return problems  # an include: its required arguments come from the files that load it
    config = roslaunch.config.ROSLaunchConfig()
    loader = roslaunch.xmlloader.XmlLoader()
    try:
        loader.load(path, config, argv=argv or [], verbose=False)
    except Exception as e:  # roslaunch raises several unrelated exception types
        return ["does not load: %s" % e]
    problems += variant_problems(path, config, argv)
    problems += training_problems(config)
    problems += recording_problems(path, config, argv)
    problems += external_problems(config, argv)
    if argv is None:
        problems += home_problems(path)
        problems += own_file_problems(path)
    for node in config.nodes + config.tests:
        if node.output == "screen" and ("ROSCONSOLE_STDOUT_LINE_BUFFERED", "1") not in node.env_args:
            problems.append("node %s writes to the screen without ROSCONSOLE_STDOUT_LINE_BUFFERED=1: redirected "
                            "to a file, its lines come in blocks, and a killed node's last ones never" % node.name)
        try:
            if not find_node(node.package, node.type):
                problems.append("node %s: no executable '%s' in package '%s'" % (node.name, node.type, node.package))
        except rospkg.ResourceNotFound:
            problems.append("node %s: package '%s' not found" % (node.name, node.package))
    return problems


def main():
    launch_dir, output = sys.argv[1], sys.argv[2]
    files = sorted(glob.glob(os.path.join(launch_dir, "*.launch")) + glob.glob(os.path.join(launch_dir, "*.launch.xml")))
    cases = []
    failures = 0
    loads = [(path, None) for path in files]
    loads += [(path, argv) for path in files for argv in EXTRA_LOADS.get(os.path.basename(path), [])]
    for path, argv in loads:
        problems = check(path, argv)
        name = os.path.basename(path) + ("" if argv is None else " " + " ".join(argv))
        if problems:
            failures += 1
            print("%s:\n  %s" % (name, "\n  ".join(problems)))
            cases.append('<testcase classname="launch" name="%s"><failure message="%s"/></testcase>'
                         % (escape(name), escape("; ".join(problems), {'"': "&quot;"})))
        else:
            print("%s: ok" % name)
            cases.append('<testcase classname="launch" name="%s"/>' % escape(name))
    if not files:
        failures += 1
        cases.append('<testcase classname="launch" name="none"><failure message="no launch files in %s"/></testcase>'
                     % escape(launch_dir))
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    with open(output, "w") as f:
        f.write('<?xml version="1.0"?>\n<testsuite name="launch_files" tests="%d" failures="%d" errors="0">%s</testsuite>\n'
                % (len(cases), failures, "".join(cases)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
