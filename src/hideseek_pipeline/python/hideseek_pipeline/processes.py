"""Process trees, signals, locks and ports: what the queue needs of the operating system."""
import fcntl
import os
import signal
import socket
import subprocess


def children(pid):
    out = subprocess.run(["ps", "-o", "pid=", "--ppid", str(pid)], capture_output=True, text=True).stdout
    return [int(x) for x in out.split()]


def tree(pid):
    """The process tree under `pid`, itself first. roslaunch starts each node in its own session, so
    the tree, not the process group, is what holds a run."""
    pids = [pid]
    for child in children(pid):
        pids.extend(tree(child))
    return pids


def alive(pid):
    if not pid:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def signal_tree(pid, sig):
    for p in tree(pid):
        try:
            os.kill(p, sig)
        except ProcessLookupError:
            pass


def stop_tree(pid):
    signal_tree(pid, signal.SIGSTOP)


def continue_tree(pid):
    signal_tree(pid, signal.SIGCONT)


def read_pid(path):
    try:
        with open(path) as f:
            return int(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def lock_held(path):
    """True while another process holds an flock on `path` (a running queue holds its lock)."""
    if not os.path.exists(path):
        return False
    with open(path, "a") as f:
        try:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            return True
        fcntl.flock(f, fcntl.LOCK_UN)
    return False


class FileLock:
    """An exclusive flock on a file, held while the `with` block runs (blocking unless `wait` is
    False, when entering raises BlockingIOError if another process holds it)."""

    def __init__(self, path, wait=True):
        self.path, self.wait, self.file = path, wait, None

    def __enter__(self):
        self.file = open(self.path, "a")
        try:
            fcntl.flock(self.file, fcntl.LOCK_EX | (0 if self.wait else fcntl.LOCK_NB))
        except BlockingIOError:
            self.file.close()
            raise
        return self

    def __exit__(self, *exc):
        fcntl.flock(self.file, fcntl.LOCK_UN)
        self.file.close()


def port_free(port):
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        return s.connect_ex(("127.0.0.1", port)) != 0


def native_bf16(cpuinfo="/proc/cpuinfo"):
    with open(cpuinfo) as f:
        flags = f.read().split()
    return "avx512_bf16" in flags or "amx_bf16" in flags
