"""A catkin workspace the pipeline runs ROS tools from: the checkout's own, or a sweep phase's
worktree at its pinned commit. Every command runs with the workspace's environment
(scripts/env.sh: Debian's python3 first, the devel space sourced), from its root."""
import os
import signal
import subprocess

from hideseek_pipeline import processes as proc

ANALYSIS_SCRIPTS = os.path.join("src", "hideseek_analysis", "scripts")


class ToolError(Exception):
    """A step of the pipeline failed; the message names it and where its log is."""


class Interrupted(ToolError):
    """A Ctrl-C (or sweep stop's SIGINT) stopped a step, which resumes where it stopped; the
    command exits 130, as a shell reports a command that SIGINT ended."""


class Workspace:
    def __init__(self, root):
        self.root = os.path.realpath(root)
        self.interrupted = False  # a SIGINT reached a command run through_interrupt
        if not os.path.isfile(os.path.join(self.root, "scripts", "env.sh")):
            raise ToolError("%s is not a hideseek checkout (no scripts/env.sh)" % self.root)

    def command(self, args, env=None, log=None, check=True, show_stderr=False, through_interrupt=False):
        """Runs `args` in the workspace's environment; stdout to `log` (a path) when given, else
        captured and returned; stderr with it, or (`show_stderr`) to this process's stderr. Raises
        ToolError naming the command when `check` and it fails. `through_interrupt`: a Ctrl-C at the
        terminal, which reaches the command too, is left to it (roslaunch stops its nodes, and a
        training writes its checkpoint), and this process waits for it to end instead of killing it."""
        _refuse_a_taken_port(args)
        wrapped = ["bash", "-c", 'source scripts/env.sh && exec "$@"', "hideseek"] + [str(a) for a in args]
        full_env = dict(os.environ, **(env or {}))
        if log:
            # A handler, not SIG_IGN, which the command would inherit.
            previous = signal.signal(signal.SIGINT, self._note_interrupt) if through_interrupt else None
            try:
                with open(log, "w") as f:
                    r = subprocess.run(wrapped, cwd=self.root, env=full_env, stdout=f, stderr=subprocess.STDOUT)
            finally:
                if through_interrupt:
                    signal.signal(signal.SIGINT, previous)
            out = ""
        else:
            r = subprocess.run(wrapped, cwd=self.root, env=full_env, stdout=subprocess.PIPE, text=True,
                               stderr=None if show_stderr else subprocess.PIPE)
            out = r.stdout
        if check and r.returncode != 0:
            where = ("see %s" % log) if log else ("its message above" if show_stderr else
                                                   (r.stderr.strip().splitlines() or ["no message"])[-1])
            raise ToolError("%s exited %d (%s)" % (os.path.basename(str(args[0])), r.returncode, where))
        return out

    def _note_interrupt(self, *_):
        self.interrupted = True

    def tool(self, package, name):
        """A program of the workspace's devel space; a workspace not built (a fresh clone beside a
        sweep's folder) stops here by name rather than as a shell's exit 127."""
        path = os.path.join(self.root, "devel", "lib", package, name)
        if not os.access(path, os.X_OK):
            raise ToolError("%s/%s is not built in %s (no %s): build the workspace first (make build)"
                            % (package, name, self.root, path))
        return path

    def resolve(self, variant, key, game=None, variant_config=None):
        """The resolver's answer for a variant (hideseek_game's resolve: game, map_file, ...), or for
        a variant file of one's own, `variant_config`, whose variant field must be `variant`."""
        args = [self.tool("hideseek_game", "resolve")] + (["--game", game] if game else []) + \
            (["--variant-config", variant_config] if variant_config else []) + [variant, key]
        return self.command(args).strip()

    def analysis_script(self, name):
        """One of hideseek_analysis' scripts; probe_set.sh in a tree pinned before it moved there
        from scripts/ (session 38) is that tree's scripts/probe_set.sh."""
        path = os.path.join(self.root, ANALYSIS_SCRIPTS, name)
        old = os.path.join(self.root, "scripts", name)
        return old if name == "probe_set.sh" and not os.path.exists(path) and os.path.exists(old) else path

    def python(self, script, *args, log=None, show_stderr=False):
        return self.command(["/usr/bin/python3", self.analysis_script(script)] + list(args), log=log,
                            show_stderr=show_stderr)


def _refuse_a_taken_port(args):
    """roslaunch -p PORT joins the master already listening at PORT, if one does: two graphs would
    meet, and each would take the other's topics. Refused before anything starts."""
    args = [str(a) for a in args]
    if not args or os.path.basename(args[0]) != "roslaunch" or "-p" not in args[:-1]:
        return
    port = args[args.index("-p") + 1]
    if port.isdigit() and not proc.port_free(int(port)):
        launch = next((a for a in args if a.endswith(".launch")), "roslaunch")
        raise ToolError("port %s is taken (a ROS master or another program listens there): %s would join "
                        "its graph; nothing was started. Stop what listens there, or choose a free port (--port; "
                        "a training's evaluation: --eval-port)" % (port, launch))
